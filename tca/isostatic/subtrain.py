r"""Equations of a subtrain (Eq. 3.18) and backlash of neighbouring teeth (Eqs. 3.19–3.20), planar.

A *subtrain* is the sun, one planet and the ring. In the plane, each tangency of two profiles is
three scalar equations (the planar form of Eq. 3.18): coincident points and parallel tangents,

.. math::
    \mathbf P_a(u_a) - \mathbf P_b(u_b) = \mathbf 0,\qquad \mathbf t_a \times \mathbf t_b = 0 ,

so a subtrain is 6 equations (sun–planet and planet–ring) in the 6 unknowns
:math:`x = (u_1, u_{2s}, u_{2r}, u_3, \phi_2, \phi_c)` for given sun angle and member centres. (With
the two-parameter surfaces of :meth:`Gear.surface` Eq. 3.18 would be 10 equations in 10 unknowns;
the report's four-parameter planet (3.9–3.11) gives 14. For spur gears the axial parameter is
degenerate — line contact — and contact of the double-crowned planet stays in its middle section,
see :mod:`tca.isostatic.flanks`.) The Jacobian is analytic, also with respect to the member centres
:math:`(\mathbf E_1, \mathbf E_c, \mathbf E_3)`, which gives :math:`\partial\phi_c/\partial\mathbf E`
of the fictitious-unknowns method (Eqs. 3.21–3.22) by implicit differentiation.

Backlash of the neighbouring pair (Eqs. 3.19–3.20), with the poses adopted from the solution:
unknowns :math:`(u_a, u_b, s)`,

.. math::
    \mathbf P_b(u_b) - \mathbf P_a(u_a) = s\,\mathbf n_a(u_a),\qquad \mathbf t_a \times \mathbf t_b = 0,

:math:`\mathbf n_a` the outward unit normal of flank *a* (the sun for the sun–planet mesh, the planet
for the planet–ring mesh): the signed distance of the two profiles along their common normal,
negative when they interfere.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.isostatic.flanks import REFLECT, PlacedTeeth, PlanarFlank, TrainFlanks, apply, cross2, nearest_tooth, perp, rot2
from tca.isostatic.train import IsostaticTrain
from tca.numerics.newton import NewtonOptions, newton

__all__ = ["Members", "Poses", "poses", "subtrain_eval", "backlash_solve", "line_crossing",
           "body_angle_map", "mate_tooth", "corner_gap", "JT_CENTRES", "BODY_SUN", "BODY_CARRIER", "BODY_RING"]

BODY_SUN, BODY_CARRIER, BODY_RING = 0, 1, 2

# dF/dT of the subtrain residuals for the centres T = (E_1, E_c, E_3) (columns x, y of each)
JT_CENTRES = np.zeros((6, 6))
JT_CENTRES[0:2, 0:2], JT_CENTRES[0:2, 2:4] = np.eye(2), -np.eye(2)
JT_CENTRES[3:5, 2:4], JT_CENTRES[3:5, 4:6] = np.eye(2), -np.eye(2)


@dataclass(eq=False)
class Members:
    """Per-member data of a batch of subtrains (one member = one planet at one position)."""

    phi1: np.ndarray  # (M,) sun angle [rad]
    theta: np.ndarray  # (M,) nominal planet angle on the carrier [rad]
    pin: np.ndarray  # (M, 2) planet centre in the carrier frame [mm]
    runout_p: np.ndarray  # (M, 2) planet eccentricity in its gear frame [mm]
    teeth: np.ndarray  # (M, 4) tooth indices: sun, planet (sun side), planet (ring side), ring
    T: np.ndarray  # (M, 3, 2) centres of sun, carrier, ring [mm]

    def take(self, idx) -> "Members":
        return Members(self.phi1[idx], self.theta[idx], self.pin[idx], self.runout_p[idx], self.teeth[idx], self.T[idx])


@dataclass(eq=False)
class Poses:
    """Body maps x -> A x + c of sun, planet and ring (run-out included in c), and centres."""

    As: np.ndarray
    cs: np.ndarray
    Ap: np.ndarray
    cp: np.ndarray
    Op: np.ndarray  # planet axis [mm]
    Tc: np.ndarray  # carrier axis [mm]
    Ar: np.ndarray
    cr: np.ndarray
    q: np.ndarray  # carrier angle of the planet, phi_c + theta [rad]
    a: np.ndarray  # planet frame angle phi_2 + pi / N_2 [rad]


def poses(train: IsostaticTrain, fl: TrainFlanks, m: Members, phi2, phic) -> Poses:
    """Body maps for planet rotations phi2 and carrier angles phic (Eqs. 3.7, 3.12-3.13, 3.16)."""
    As = rot2(m.phi1)
    cs = m.T[:, BODY_SUN] + apply(As, fl.sun.runout)
    q = phic + m.theta
    Aq = rot2(q)
    Tc = m.T[:, BODY_CARRIER]
    Op = Tc + apply(Aq, m.pin)
    a = phi2 + math.pi / train.planet.teeth
    Ap = Aq @ REFLECT @ rot2(a)
    cp = Op + apply(Ap, m.runout_p)
    Ar = np.broadcast_to(REFLECT @ rot2(train.ring_phase), (len(q), 2, 2))
    cr = m.T[:, BODY_RING] + apply(Ar, fl.ring.runout)
    return Poses(As, cs, Ap, cp, Op, Tc, Ar, cr, q, a)


def subtrain_eval(train: IsostaticTrain, fl: TrainFlanks, m: Members, x: np.ndarray, full: bool = False):
    """Residuals F (M, 6) and Jacobian J (M, 6, 6) of Eq. (3.18) (planar); dF/dT is :data:`JT_CENTRES`.

    With ``full``, also returns the poses and the world contact data of both meshes.
    """
    us, ups, upr, ur, ph2, phc = x.T
    P = poses(train, fl, m, ph2, phc)
    ks, kps, kpr, kr = m.teeth.T
    Ps, ts, tsu, Ask, gs = fl.sun.place(P.As, P.cs, ks, us)
    Pps, tps, tpsu, Apsk, gps = fl.planet_s.place(P.Ap, P.cp, kps, ups)
    Ppr, tpr, tpru, Aprk, gpr = fl.planet_r.place(P.Ap, P.cp, kpr, upr)
    Pr, tr, tru, Ark, gr = fl.ring.place(P.Ar, P.cr, kr, ur)
    n = len(x)
    F = np.empty((n, 6))
    F[:, 0:2] = Ps - Pps
    F[:, 2] = cross2(ts, tps)
    F[:, 3:5] = Ppr - Pr
    F[:, 5] = cross2(tpr, tr)
    J = np.zeros((n, 6, 6))
    # planet points: d/dphi2 = -J (P - O_p) (the planet frame is reflected), d/dphic = J (P - E_c)
    J[:, 0:2, 0] = ts
    J[:, 0:2, 1] = -tps
    J[:, 0:2, 4] = perp(Pps - P.Op)
    J[:, 0:2, 5] = -perp(Pps - P.Tc)
    J[:, 2, 0] = cross2(tsu, tps)
    J[:, 2, 1] = cross2(ts, tpsu)
    J[:, 2, 4] = -cross2(ts, perp(tps))
    J[:, 2, 5] = cross2(ts, perp(tps))
    J[:, 3:5, 2] = tpr
    J[:, 3:5, 3] = -tr
    J[:, 3:5, 4] = -perp(Ppr - P.Op)
    J[:, 3:5, 5] = perp(Ppr - P.Tc)
    J[:, 5, 2] = cross2(tpru, tr)
    J[:, 5, 3] = cross2(tpr, tru)
    J[:, 5, 4] = -cross2(perp(tpr), tr)
    J[:, 5, 5] = cross2(perp(tpr), tr)
    if not full:
        return F, J
    mesh = {
        "point_s": Ps, "point_r": Ppr,
        "normal_s": apply(Ask, fl.sun.normal(*fl.sun.eval(us)[1:])[0]),
        "normal_r": apply(Aprk, fl.planet_r.normal(*fl.planet_r.eval(upr)[1:])[0]),
        "margin": np.stack([np.minimum(fl.sun.margin(gs), fl.planet_s.margin(gps)),
                            np.minimum(fl.planet_r.margin(gpr), fl.ring.margin(gr))], -1),
    }
    return F, J, P, mesh


def line_crossing(flank: PlanarFlank, A, c, k, P0, nu, u0=None, iters: int = 8):
    """u where tooth k of a placed flank crosses the line through P0 along nu (guesses for the solves)."""
    u = np.zeros(len(P0)) if u0 is None else np.array(u0, float)
    lo, hi = flank.u_range
    w = hi - lo
    for _ in range(iters):
        Pw, t, _, _, _ = flank.place(A, c, k, u)
        f = cross2(Pw - P0, nu)
        df = cross2(t, nu)
        u = np.clip(u - f / np.where(np.abs(df) > 1e-12, df, 1e-12), lo - w, hi + w)
    return u


def backlash_solve(a: PlacedTeeth, b: PlacedTeeth, ua0, ub0, tol: float):
    """Signed distance s along the common normal of the teeth a and b, from guesses ua0, ub0 (M,) (Eq. 3.19).

    Returns (u_a, u_b, s, converged, margin) with margin the smaller working-area margin of both points [mm].
    """
    fa, fb = a.flank, b.flank

    def fun(x, idx):
        ua, ub, s = x.T
        Pa, ta, tau, Aak, ga = a.take(idx).place(ua)
        Pb, tb, tbu, _, _ = b.take(idx).place(ub)
        _, g1, g2 = fa.eval(ua)
        nl, dnl = fa.normal(g1, g2)
        na, dna = apply(Aak, nl), apply(Aak, dnl)
        F = np.empty((len(x), 3))
        F[:, 0:2] = Pa + s[:, None] * na - Pb
        F[:, 2] = cross2(ta, tb)
        J = np.zeros((len(x), 3, 3))
        J[:, 0:2, 0] = ta + s[:, None] * dna
        J[:, 0:2, 1] = -tb
        J[:, 0:2, 2] = na
        J[:, 2, 0] = cross2(tau, tb)
        J[:, 2, 1] = cross2(ta, tbu)
        return F, J

    x0 = np.stack([ua0, ub0, np.zeros(len(ua0))], -1)
    r = newton(fun, x0, NewtonOptions(tol=tol, maxiter=30), raise_on_failure=False,
               what="backlash of neighbouring teeth")
    ua, ub, s = r.x.T
    ga = fa.eval(ua)[0]
    gb = fb.eval(ub)[0]
    margin = np.minimum(fa.margin(ga), fb.margin(gb))
    ok = r.converged & np.isfinite(r.x).all(-1)
    return ua, ub, s, ok, margin


def body_angle_map(train: IsostaticTrain, P: Poses, body: str):
    """(c0, sign): a body maps local polar angle t to world angle c0 + sign t about its centre."""
    if body == "sun":
        return np.arctan2(P.As[:, 1, 0], P.As[:, 0, 0]), 1
    if body == "planet":
        return P.q + math.pi - P.a, -1
    return np.full(len(P.q), math.pi - train.ring_phase), -1


def mate_tooth(train: IsostaticTrain, flank: PlanarFlank, P: Poses, body: str, centre, target_point):
    """Tooth of `body` whose flank's pitch point is nearest the world point `target_point`."""
    c0, sg = body_angle_map(train, P, body)
    d = target_point - centre
    return nearest_tooth(c0, sg, flank.pitch_angle, flank.teeth, np.arctan2(d[:, 1], d[:, 0]))


def corner_gap(teeth: PlacedTeeth, uc, mate: PlacedTeeth, samples: int = 9, iters: int = 12):
    """Signed distance of the points u = uc (M,) of `teeth` from the working area of the `mate` teeth.

    Negative: the point is inside the mate's tooth. The foot of the normal is searched in the mate's working area
    (nearest of `samples` points, then Newton on (P_c - P_m) . t_m = 0, kept inside the area); where the point has
    no foot inside that area the gap is +inf (the mate's own end points are checked the other way round).
    Returns (gap [mm], u of the foot on the mate).
    """
    k = len(uc)
    fm = mate.flank
    Pc = teeth.place(uc)[0]
    us = np.linspace(fm.u_form, fm.u_tip, samples)
    rep = lambda a: np.repeat(a, samples, 0)  # noqa: E731
    Ps = fm.place(rep(mate.A), rep(mate.c), rep(mate.k), np.tile(us, k))[0].reshape(k, samples, 2)
    u = us[np.argmin(np.linalg.norm(Ps - Pc[:, None], axis=-1), axis=1)]
    for _ in range(iters):  # foot of the normal from Pc on the mate: (Pc - Pm) . t_m = 0
        Pm, t, tu, _, _ = mate.place(u)
        f = np.einsum("...i,...i", Pc - Pm, t)
        df = np.einsum("...i,...i", Pc - Pm, tu) - np.einsum("...i,...i", t, t)
        u = np.clip(u - f / np.where(np.abs(df) > 1e-12, df, -1e-12), fm.u_form, fm.u_tip)
    Pm, t, tu, Amk, g = mate.place(u)
    n = apply(Amk, fm.normal(*fm.eval(u)[1:])[0])
    foot = np.abs(np.einsum("...i,...i", Pc - Pm, t)) < 1e-9 * np.linalg.norm(t, axis=-1)
    return np.where(foot, np.einsum("...i,...i", Pc - Pm, n), np.inf), u
