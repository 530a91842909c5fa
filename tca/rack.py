r"""Generating rack-cutter in normal section: straight or parabolic flank, rounded tip, tip line.

Coordinates of the normal section (Fig. 1.3(a)): ``h`` points toward the tip of the generated
tooth, ``eta`` across the tooth toward its +y flank; the generated tooth occupies
``|eta| < eta_flank(h)`` and is centred on ``eta = 0``. Profile shift ``x`` moves the rack by
``x m`` toward the tooth tip, thickening the tooth at the pitch circle (external and internal).

Flank (side +1), parameter ``u`` [mm] along the straight profile from the point ``Q0`` on the
generating pitch line, with the parabolic modification of Eq. (1.5)
:math:`\Delta = a_c (u - u_0)^2` applied along the flank normal, into the tooth:

.. math::
    P(u) = Q_0 + u\,(\cos\alpha_n, -\sin\alpha_n) - a_c (u-u_0)^2 (\sin\alpha_n, \cos\alpha_n),
    \qquad Q_0 = (0,\; \pi m/4 + x m \tan\alpha_n).

The tip of the rack (addendum ``h_a0 m`` below the reference line) is rounded by an arc of
radius ``rho_f m`` tangent to the flank and to the tip line; the arc generates the fillet and
the tip line the root circle of the gear. The transverse section of the skew rack stretches
``eta`` by ``1 / cos(beta_ref)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import GeometryError, InputError

__all__ = ["RackCutter", "RackSegment", "rack_segments"]


@dataclass(frozen=True)
class RackCutter:
    """Generating rack-cutter of a gear flank pair, in normal section."""

    module: float  # normal module m_n [mm]
    pressure_angle: float  # normal pressure angle alpha_n [rad]
    addendum: float = 1.25  # tool addendum h_a0 / m
    tip_radius: float = 0.25  # tool tip rounding rho_f / m
    parabola_pos: float = 0.0  # a_c of the flank generating the +y tooth flank [1/mm]
    parabola_neg: float = 0.0  # a_c of the flank generating the -y tooth flank [1/mm]
    parabola_apex: float = 0.0  # u_0, parabola apex measured from the pitch point [mm]

    def __post_init__(self):
        if not (self.module > 0):
            raise InputError("module_mm", self.module, "> 0")
        if not (0 < self.pressure_angle < math.radians(45)):
            raise InputError("pressure_angle_deg", math.degrees(self.pressure_angle), "in (0, 45)")
        if not (0 < self.addendum <= 3):
            raise InputError("tool_addendum", self.addendum, "in (0, 3] modules")
        if not (0 < self.tip_radius < 1):
            raise InputError("tool_tip_radius", self.tip_radius, "in (0, 1) modules (a sharp tool tip has no fillet)")
        for name in ("parabola_pos", "parabola_neg"):
            v = getattr(self, name)
            if not (0 <= v < 0.5):
                raise InputError(name + "_per_mm", v, "in [0, 0.5) 1/mm (parabola coefficient, Eq. 1.5)")

    def parabola(self, side: int) -> float:
        """Parabola coefficient a_c of the rack flank generating tooth flank `side` [1/mm]."""
        return self.parabola_pos if side > 0 else self.parabola_neg


@dataclass(frozen=True)
class RackSegment:
    """One piece of the rack profile for tooth side +1: point and 3 derivatives in (h, eta_n)."""

    kind: str  # "root" (tip line), "fillet" (tip arc) or "flank"
    t0: float  # parameter range, increasing toward the tooth tip
    t1: float
    coef: tuple  # piece-specific constants

    def eval(self, t):
        """(P, P', P'', P''') in normal-section coordinates (h, eta), each (..., 2)."""
        t = np.asarray(t, dtype=float)
        z = np.zeros_like(t)
        if self.kind == "flank":
            ca, sa, eta0, a, u0 = self.coef
            du = t - u0
            P = np.stack([t * ca - a * du**2 * sa, eta0 - t * sa - a * du**2 * ca], -1)
            P1 = np.stack([ca - 2 * a * du * sa, -sa - 2 * a * du * ca], -1)
            P2 = np.stack([z - 2 * a * sa, z - 2 * a * ca], -1)
            P3 = np.zeros_like(P)
        elif self.kind == "fillet":
            ch, ceta, rho = self.coef
            c, s = np.cos(t), np.sin(t)
            P = np.stack([ch - rho * c, ceta - rho * s], -1)
            P1 = np.stack([rho * s, -rho * c], -1)
            P2 = np.stack([rho * c, rho * s], -1)
            P3 = np.stack([-rho * s, rho * c], -1)
        elif self.kind == "root":
            (htip,) = self.coef
            P = np.stack([z + htip, -t], -1)
            P1 = np.stack([z, z - 1.0], -1)
            P2 = np.zeros_like(P)
            P3 = np.zeros_like(P)
        else:  # pragma: no cover - constructed internally only
            raise ValueError(self.kind)
        return P, P1, P2, P3


def rack_segments(rack: RackCutter, side: int, profile_shift: float, flank_tip_h: float) -> dict[str, RackSegment]:
    """Root, fillet and flank pieces of the rack generating tooth flank `side` (+1 / -1).

    All pieces are returned for side +1 geometry; the -y flank is its mirror image and differs
    only through its own parabola coefficient. ``flank_tip_h`` [mm] is the height ``h`` up to
    which the flank parameter range is extended (beyond the gear's tip).
    """
    m, al = rack.module, rack.pressure_angle
    ca, sa = math.cos(al), math.sin(al)
    a, u0 = rack.parabola(side), rack.parabola_apex
    eta0 = math.pi * m / 4 + profile_shift * m * math.tan(al)
    flank = RackSegment("flank", 0.0, 0.0, (ca, sa, eta0, a, u0))
    h_tip = (profile_shift - rack.addendum) * m
    rho = rack.tip_radius * m

    def junction_residual(u):
        P, P1, _, _ = flank.eval(np.array([u]))
        T = P1[0] / np.linalg.norm(P1[0])
        n_out = np.array([-T[1], T[0]])
        return P[0, 0] + rho * n_out[0] - (h_tip + rho), P[0], n_out

    # Newton on the tangency of the tip arc with the (parabolic) flank, from the straight-flank value.
    u = (h_tip + rho * (1 - sa)) / ca
    for _ in range(50):
        f, _, _ = junction_residual(u)
        df = (junction_residual(u + 1e-7)[0] - junction_residual(u - 1e-7)[0]) / 2e-7
        step = f / df
        u -= step
        if abs(step) < 1e-14:
            break
    f, Pj, n_out = junction_residual(u)
    if abs(f) > 1e-9:
        raise GeometryError("rack-cutter", "tip rounding", f"no tangent tip arc (residual {abs(f):.2e} mm)")
    uj = u
    C = Pj + rho * n_out
    w_j = math.atan2(n_out[1], n_out[0])
    if C[1] > math.pi * m / 2 + 1e-12:
        raise GeometryError(
            "rack-cutter", "tip radius too large",
            f"tool_tip_radius {rack.tip_radius} m leaves no tip land (arc centre at eta {C[1]:.4f} mm > half pitch {math.pi * m / 2:.4f} mm)",
        )
    u_tip = (flank_tip_h) / ca + 0.0
    # extend the flank range beyond the tip height (parabola bends it; be generous)
    u_tip = max(u_tip, uj) + 0.5 * m
    return {
        "root": RackSegment("root", -math.pi * m / 2, -C[1], (h_tip,)),
        "fillet": RackSegment("fillet", 0.0, w_j, (C[0], C[1], rho)),
        "flank": RackSegment("flank", uj, u_tip, (ca, sa, eta0, a, u0)),
    }
