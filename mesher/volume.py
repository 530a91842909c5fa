r"""Exact volume of the meshed tooth region, from the tooth surfaces alone (reference for the mesher).

The region of one tooth (Step 1) at level z is bounded by: side −1 from the space centre
(root, fillet, flank), the tip circle, side +1 back down to its space centre, the radial line to
the rim circle :math:`r_i`, the rim arc and the radial line back. By Green's theorem its area is

.. math:: A(z) = \tfrac12 \Big|\oint (x\,dy - y\,dx)\Big|
          = \tfrac12 \Big|\sum_{\text{pieces}} \int (x\,y_u - y\,x_u)\,du
            + r_a^2 (\theta_{a+} - \theta_{a-}) - r_i^2\,\tfrac{2\pi}{N}\Big| ,

radial lines contributing nothing (a fillet that folds back is trimmed where it crosses the flank,
:mod:`mesher.region`). Each surface piece is integrated over its own parameter with
composite Gauss–Legendre quadrature (the integrands are smooth on every piece), the flank up to
the tip parameter found here by bisection on :math:`|r_{xy}| = r_a`, and the volume is
:math:`V = \int_{-B/2}^{B/2} A(z)\,dz` by Gauss–Legendre in z. Nothing of the mesher's node
placement is used.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from tca.geometry.gear import Gear

from mesher.region import fillet_start

__all__ = ["section_area", "tooth_region_volume"]


def _gl(a: float, b: float, panels: int = 6, order: int = 16):
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(a, b, panels + 1)
    h = np.diff(edges)[:, None] / 2
    mid = (edges[:-1] + edges[1:])[:, None] / 2
    return (mid + h * x).ravel(), (h * w).ravel()


def _piece(surface, a: float, b: float, z: float) -> float:
    """Integral of (x y_u - y x_u) du over u from a to b at level z."""
    u, w = _gl(a, b)
    sp = surface.evaluate(u, np.full_like(u, z))
    f = sp.r[:, 0] * sp.r_u[:, 1] - sp.r[:, 1] * sp.r_u[:, 0]
    return float(np.dot(f, w))


def _tip(gear: Gear, side: int, z: float) -> float:
    s = gear.surface(side, "flank")
    ar = gear.area(side)

    def f(u):
        p = s.points(u, z)
        return gear.kappa * (math.hypot(p[0], p[1]) - gear.r_tip)

    lo, hi = ar.u_form, s.u_range[1]
    return brentq(f, lo, hi, xtol=1e-14, rtol=1e-15, maxiter=200)


def section_area(gear: Gear, rim_radius: float, z: float) -> float:
    """Area of the transverse section of one tooth region at level z [mm^2] (see module docstring)."""
    total = 0.0
    ang = {}
    for side in (1, -1):
        root, fil, fl = (gear.surface(side, p) for p in ("root", "fillet", "flank"))
        ut = _tip(gear, side, z)
        u0, w0, _ = fillet_start(gear, side)  # a folded fillet is trimmed where it crosses the flank
        I = (_piece(root, *root.u_range, z) + _piece(fil, fil.u_range[0], w0, z) + _piece(fl, u0, ut, z))
        total += -side * I  # side -1 runs from its space centre to the tip, side +1 back down
        p = fl.points(ut, z)
        ang[side] = math.atan2(p[1], p[0])
    dth = (ang[1] - ang[-1] + math.pi) % (2 * math.pi) - math.pi
    total += gear.r_tip**2 * dth - rim_radius**2 * gear.pitch_angle
    return 0.5 * abs(total)


def tooth_region_volume(gear: Gear, rim_radius: float, order: int = 24) -> float:
    """Volume of one tooth with its rim sector down to `rim_radius` over the face width [mm^3]."""
    h = 0.5 * gear.face_width
    x, w = np.polynomial.legendre.leggauss(order)
    return float(sum(wi * h * section_area(gear, rim_radius, h * xi) for xi, wi in zip(x, w)))
