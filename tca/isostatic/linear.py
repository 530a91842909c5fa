r"""Geometric interpretation of section 3.4.2, in closed form and generalised to first order in the errors.

Section 3.4.2 (Fig. 3.9). An indexing error :math:`\Delta E_t` of planet 1 opens a backlash
:math:`s = 2\Delta E_t\cos\alpha` in its subtrain (the planet moves away from both the sun and the
ring flank, each by :math:`\Delta E_t\cos\alpha` along the lines of action). The floating sun closes it
by a small rotation about :math:`O_{23}`, the intersection of the lines of action of planets 2 and 3;
the three lines form an equilateral triangle circumscribing the base circle :math:`r_{b1}`, so
:math:`\overline{O_{23}H} = 3r_{b1}` and :math:`\overline{O_{23}O_1} = 2r_{b1}`:

.. math::
    \Delta\phi_1 = \frac{s}{3r_{b1}},\qquad \Delta\phi_c = m_{c1}\,\Delta\phi_1,\qquad
    \Delta E_1 = \Delta\phi_1\cdot 2r_{b1} = \frac{2s}{3}

(Table 3.1, :math:`\Delta E_t` = 20 μm: s = 37.6 μm, Δφ1 = 21.2 arcsec, Δφc = 6.38 arcsec,
ΔE1 = 25 μm).

The same kinematics, to first order in the errors for involute gears, for any error and any
isostatic choice of floating members: let :math:`\boldsymbol\nu_i = R(q_i)(\sin\alpha, \cos\alpha)` be the
outward normal of the sun's flank at its mesh with planet *i* and :math:`\boldsymbol\mu_i =
R(q_i)(\sin\alpha, -\cos\alpha)` that of the planet's flank at the ring (:math:`q_i = \phi_c +
\theta_i`). The backlash of subtrain *i*, summed over its two meshes (the planet's own rotation
moves one into the other), is

.. math::
    g_i = s_i - \mathbf e_1\cdot\boldsymbol\nu_i + \mathbf e_c\cdot(\boldsymbol\nu_i - \boldsymbol\mu_i)
          + \mathbf e_3\cdot\boldsymbol\mu_i + \frac{r_{b1}}{m_{c1}}\,\Delta\phi_c ,

with :math:`s_i` the opening produced by the errors: a displacement :math:`\mathbf d` of planet *i*
(pin errors, its run-out) gives :math:`\mathbf d\cdot(\boldsymbol\nu_i - \boldsymbol\mu_i)` (only its
tangential part counts, :math:`2\cos\alpha\,\mathbf d\cdot\mathbf t_i`), a displacement of the sun's
teeth (run-out, a fixed centre error) :math:`-\boldsymbol\varepsilon_1\cdot\boldsymbol\nu_i`, of the ring's
teeth :math:`\boldsymbol\varepsilon_3\cdot\boldsymbol\mu_i`. All planets touch: :math:`g_i = 0`, :math:`N_p`
linear equations for the floating centres and :math:`\Delta\phi_c` (square when the train is isostatic).
With equally spaced planets :math:`\sum_i\boldsymbol\nu_i = 0`, hence in case 2
:math:`\Delta\phi_c = -m_{c1}\sum_i s_i / (N_p r_{b1})` and :math:`\mathbf e_1 = \tfrac{2}{3}\sum_i
(s_i - \bar s)\,\boldsymbol\nu_i`, which is the construction above. Consequences: a carrier-centre error
gives no TE and a fixed sun offset :math:`2\cos\alpha\,|\Delta\mathbf E_c|`; a sun run-out is cancelled by an
equal and opposite sun displacement; a planet run-out :math:`\varepsilon_p` gives a harmonic TE of
amplitude :math:`m_{c1}\,2\cos\alpha\,\varepsilon_p/(3r_{b1})` with the period of the planet's turn
relative to the carrier; a radial pin error has no effect at all with involute gears (with
:math:`N_3 = N_1 + 2N_2` both meshes change their operating pressure angle alike, and the backlash
the sun mesh gains, :math:`(r_{b1} + r_{b2})(\mathrm{inv}\,\alpha_w - \mathrm{inv}\,\alpha)`, the ring mesh
loses).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.errors import InputError
from tca.isostatic.flanks import REFLECT, apply, rot2
from tca.isostatic.train import IsostaticTrain

__all__ = ["IndexingClosedForm", "indexing_closed_form", "LinearResponse", "linear_response"]


@dataclass(frozen=True)
class IndexingClosedForm:
    """Section 3.4.2: backlash s [mm], sun turn [rad], carrier lag increase [rad], sun displacement [mm]."""

    s: float
    dphi1: float
    dphic: float
    dE1: float


def indexing_closed_form(r_b1: float, pressure_angle: float, ratio: float, dEt: float) -> IndexingClosedForm:
    """s = 2 dEt cos(alpha), dphi1 = s / (3 r_b1), dphic = m_c1 dphi1, dE1 = 2 s / 3 (three planets, floating sun)."""
    if not (r_b1 > 0 and 0 < pressure_angle < math.pi / 2 and 0 < ratio < 1):
        raise InputError("indexing_closed_form", (r_b1, pressure_angle, ratio), "r_b1 > 0, 0 < alpha < 90 deg, 0 < m_c1 < 1")
    s = 2 * dEt * math.cos(pressure_angle)
    dphi1 = s / (3 * r_b1)
    return IndexingClosedForm(s, dphi1, ratio * dphi1, 2 * s / 3)


@dataclass(frozen=True, eq=False)
class LinearResponse:
    """First-order response to the errors at sun angles phi1."""

    phi1: np.ndarray
    te: np.ndarray  # Delta phi_c [rad]
    sun_center: np.ndarray  # (n, 2) [mm]
    carrier_center: np.ndarray  # (n, 2) [mm]
    ring_center: np.ndarray  # (n, 2) [mm]
    opening: np.ndarray  # (n, Np) s_i [mm]
    planet_backlash: np.ndarray  # (n, Np) loop backlash g_i (non-zero only for a rigid hyperstatic train) [mm]


def linear_response(train: IsostaticTrain, phi1) -> LinearResponse:
    """Carrier TE and member centres to first order in the errors (involute gears, module docstring)."""
    phi1 = np.asarray(phi1, float).reshape(-1)
    n, Np = len(phi1), train.n_planets
    d = train.dof
    free = train.constraints.free_centres
    if d.mobility > 0 or (d.mobility < 0 and free) or d.singular:
        raise InputError("planets.count", Np, f"{d.isostatic_planets} (the linear model needs an isostatic train or "
                         "fixed axes)")
    al = train.pressure_angle
    m_c1 = train.ratio
    K = train.sun.r_b / m_c1
    N1, N2 = train.sun.teeth, train.planet.teeth
    phc = m_c1 * phi1
    q = phc[:, None] + train.theta[None, :]  # (n, Np)
    Rq = rot2(q)
    nu = apply(Rq, np.array([math.sin(al), math.cos(al)]))
    mu = apply(Rq, np.array([math.sin(al), -math.cos(al)]))
    s = np.zeros((n, Np))
    # planet displacements: pin errors and run-out
    pins = np.array([[p.radial, p.tangential] for p in train.placements])
    dpl = apply(Rq, pins[None, :, :])
    a = (N1 / N2) * (phi1[:, None] - phc[:, None] - train.theta[None, :]) + math.pi / N2
    for i, p in enumerate(train.planets):
        eps = p.tooth_transform(np.array(0))[1][:2]
        dpl[:, i] += apply(Rq[:, i] @ REFLECT @ rot2(a[:, i]), eps)
    s += np.einsum("nij,nij->ni", dpl, nu - mu)
    # sun and ring teeth displaced by their run-out
    e1 = apply(rot2(phi1), train.sun.tooth_transform(np.array(0))[1][:2])
    s -= np.einsum("nj,nij->ni", e1, nu)
    e3 = REFLECT @ rot2(train.ring_phase) @ train.ring.tooth_transform(np.array(0))[1][:2]
    s += np.einsum("j,nij->ni", e3, mu)
    # fixed centres (installment errors)
    sens = {"sun": -nu, "carrier": nu - mu, "ring": mu}
    centres = {"sun": np.array(train.sun_center), "carrier": np.array(train.carrier_center),
               "ring": np.array(train.ring_center)}
    for b in ("sun", "carrier", "ring"):
        if b not in free:
            s += np.einsum("j,nij->ni", centres[b], sens[b])
    out = {b: np.broadcast_to(centres[b], (n, 2)).copy() for b in centres}
    if free:
        A = np.concatenate([sens[b] for b in free] + [np.full((n, Np, 1), K)], -1)  # (n, Np, 2 nf + 1)
        sol = np.linalg.solve(A, -s[..., None])[..., 0]
        for k, b in enumerate(free):
            out[b] = sol[:, 2 * k:2 * k + 2]
        te = sol[:, -1]
        gap = np.zeros((n, Np))
    else:
        te = (-s / K).max(-1)  # the first planet to touch holds the carrier
        gap = s + K * te[:, None]
    return LinearResponse(phi1, te, out["sun"], out["carrier"], out["ring"], s, gap)
