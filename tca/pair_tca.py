r"""Tooth contact analysis of a gear pair over several cycles of meshing (Eqs. 1.9–1.14).

Procedure (section 1.4):

1. The reference pair of teeth (tooth 0 of each gear) is solved over a grid of :math:`\phi_1`
   commensurate with the angular pitch :math:`2\pi/N_1`: a coarse continuation from the pitch
   point outward (Newton from the previous solutions, quadratic predictor), then the fine grid in
   one batched Newton solve from spline-interpolated guesses (Eq. 1.12).
2. Each point is classified. If the point of tangency lies inside both working areas it is the
   contact; otherwise the bounded surfaces first touch along a boundary (edge contact) or at a
   corner of a working area, found by :mod:`tca.contact`; the first touch is the largest
   :math:`\phi_2` among the valid ones. A point of tangency below the start of the fillet marks
   contact with the fillet (interference).
3. Neighbouring pairs of identical teeth repeat the reference pair shifted by one pitch, so the
   transmission function of the drive is :math:`\phi_2(\phi_1) = \max_k \phi_2^{(k)}(\phi_1)`:
   the pair with the largest :math:`\Delta\phi_2` is in contact (the others have backlash).
   Transmission errors follow Eq. (1.13), :math:`\Delta\phi_2 = \phi_2 - (N_1/N_2)\phi_1`, in the
   absolute sense of :mod:`tca.pair`; paths of contact are Eq. (1.14).

Every converged point is verified: max residual < ``max_residual`` (1e-10 mm by default), or a
:class:`~tca.errors.ConvergenceError` names the position.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from .contact import PlacedFlank, corner_system, edge_edge_system, edge_system, tangency_system
from .ellipse import contact_ellipse
from .errors import ConvergenceError, GeometryError, InputError
from .newton import NewtonResult, newton
from .pair import GearPair

__all__ = ["TCAOptions", "ContactKind", "ReferencePairSolution", "PairTCAResult", "run_pair_tca", "solve_reference_pair", "bounded_pass", "ellipse_outlines",
           "ARCSEC"]

ARCSEC = math.pi / (180 * 3600)  # one arcsecond [rad]


class ContactKind:
    NONE, SURFACE, EDGE, CORNER, FILLET = 0, 1, 2, 3, 4
    names = {0: "none", 1: "surface", 2: "edge", 3: "corner", 4: "fillet"}


@dataclass(frozen=True)
class TCAOptions:
    """Resolution and tolerances of a pair TCA."""

    cycles: int = 2
    steps_per_cycle: int = 40
    elastic_approach: float = 0.0065  # [mm], for the contact ellipse
    tol: float = 1e-11  # Newton target on residuals [mm]
    max_residual: float = 1e-10  # verification of every converged point [mm]
    coarse_per_cycle: int = 10  # sequential continuation points per cycle; the rest are solved in one batch
    area_tol: float = 1e-7  # [mm] a point on a boundary counts as inside

    def __post_init__(self):
        if not (isinstance(self.cycles, int) and 1 <= self.cycles <= 50):
            raise InputError("tca.cycles", self.cycles, "an integer in [1, 50]")
        if not (isinstance(self.steps_per_cycle, int) and 4 <= self.steps_per_cycle <= 2000):
            raise InputError("tca.steps_per_cycle", self.steps_per_cycle, "an integer in [4, 2000]")
        if not (0 < self.elastic_approach < 1):
            raise InputError("tca.elastic_approach_mm", self.elastic_approach, "in (0, 1) mm")
        if not (isinstance(self.coarse_per_cycle, int) and 2 <= self.coarse_per_cycle):
            raise InputError("tca.coarse_per_cycle", self.coarse_per_cycle, "an integer >= 2")

    @property
    def coarse_every(self) -> int:
        """Stride of the sequential continuation on the fine grid."""
        return max(1, round(self.steps_per_cycle / self.coarse_per_cycle))


@dataclass(frozen=True, eq=False)
class ReferencePairSolution:
    """Contact of the reference pair of teeth on the grid phi1 = phi1_0 + j h."""

    phi1: np.ndarray  # (n,)
    phi2: np.ndarray  # (n,), -inf where no contact
    x: np.ndarray  # (n, 5) u1, v1, u2, v2, phi2
    kind: np.ndarray  # (n,) ContactKind
    residual: np.ndarray  # (n,)
    where: np.ndarray  # (n,) boundary code: 10*flank + boundary for edges, 100*flank + 10*a + b for corners
    j: np.ndarray  # (n,) grid index
    newton_iterations: int
    tangency: np.ndarray  # (n,) a point of tangency of the extended surfaces was found
    out_of_mesh: np.ndarray  # (n,) beyond the position where the pair was seen to leave its mesh


@dataclass(frozen=True, eq=False)
class PairTCAResult:
    """Pair TCA over `cycles` cycles: per-position arrays and the reference-pair curve."""

    pair: GearPair
    options: TCAOptions
    phi1: np.ndarray
    phi2: np.ndarray
    te: np.ndarray  # Delta phi2 [rad]
    active_pair: np.ndarray  # index k of the pair in contact
    kind: np.ndarray
    point_f: np.ndarray  # contact point in S_f [mm]
    params: np.ndarray  # (n, 4) u1, v1, u2, v2 on the reference teeth
    point1: np.ndarray  # contact point on tooth surface 1, gear-1 frame [mm]
    point2: np.ndarray  # contact point on tooth surface 2, gear-2 frame [mm]
    ellipse_a: np.ndarray  # semi-major axis [mm]
    ellipse_b: np.ndarray  # semi-minor axis [mm]
    ellipse_angle: np.ndarray  # major axis from the projected gear-1 axis [rad]
    residual: np.ndarray
    reference: ReferencePairSolution
    transitions: np.ndarray  # phi1 at which the pair in contact changes [rad]
    elapsed: float
    boundary: np.ndarray  # where edge/corner contact is: 10 flank + boundary (1 tip, 2 z_max, 3 z_min),
    #                       100 flank + 10 boundary + end for corners, 1000 + 10 b1 + b2 for edge-to-edge
    transition_te: np.ndarray  # TE at the transitions [rad] (both pairs in contact there)
    te_extremes: tuple  # (min, max) of the TE function [rad]: grid, exact transitions, refined vertices

    def edge_boundaries(self) -> set[int]:
        """Working-area boundaries (1 tip, 2 z_max, 3 z_min) that carry edge or corner contact."""
        out = set()
        for w in self.boundary[(self.kind == ContactKind.EDGE) | (self.kind == ContactKind.CORNER)]:
            w = int(w)
            if w >= 1000:
                out |= {(w // 10) % 10, w % 10}
            elif w >= 100:
                out.add((w // 10) % 10)
            else:
                out.add(w % 10)
        return out

    @property
    def te_arcsec(self) -> np.ndarray:
        return self.te / ARCSEC

    @property
    def te_peak_to_peak_arcsec(self) -> float:
        """Peak-to-peak TE [arcsec], with the extremes at the exact transitions and refined vertices."""
        return float(self.te_extremes[1] - self.te_extremes[0]) / ARCSEC

    @property
    def edge_contact(self) -> bool:
        return bool(np.any((self.kind == ContactKind.EDGE) | (self.kind == ContactKind.CORNER)))

    @property
    def max_residual(self) -> float:
        return float(np.max(self.residual))

    def summary(self) -> dict:
        """Key numbers (JSON-ready)."""
        kinds = {ContactKind.names[k]: int(np.sum(self.kind == k)) for k in np.unique(self.kind)}
        finite_a = self.ellipse_a[np.isfinite(self.ellipse_a)]
        return {
            "te_peak_to_peak_arcsec": self.te_peak_to_peak_arcsec,
            "te_max_arcsec": float(self.te_extremes[1] / ARCSEC),
            "te_min_arcsec": float(self.te_extremes[0] / ARCSEC),
            "te_transitions_arcsec": [float(t / ARCSEC) for t in self.transition_te],
            "edge_contact": self.edge_contact,
            "contact_kinds": kinds,
            "positions": int(len(self.phi1)),
            "cycles": self.options.cycles,
            "transitions_deg": [math.degrees(t) for t in self.transitions],
            "max_residual_mm": self.max_residual,
            "line_contact": bool(np.any(np.isinf(self.ellipse_a) & (self.kind == ContactKind.SURFACE))),
            "ellipse_major_max_mm": float(finite_a.max()) if finite_a.size else None,
            "elapsed_s": self.elapsed,
        }


# ---------------------------------------------------------------------------------------------
def _contact_ratio(pair: GearPair) -> float:
    """Transverse + overlap contact ratio of the nominal involute pair (sizes the search range)."""
    g1, g2 = pair.gear1, pair.gear2
    at = g1.transverse_pressure_angle
    pbt = 2 * math.pi * g1.r_b / g1.teeth
    a1 = math.sqrt(max(g1.r_tip**2 - g1.r_b**2, 0.0))
    a2 = math.sqrt(max(g2.r_tip**2 - g2.r_b**2, 0.0))
    line = pair.E * math.sin(at)
    if pair.kind == "external":
        ea = (a1 + a2 - line) / pbt
    elif pair.kind == "internal":
        ea = (a1 - a2 + line) / pbt
    else:
        ea = (a2 - a1 + line) / pbt
    eb = min(g1.face_width, g2.face_width) * math.sin(g1.helix) / (math.pi * g1.module)
    return max(ea, 1.0) + eb


def _flanks(pair: GearPair):
    m1, m2 = pair.mounts()
    return PlacedFlank(pair.gear1, pair.side1, m1), PlacedFlank(pair.gear2, pair.side2, m2)


def _start(pair: GearPair, f1: PlacedFlank):
    """phi1 at which the pitch point of flank 1 (u = 0, z = 0) is on the line of centres."""
    p = f1.surface.evaluate(0.0, 0.0).r
    phi1_0 = -math.atan2(p[1], p[0])
    return phi1_0


def _solve_one(fun, x0, tol, prefer, maxiter=20):
    res = newton(fun, x0[None, :], tol=tol, maxiter=maxiter, raise_on_failure=False, prefer=prefer,
                 prefer_weights=PREFER_WEIGHTS, max_backtracks=8)
    return res.x[0], bool(res.converged[0]), float(res.residual[0]), int(res.iterations[0])


# weights of the preferred point (centre of flank 1's working area) in the first Newton phase
PREFER_WEIGHTS = np.array([1e-3, 1e-3, 0.0, 0.0, 0.0])


def _centre_preference(f1: PlacedFlank):
    """Preferred tangency point: the centre of flank 1's working area (selects a point of a contact line)."""
    ar = f1.gear.area(f1.side)
    uc, vc = 0.5 * (ar.u_form + ar.u_tip), 0.5 * (ar.z_min + ar.z_max)

    def prefer(x, idx):
        p = x.copy()
        p[:, 0] = uc
        p[:, 1] = vc
        return p

    return prefer


def _constraints(f1, f2, x):
    """Working-area constraints (n, 2, 4) of both flanks at parameters x."""
    l1 = f1.surface.evaluate(x[:, 0], x[:, 1])
    l2 = f2.surface.evaluate(x[:, 2], x[:, 3])
    return np.stack([f1.constraints(l1, x[:, 0]), f2.constraints(l2, x[:, 2])], 1)


def _in_domain(f1, f2, x) -> np.ndarray:
    """Tangency points within the parameter domains of both surfaces (not run off to infinity)."""
    ok = np.isfinite(x).all(-1)
    for f, (iu, iv) in ((f1, (0, 1)), (f2, (2, 3))):
        s = f.surface
        du = s.u_range[1] - s.u_range[0]
        ok &= (x[:, iu] > s.u_range[0] - du) & (x[:, iu] < s.u_range[1] + du)
        ok &= (x[:, iv] > s.v_range[0]) & (x[:, iv] < s.v_range[1])
    return ok


DEEP_INSIDE = 0.05  # [mm] a tangency this far inside both working areas must have neighbours


def solve_reference_pair(pair: GearPair, opts: TCAOptions = TCAOptions(), span_cycles: float | None = None,
                         bounded: str = "all") -> "ReferencePairSolution":
    """Contact of the reference pair of teeth over phi1_0 +- span (in cycles) on the TCA grid.

    With ``bounded="all"`` every position whose tangency is not inside both working areas gets an
    edge/corner search; with ``"none"`` only the tangency pass is done (see :func:`bounded_pass`).
    """
    f1, f2 = _flanks(pair)
    ratio = pair.ratio
    pitch = 2 * math.pi / pair.gear1.teeth
    h = pitch / opts.steps_per_cycle
    phi1_0 = _start(pair, f1)
    if span_cycles is None:
        span_cycles = 0.5 * _contact_ratio(pair) + 0.75
    J = int(math.ceil(span_cycles * opts.steps_per_cycle))
    js = np.arange(-J, J + 1)
    phis = phi1_0 + js * h
    n = len(js)
    prefer = _centre_preference(f1)
    X = np.full((n, 5), np.nan)
    tan_ok = np.zeros(n, bool)
    beyond = np.zeros(n, bool)  # past the point where the pair left its mesh
    total_its = 0

    out_of_mesh = max(pair.gear1.module, pair.gear2.module)

    def deep(x):
        return bool(np.all(_constraints(f1, f2, x[None])[0] < -DEEP_INSIDE))

    # ---- tangency: coarse continuation from the pitch point in both directions
    x0 = np.array([0.0, 0.0, 0.0, 0.0, ratio * phi1_0])
    xs, conv, res, its = _solve_one(tangency_system(f1, f2, np.array([phi1_0])), x0, opts.tol, prefer, 60)
    total_its += its
    i0 = J
    if conv and _in_domain(f1, f2, xs[None])[0]:
        X[i0], tan_ok[i0] = xs, True
    c = opts.coarse_every
    block = 6
    if tan_ok[i0]:
        # block continuation: `block` coarse points per direction solved together, guesses extrapolated
        # by a polynomial through the last solved coarse points
        for direction in (1, -1):
            hist = [i0]
            stop = False
            while not stop:
                # blocks grow with the history: a single known point extrapolates poorly
                size = min(block, 2 * len(hist) - 1)
                targets = [hist[-1] + direction * c * (q + 1) for q in range(size)]
                targets = [i for i in targets if 0 <= i < n]
                if not targets:
                    break
                known = np.array(hist[-4:])
                deg = min(len(known) - 1, 2)
                if deg == 0:
                    guess = np.repeat(X[known[-1]][None], len(targets), 0)
                else:
                    coef = np.polyfit(js[known], X[known], deg)
                    guess = np.stack([np.polyval(coef[:, k], js[targets]) for k in range(5)], -1)
                r = newton(tangency_system(f1, f2, phis[targets]), guess, tol=opts.tol, maxiter=20,
                           raise_on_failure=False, prefer=prefer, prefer_weights=PREFER_WEIGHTS, max_backtracks=8)
                total_its += int(r.iterations.sum())
                good = r.converged & _in_domain(f1, f2, r.x)
                for q, i in enumerate(targets):
                    if not good[q]:
                        # retry once from the last solution; then the pair has left its mesh (or raise)
                        xs, conv, res, its = _solve_one(tangency_system(f1, f2, np.array([phis[i]])), X[hist[-1]],
                                                        opts.tol, prefer, maxiter=10)
                        total_its += its
                        if not (conv and _in_domain(f1, f2, xs[None])[0]):
                            if deep(X[hist[-1]]):
                                raise ConvergenceError("pair TCA (tangency)", f"phi1 = {math.degrees(phis[i]):.6f} deg",
                                                       res, its)
                            if _constraints(f1, f2, X[hist[-1]][None])[0][:, 1].max() > 0.25 * out_of_mesh:
                                # already past a tooth tip and the tangency runs off: leaving the mesh
                                if direction > 0:
                                    beyond[hist[-1] + 1:] = True
                                else:
                                    beyond[:hist[-1]] = True
                            stop = True
                            break
                    else:
                        xs = r.x[q]
                    X[i], tan_ok[i] = xs, True
                    hist.append(i)
                    # out of mesh: the tangency point is past a tooth tip by more than a module; the
                    # positions beyond cannot touch either (past a face edge the pair may still touch at
                    # that edge, so those positions are searched for edge contact)
                    if _constraints(f1, f2, xs[None])[0][:, 1].max() > out_of_mesh:
                        if direction > 0:
                            beyond[i + 1:] = True
                        else:
                            beyond[:i] = True
                        stop = True
                        break

    # ---- fine grid: batched Newton from spline guesses between coarse points
    coarse = np.flatnonzero(tan_ok)
    if len(coarse) >= 2:
        lo, hi = coarse.min(), coarse.max()
        fine = np.setdiff1d(np.arange(lo, hi + 1), coarse)
        if len(fine):
            if len(coarse) >= 4:
                guess = CubicSpline(js[coarse], X[coarse], axis=0)(js[fine])
            else:
                guess = np.stack([np.interp(js[fine], js[coarse], X[coarse][:, k]) for k in range(5)], -1)
            r = newton(tangency_system(f1, f2, phis[fine]), guess, tol=opts.tol, maxiter=40, raise_on_failure=False,
                       prefer=prefer, prefer_weights=PREFER_WEIGHTS)
            total_its += int(r.iterations.sum())
            good = r.converged & _in_domain(f1, f2, r.x)
            X[fine[good]], tan_ok[fine[good]] = r.x[good], True
            for q in np.flatnonzero(~good):
                i = fine[q]
                nb = coarse[np.argmin(np.abs(coarse - i))]
                if not deep(X[nb]):
                    continue  # near the end of the mesh: the bounded search takes over
                # second chance from the nearest solved neighbour: a failure here is an error
                xs, conv, res, its = _solve_one(tangency_system(f1, f2, np.array([phis[i]])), X[nb], opts.tol, prefer)
                if not (conv and _in_domain(f1, f2, xs[None])[0]):
                    raise ConvergenceError("pair TCA (tangency)", f"phi1 = {math.degrees(phis[i]):.6f} deg", res, its)
                X[i], tan_ok[i] = xs, True

    kind = np.zeros(n, int)
    where = np.zeros(n, int)
    phi2 = np.full(n, -np.inf)
    resid = np.full(n, np.nan)
    it = np.flatnonzero(tan_ok)
    if len(it):
        Fv, _ = tangency_system(f1, f2, phis[it])(X[it], np.arange(len(it)))
        resid[it] = np.abs(Fv).max(-1)
        if np.any(resid[it] > opts.max_residual):
            k = it[np.argmax(resid[it])]
            raise ConvergenceError("pair TCA verification", f"phi1 = {math.degrees(phis[k]):.6f} deg", float(resid[k]), 0)
    viol = np.zeros((n, 2, 4), bool)
    if len(it):
        viol[it] = _constraints(f1, f2, X[it]) > opts.area_tol
    inside = tan_ok & ~viol.reshape(n, -1).any(-1)
    kind[inside] = ContactKind.SURFACE
    phi2[inside] = X[inside, 4]
    # tangency beyond the fillet start only (contact with the fillet region of a flank)
    fillet_only = tan_ok & ~inside & ~viol[:, :, 1:].any((1, 2))
    kind[fillet_only] = ContactKind.FILLET
    phi2[fillet_only] = X[fillet_only, 4]

    ref = ReferencePairSolution(phis, phi2, X, kind, resid, where, js, total_its, tan_ok, beyond)
    if bounded == "all":
        bounded_pass(pair, ref, np.flatnonzero((ref.kind == ContactKind.NONE) & ~ref.out_of_mesh), opts)
    return ref


def bounded_pass(pair: GearPair, ref: "ReferencePairSolution", sel: np.ndarray, opts: TCAOptions) -> None:
    """Edge, edge-to-edge and corner contact at reference positions `sel` (tangency not inside); in place."""
    sel = np.asarray(sel, int)
    if not len(sel):
        return
    f1, f2 = _flanks(pair)
    ratio = pair.ratio
    phis, X, js = ref.phi1, ref.x, ref.j
    tan_ok = ref.tangency
    g2 = np.where(tan_ok, X[:, 4], np.nan)
    te_known = g2 - ratio * phis
    fin = np.isfinite(te_known)
    te_guess = np.interp(js, js[fin], te_known[fin]) if fin.any() else np.zeros(len(js))
    guess2 = ratio * phis[sel] + te_guess[sel]
    xb, kb, wb, rb = _bounded_contacts(pair, f1, f2, phis, sel, guess2, opts)
    touch = np.isfinite(xb[:, 4])
    # line contact clipped by a boundary: the boundary point lies on the line of contact (same phi2)
    line = touch & tan_ok[sel] & (np.abs(xb[:, 4] - X[sel, 4]) < 1e-10)
    kb = np.where(line, ContactKind.SURFACE, kb)
    t = sel[touch]
    X[t] = xb[touch]
    ref.kind[t], ref.where[t], ref.phi2[t], ref.residual[t] = kb[touch], wb[touch], xb[touch, 4], rb[touch]
    bad = t[ref.residual[t] > opts.max_residual]
    if len(bad):
        k = bad[np.argmax(ref.residual[bad])]
        raise ConvergenceError("edge-contact verification", f"phi1 = {math.degrees(phis[k]):.6f} deg",
                               float(ref.residual[k]), 0)





def _u_of_radius(flank: PlacedFlank):
    """Interpolant u(radius) of a flank's rack-generated profile (guesses for point projections)."""
    h = flank.gear.helicoid(flank.side)
    us = np.linspace(h.u_range[0], h.u_range[1], 200)
    rad = np.linalg.norm(h.profile(us)[0], axis=-1)
    order = np.argsort(rad)
    return lambda r: np.interp(r, rad[order], us[order])


def _boundary_param(flank: PlacedFlank, b: int):
    """Range (t0, t1) of the parameter along boundary b, and a map t -> (u, v) on it."""
    ar = flank.gear.area(flank.side)
    if b == 1:  # tip: parameter is z
        return (ar.z_min, ar.z_max), lambda t: _tip_points(flank, np.full(np.shape(t), ar.u_tip), t)
    zb = ar.z_max if b == 2 else ar.z_min
    u_end = _tip_points(flank, np.array([ar.u_tip]), np.array([zb]))[0, 0]
    return (ar.u_form, u_end), lambda t: np.stack([np.asarray(t, float), np.full(np.shape(t), zb)], -1)


def _bounded_contacts(pair, f1, f2, phis, sel, phi2_guess, opts, samples: int = 9):
    """First touch of the bounded flanks along their boundaries, where tangency is not inside.

    For every physical boundary (tip, z_max, z_min) of both flanks, points sampled along it are
    put on the other flank by turning gear 2 (three position equations, well conditioned); the
    first touch along that boundary is the largest phi2 among the points that land inside the
    other working area. An interior maximum is refined by the edge-tangency equations
    (:func:`tca.contact.edge_system`); a maximum at an end of the boundary is a corner contact.
    Returns x (n, 5), kind, where-code and residual for the positions `sel` (-inf phi2: no touch).
    """
    n = len(sel)
    out_x = np.full((n, 5), np.nan)
    out_x[:, 4] = -np.inf
    out_kind = np.zeros(n, int)
    out_where = np.zeros(n, int)
    out_res = np.full(n, np.nan)
    flanks = (f1, f2)
    for fl in (1, 2):
        fi, fo = flanks[fl - 1], flanks[2 - fl]
        u_of_r = _u_of_radius(fo)
        bounds = [_boundary_param(fi, b) for b in (1, 2, 3)]

        def project(tts, ph2gs):
            """Put boundary points t (n, m) of the three boundaries on the other flank in one batched solve;
            per boundary: (uv (n, m, 2), NewtonResult, constraints of the other flank)."""
            uvs, ph1s, ph2s, shapes = [], [], [], []
            for ((_, on_b), tt, ph2g) in zip(bounds, tts, ph2gs):
                P = np.repeat(np.arange(n), tt.shape[1])
                uvs.append(on_b(tt.ravel()))
                ph1s.append(phis[sel][P])
                ph2s.append(ph2g[P])
                shapes.append(tt.shape)
            uv, ph1, ph2 = np.concatenate(uvs), np.concatenate(ph1s), np.concatenate(ph2s)
            if fl == 1:
                pw, _, _ = f1.world(uv[:, 0], uv[:, 1], ph1)
                Rf, _, tf, _ = f2.frame(ph2)
            else:
                pw, _, _ = f2.world(uv[:, 0], uv[:, 1], ph2)
                Rf, _, tf, _ = f1.frame(ph1)
            loc = np.einsum("nji,nj->ni", Rf, pw.r - tf)
            g = np.stack([u_of_r(np.hypot(loc[:, 0], loc[:, 1])), loc[:, 2], ph2], -1)
            rr = newton(corner_system(f1, f2, ph1, fl, uv), g, tol=opts.tol, maxiter=15, raise_on_failure=False,
                        max_backtracks=6)
            con = fo.constraints(fo.surface.evaluate(rr.x[:, 0], rr.x[:, 1]), rr.x[:, 0])
            out, k = [], 0
            for uvb, shape in zip(uvs, shapes):
                sl = slice(k, k + len(uvb))
                k += len(uvb)
                out.append((uvb.reshape(shape + (2,)), NewtonResult(rr.x[sl], rr.residual[sl], rr.iterations[sl],
                                                                    rr.converged[sl]), con[sl]))
            return out

        # level 1: uniform samples; level 2: samples around the best level-1 sample (sharp maxima)
        T1s = [np.broadcast_to(np.linspace(t0, t1, samples), (n, samples)) for (t0, t1), _ in bounds]
        lev1 = project(T1s, [phi2_guess] * 3)
        T2s, g2s = [], []
        for ((t0, t1), _), T1, (uv1, r1, con1) in zip(bounds, T1s, lev1):
            ins1 = np.all(con1 <= opts.area_tol, -1) & r1.converged
            v1 = np.where(ins1, r1.x[:, 2], -np.inf).reshape(n, samples)
            k1 = np.argmax(v1, 1)
            dt = (t1 - t0) / (samples - 1)
            lo_t = np.clip(T1[np.arange(n), k1] - dt, t0, t1)
            hi_t = np.clip(T1[np.arange(n), k1] + dt, t0, t1)
            T2s.append(lo_t[:, None] + (hi_t - lo_t)[:, None] * np.linspace(0, 1, samples)[None, :])
            g2s.append(np.where(np.isfinite(v1.max(1)), v1.max(1), phi2_guess))
        lev2 = project(T2s, g2s)
        for b, ((t0, t1), _), T1, T2, (uv1, r1, con1), (uv2, r2, con2) in zip((1, 2, 3), bounds, T1s, T2s, lev1, lev2):
            # keep both levels (level 1 catches edge-to-edge crossings anywhere along the boundary)
            T = np.concatenate([T1, T2], 1)
            order = np.argsort(T, 1, kind="stable")
            uvb_all = np.concatenate([uv1, uv2], 1)
            uvb_all = np.take_along_axis(uvb_all, order[..., None], 1)
            X3 = np.concatenate([r1.x.reshape(n, samples, 3), r2.x.reshape(n, samples, 3)], 1)
            X3 = np.take_along_axis(X3, order[..., None], 1)
            CON = np.concatenate([con1.reshape(n, samples, 4), con2.reshape(n, samples, 4)], 1)
            CON = np.take_along_axis(CON, order[..., None], 1)
            CONV = np.take_along_axis(np.concatenate([r1.converged.reshape(n, samples), r2.converged.reshape(n, samples)], 1), order, 1)
            RES = np.take_along_axis(np.concatenate([r1.residual.reshape(n, samples), r2.residual.reshape(n, samples)], 1), order, 1)
            m2 = 2 * samples
            ends = np.zeros((n, m2), bool)
            tt = np.take_along_axis(T, order, 1)
            ends |= (tt <= t0 + 1e-12) | (tt >= t1 - 1e-12)
            inside = np.all(CON <= opts.area_tol, -1) & CONV
            val = np.where(inside, X3[:, :, 2], -np.inf)
            best = np.argmax(val, 1)
            bval = val[np.arange(n), best]
            has = np.isfinite(bval)
            xo = X3
            res3 = RES
            # edge-to-edge: where the projected boundary leaves the other working area through one of its
            # physical boundaries, the two boundary curves cross (guess by linear interpolation)
            co = CON
            conv2 = CONV
            for b2 in (1, 2, 3):
                c = co[:, :, b2]
                others = np.delete(co, b2, axis=2).max(-1) <= 1e-3
                cross = (np.sign(c[:, :-1]) != np.sign(c[:, 1:])) & conv2[:, :-1] & conv2[:, 1:]
                cross &= others[:, :-1] | others[:, 1:]
                pi, si = np.nonzero(cross)
                if not len(pi):
                    continue
                t = (c[pi, si] / (c[pi, si] - c[pi, si + 1]))[:, None]
                uvi = uvb_all[pi, si] * (1 - t) + uvb_all[pi, si + 1] * t
                oth = xo[pi, si] * (1 - t) + xo[pi, si + 1] * t
                g = np.empty((len(pi), 5))
                if fl == 1:
                    g[:, :2], g[:, 2:4], bb = uvi, oth[:, :2], (b, b2)
                else:
                    g[:, :2], g[:, 2:4], bb = oth[:, :2], uvi, (b2, b)
                g[:, 4] = oth[:, 2]
                ree = newton(edge_edge_system(f1, f2, phis[sel][pi], *bb), g, tol=opts.tol, maxiter=40,
                             raise_on_failure=False)
                xe = ree.x
                c1 = f1.constraints(f1.surface.evaluate(xe[:, 0], xe[:, 1]), xe[:, 0])
                c2 = f2.constraints(f2.surface.evaluate(xe[:, 2], xe[:, 3]), xe[:, 2])
                c1[:, bb[0]] = 0.0
                c2[:, bb[1]] = 0.0
                ok = ree.converged & np.all(c1 <= opts.area_tol, -1) & np.all(c2 <= opts.area_tol, -1)
                for q in np.flatnonzero(ok):
                    i = pi[q]
                    if xe[q, 4] > out_x[i, 4] + 1e-13:
                        out_x[i], out_kind[i], out_res[i] = xe[q], ContactKind.EDGE, ree.residual[q]
                        out_where[i] = 1000 + 10 * bb[0] + bb[1]

            def full(uvi, oth):
                x = np.empty(oth.shape[:-1] + (5,))
                if fl == 1:
                    x[..., :2], x[..., 2:4] = uvi, oth[..., :2]
                else:
                    x[..., :2], x[..., 2:4] = oth[..., :2], uvi
                x[..., 4] = oth[..., 2]
                return x

            if not has.any():
                continue
            # interior maxima: refine with the edge-tangency equations
            interior = has & ~ends[np.arange(n), best]
            cand_x = full(uvb_all[np.arange(n), best], xo[np.arange(n), best])
            cand_kind = np.where(interior, ContactKind.EDGE, ContactKind.CORNER)
            cand_where = np.where(interior, 10 * fl + b, 100 * fl + 10 * b + np.where(best == 0, 0, 9))
            cand_where = np.where(interior, cand_where, 100 * fl + 10 * b + np.where(np.take_along_axis(T, order, 1)[np.arange(n), best] <= t0 + 1e-12, 0, 9))
            cand_res = res3[np.arange(n), best]
            if interior.any():
                ii = np.flatnonzero(interior)
                re = newton(edge_system(f1, f2, phis[sel][ii], fl, b), cand_x[ii], tol=opts.tol, maxiter=40,
                            raise_on_failure=False)
                xe = re.x
                c1 = f1.constraints(f1.surface.evaluate(xe[:, 0], xe[:, 1]), xe[:, 0])
                c2 = f2.constraints(f2.surface.evaluate(xe[:, 2], xe[:, 3]), xe[:, 2])
                cc = np.stack([c1, c2], 1)
                cc[:, fl - 1, b] = 0.0
                good = re.converged & np.all(cc <= opts.area_tol, (1, 2)) & (xe[:, 4] >= bval[ii] - 1e-12)
                cand_x[ii[good]] = xe[good]
                cand_res[ii[good]] = re.residual[good]
                # a maximum that the refinement could not confirm stays a sampled boundary point; it is
                # still a touch of the bounded surfaces (the sample lies on both), reported as an edge
            better = has & (cand_x[:, 4] > out_x[:, 4] + 1e-13)
            out_x[better] = cand_x[better]
            out_kind[better] = cand_kind[better]
            out_where[better] = cand_where[better]
            out_res[better] = cand_res[better]
    return out_x, out_kind, out_where, out_res


def _tip_points(fi, u, v):
    """(u, v) on the tip boundary of flank fi at axial positions v (vectorized Newton in u)."""
    from .contact import boundary_derivs

    u = np.array(u, float)
    v = np.asarray(v, float)
    for _ in range(50):
        loc = fi.surface.evaluate(u, v)
        c, cu, _ = boundary_derivs(fi, loc, u, 1)
        du = -c / cu
        u = u + du
        if np.abs(du).max() < 1e-14:
            break
    return np.stack([u, v], -1)


def _transitions(pair, f1, f2, ref, J, s, opts, phi1, cand, a, ks, kind_c):
    """phi1 and TE at each change of the pair in contact (exact where both contacts are surface contacts).

    Between grid points i and i+1 the pair in contact changes from ka to kb; the transition is the
    root of g(phi) = TE_ka(phi) - TE_kb(phi), where TE_k(phi) is the reference pair's TE at
    phi - k p (p the angular pitch). Regula falsi (Illinois) on batched tangency solves.
    """
    pitch = 2 * math.pi / pair.gear1.teeth
    ratio = pair.ratio
    idx = np.flatnonzero(np.diff(ks[a]) != 0)
    n = len(idx)
    lo, hi = phi1[idx], phi1[idx + 1]
    ka, kb = a[idx], a[idx + 1]
    ga = cand[idx, ka] - cand[idx, kb]
    gb = cand[idx + 1, ka] - cand[idx + 1, kb]
    with np.errstate(invalid="ignore", divide="ignore"):  # masked where a pair has no contact (-inf)
        frac = np.where(np.isfinite(ga) & np.isfinite(gb) & (ga != gb), ga / np.where(ga != gb, ga - gb, 1.0), 0.5)
    frac = np.clip(frac, 0.0, 1.0)
    t_phi = lo + frac * (hi - lo)
    t_te = np.where(np.isfinite(ga), cand[idx, ka] + frac * (cand[idx + 1, ka] - cand[idx, ka]), np.nan)
    exact = np.zeros(n, bool)
    for q in range(n):
        i = idx[q]
        exact[q] = all(kind_c[i + di, col] == ContactKind.SURFACE for di in (0, 1) for col in (ka[q], kb[q]))
    if not exact.any():
        return t_phi.tolist(), t_te.tolist()
    sel = np.flatnonzero(exact)
    # reference-grid indices bracketing each pair's position (guesses by linear interpolation)
    h = pitch / s
    j0 = ref.j[J]

    def solve(phi, kcol_a, kcol_b):
        """TE of pairs ka and kb at phi, in one batched Newton solve."""
        k = np.concatenate([ks[kcol_a], ks[kcol_b]])
        phr = np.concatenate([phi, phi]) - k * pitch
        jf = (phr - ref.phi1[J]) / h + j0 + J
        jl = np.clip(np.floor(jf).astype(int), 0, len(ref.j) - 2)
        w = (jf - jl)[:, None]
        guess = ref.x[jl] * (1 - w) + ref.x[jl + 1] * w
        r = newton(tangency_system(f1, f2, phr), guess, tol=opts.tol, maxiter=30, raise_on_failure=False)
        te, conv = r.x[:, 4] - ratio * phr, r.converged
        m = len(phi)
        return te[:m], conv[:m], te[m:], conv[m:]

    xa, xb = lo[sel].copy(), hi[sel].copy()
    fa, fb = ga[sel].copy(), gb[sel].copy()
    ok = np.ones(len(sel), bool)
    side = np.zeros(len(sel), int)
    xm = t_phi[sel].copy()
    tem = t_te[sel].copy()
    for _ in range(40):
        xm = np.where(fa != fb, (xa * fb - xb * fa) / np.where(fa != fb, fb - fa, 1.0), 0.5 * (xa + xb))
        ta, ca, tb, cb = solve(xm, ka[sel], kb[sel])
        ok &= ca & cb
        fm = ta - tb
        tem = ta
        if np.all(np.abs(fm) < 1e-13) or not ok.any():
            break
        left = fm * fa > 0  # root between xm and xb
        xa, fa = np.where(left, xm, xa), np.where(left, fm, fa)
        xb, fb = np.where(left, xb, xm), np.where(left, fb, fm)
        # Illinois: halve the stale end's value
        fb = np.where(left & (side == 1), fb / 2, fb)
        fa = np.where(~left & (side == -1), fa / 2, fa)
        side = np.where(left, 1, -1)
    t_phi[sel[ok]] = xm[ok]
    t_te[sel[ok]] = tem[ok]
    return t_phi.tolist(), t_te.tolist()


def _extremes(te, kk, kind, trans_te):
    """(min, max) TE: grid values, exact transitions, and interior extrema refined by a local parabola."""
    vals = list(te) + [t for t in trans_te if np.isfinite(t)]
    for i in range(1, len(te) - 1):
        same = kk[i - 1] == kk[i] == kk[i + 1] and np.all(kind[i - 1:i + 2] == ContactKind.SURFACE)
        if not same:
            continue
        if (te[i] >= te[i - 1] and te[i] >= te[i + 1]) or (te[i] <= te[i - 1] and te[i] <= te[i + 1]):
            y0, y1, y2 = te[i - 1], te[i], te[i + 1]
            den = y0 - 2 * y1 + y2
            if den != 0:
                vals.append(y1 - (y2 - y0) ** 2 / (8 * den))
    return (float(min(vals)), float(max(vals)))


# ---------------------------------------------------------------------------------------------
def run_pair_tca(pair: GearPair, opts: TCAOptions = TCAOptions()) -> PairTCAResult:
    """TCA of a gear pair over opts.cycles cycles of meshing; see the module docstring."""
    t0 = time.perf_counter()
    f1, f2 = _flanks(pair)
    ref = solve_reference_pair(pair, opts, bounded="none")
    s = opts.steps_per_cycle
    ratio = pair.ratio
    J = (len(ref.j) - 1) // 2
    half = opts.cycles * s // 2
    out_j = np.arange(-half, -half + opts.cycles * s + 1)
    K = int(math.ceil(J / s)) + opts.cycles
    ks = np.arange(-K, K + 1)
    # candidate pair k at output index j uses the reference solution at j - k s
    rj = out_j[:, None] - ks[None, :] * s
    valid = np.abs(rj) <= J
    te_ref = ref.phi2 - ratio * ref.phi1
    cand = np.where(valid, te_ref[np.clip(rj + J, 0, 2 * J)], -np.inf)
    # bounded contacts can only lower a pair's phi2 below its tangency (the bounded surfaces lie on the
    # extended ones), so search them only where the pair could still be the one in contact
    env = cand.max(1)
    te_tan = np.where(ref.tangency, ref.x[:, 4] - ratio * ref.phi1, np.inf)
    need = np.zeros(len(ref.j), bool)
    for q, k in enumerate(ks):
        jj = rj[:, q]
        ok = valid[:, q]
        idx = jj[ok] + J
        need[idx] |= (ref.kind[idx] == ContactKind.NONE) & ~ref.out_of_mesh[idx] & (
            (te_tan[idx] > env[ok] + 1e-10) | ~np.isfinite(env[ok]))
    bounded_pass(pair, ref, np.flatnonzero(need), opts)
    te_ref = ref.phi2 - ratio * ref.phi1
    cand = np.where(valid, te_ref[np.clip(rj + J, 0, 2 * J)], -np.inf)
    if not np.all(np.isfinite(cand.max(1))):
        i = int(np.flatnonzero(~np.isfinite(cand.max(1)))[0])
        raise GeometryError("pair", "no contact",
                            f"no pair of teeth is in contact at phi1 = "
                            f"{math.degrees(ref.phi1[J] + out_j[i] * (2 * math.pi / pair.gear1.teeth) / s):.4f} deg "
                            "(contact ratio below 1, or working areas that do not overlap)")
    best = cand.max(1, keepdims=True)
    tie = cand >= best - 1e-10
    kind_c = np.where(valid, ref.kind[np.clip(rj + J, 0, 2 * J)], 0)
    pref = np.where(tie, (kind_c == ContactKind.SURFACE) * 1e6 - np.abs(rj), -np.inf)
    a = np.argmax(pref, 1)
    jr = rj[np.arange(len(out_j)), a] + J
    pitch1 = 2 * math.pi / pair.gear1.teeth
    kk = ks[a]
    phi1 = ref.phi1[J] + out_j * (pitch1 / s)
    te = te_ref[jr]
    phi2 = te + ratio * phi1
    kind = ref.kind[jr]
    if np.any(kind == ContactKind.FILLET):
        i = int(np.flatnonzero(kind == ContactKind.FILLET)[0])
        raise GeometryError("pair", "interference",
                            f"at phi1 = {math.degrees(phi1[i]):.4f} deg the tooth in contact touches below the start of "
                            f"the fillet of its mate (tip interference); reduce the addendum or change the profile shifts")
    X = ref.x[jr]
    # contact points in S_f and on the reference teeth
    w1, l1, _ = f1.world(X[:, 0], X[:, 1], ref.phi1[jr])
    w2, l2, _ = f2.world(X[:, 2], X[:, 3], X[:, 4])
    ea = np.full(len(jr), np.nan)
    eb = np.full(len(jr), np.nan)
    eang = np.full(len(jr), np.nan)
    surf = kind == ContactKind.SURFACE
    if surf.any():
        m1, _ = pair.mounts()
        axis = np.broadcast_to(m1.axis, (int(surf.sum()), 3))
        sub1 = type(w1)(*(f[surf] for f in w1))
        sub2 = type(w2)(*(f[surf] for f in w2))
        a_, b_, ang_, _ = contact_ellipse(sub1, sub2, opts.elastic_approach, axis)
        ea[surf], eb[surf], eang[surf] = a_, b_, ang_
    # transitions: where the active pair changes, solved exactly (TE of both pairs equal) where both
    # contacts are surface contacts, interpolated otherwise
    trans, trans_te = _transitions(pair, f1, f2, ref, J, s, opts, phi1, cand, a, ks, kind_c)
    ext = _extremes(te, kk, kind, trans_te)
    return PairTCAResult(
        pair, opts, phi1, phi2, te, kk, kind, w1.r,
        X[:, :4], l1.r, l2.r, ea, eb, eang, ref.residual[jr], ref, np.array(trans), time.perf_counter() - t0,
        ref.where[jr], np.array(trans_te), ext,
    )


def ellipse_outlines(result: PairTCAResult, which: int, npts: int = 48) -> np.ndarray:
    """Contact ellipses as closed 3D outlines (n, npts, 3) in the frame of gear `which` (1 or 2).

    NaN where there is no ellipse (edge contact) or where it is unbounded (line contact).
    """
    pair = result.pair
    f1, f2 = _flanks(pair)
    n = len(result.phi1)
    out = np.full((n, npts, 3), np.nan)
    ok = np.isfinite(result.ellipse_a) & np.isfinite(result.ellipse_b)
    if not ok.any():
        return out
    X = result.params[ok]
    ph1 = result.phi1[ok] - result.active_pair[ok] * 2 * math.pi / pair.gear1.teeth
    w1, _, _ = f1.world(X[:, 0], X[:, 1], ph1)
    ph2 = (result.phi2[ok] - result.active_pair[ok] * 2 * math.pi / pair.gear2.teeth)
    nrm = w1.n
    axis = np.broadcast_to(pair.mounts()[0].axis, nrm.shape)
    e1 = axis - np.einsum("ij,ij->i", axis, nrm)[:, None] * nrm
    e1 /= np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = np.cross(nrm, e1)
    ang = result.ellipse_angle[ok]
    A = np.cos(ang)[:, None] * e1 + np.sin(ang)[:, None] * e2  # major axis direction
    B = np.cross(nrm, A)
    t = np.linspace(0, 2 * math.pi, npts)
    pts = (w1.r[:, None, :] + result.ellipse_a[ok][:, None, None] * np.cos(t)[None, :, None] * A[:, None, :]
           + result.ellipse_b[ok][:, None, None] * np.sin(t)[None, :, None] * B[:, None, :])
    flank = f1 if which == 1 else f2
    phi = ph1 if which == 1 else ph2
    R, _, tt, _ = flank.frame(phi)
    out[ok] = np.einsum("nji,nkj->nki", R, pts - tt[:, None, :])
    return out
