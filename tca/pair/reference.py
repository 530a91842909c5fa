r"""Continuation of the reference pair of teeth over a grid of :math:`\phi_1` (section 1.4, Eqs. 1.9–1.12).

A coarse continuation from the pitch point outward (Newton from the previous solutions, quadratic
predictor), then the fine grid in one batched Newton solve from spline-interpolated guesses; each
point of tangency is classified against both working areas (:func:`tca.pair.bounded.bounded_pass`
finds the edge and corner contacts where it lies outside).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

from tca.contact.systems import PlacedFlank, tangency_system
from tca.errors import ConvergenceError
from tca.geometry.involute import working_pressure_angle
from tca.numerics.newton import NewtonOptions, PreferredPoint, newton
from tca.pair.gear_pair import GearPair
from tca.pair.bounded import bounded_pass
from tca.pair.relief import relief_pass
from tca.pair.result import ContactKind, ReferencePairSolution, TCAOptions
from tca.pair.sections import section_tangency

__all__ = ["solve_reference_pair", "classify_tangency", "in_domain"]


def _contact_ratio(pair: GearPair) -> float:
    """Transverse + overlap contact ratio of the nominal involute pair (sizes the search range)."""
    g1, g2 = pair.gear1, pair.gear2
    at = working_pressure_angle(g1, g2, pair.E)
    if not math.isfinite(at):
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




def _start(pair: GearPair, f1: PlacedFlank):
    """phi1 at which the pitch point of flank 1 (u = 0, z = 0) is on the line of centres."""
    p = f1.surface.evaluate(0.0, 0.0).r
    phi1_0 = -math.atan2(p[1], p[0])
    return phi1_0


def _solve_one(fun, x0, tol, prefer: PreferredPoint, maxiter=20):
    res = newton(fun, x0[None, :], NewtonOptions(tol=tol, maxiter=maxiter, max_backtracks=8), prefer=prefer,
                 raise_on_failure=False)
    return res.x[0], bool(res.converged[0]), float(res.residual[0]), int(res.iterations[0])


def _by_sections(f1, f2, phi: float, guesses, tol: float, reach: float = math.inf):
    """The fallback of a failed Newton solve at phi: :func:`tca.pair.sections.section_tangency` from each guess in
    turn, in both surfaces' domains and within ``reach`` modules of both working areas, or None."""
    ar = f1.gear.area(f1.side)
    centre = (0.5 * (ar.u_form + ar.u_tip), 0.5 * (ar.z_min + ar.z_max))
    reach = reach * max(f1.gear.module, f2.gear.module)
    for x0 in guesses:
        if x0 is None or not np.all(np.isfinite(x0)):
            continue
        r = section_tangency(f1, f2, phi, np.asarray(x0, float), tol, centre)
        if r is not None and r[1] < tol and in_domain(f1, f2, r[0][None])[0] and \
                _constraints(f1, f2, r[0][None]).max() <= reach:
            return r[0]
    return None


RESCUE_REACH = 0.5  # [modules] how far outside the working areas a start found by sections may lie


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


def classify_tangency(f1, f2, X: np.ndarray, tan_ok: np.ndarray, area_tol: float, kind: np.ndarray,
                      phi2: np.ndarray) -> None:
    """Mark the points of tangency inside both working areas SURFACE and those beyond the start of a fillet only
    FILLET (contact with the fillet region), with their phi2 [rad]; in place, the others untouched."""
    n = len(X)
    it = np.flatnonzero(tan_ok)
    viol = np.zeros((n, 2, 4), bool)
    if len(it):
        viol[it] = _constraints(f1, f2, X[it]) > area_tol
    inside = tan_ok & ~viol.reshape(n, -1).any(-1)
    kind[inside] = ContactKind.SURFACE
    phi2[inside] = X[inside, 4]
    fillet_only = tan_ok & ~inside & ~viol[:, :, 1:].any((1, 2))
    kind[fillet_only] = ContactKind.FILLET
    phi2[fillet_only] = X[fillet_only, 4]


def _constraints(f1, f2, x):
    """Working-area constraints (n, 2, 4) of both flanks at parameters x."""
    l1 = f1.surface.evaluate(x[:, 0], x[:, 1])
    l2 = f2.surface.evaluate(x[:, 2], x[:, 3])
    return np.stack([f1.constraints(l1, x[:, 0]), f2.constraints(l2, x[:, 2])], 1)


def in_domain(f1, f2, x) -> np.ndarray:
    """Tangency points within the parameter domains of both surfaces (not run off to infinity)."""
    ok = np.isfinite(x).all(-1)
    for f, (iu, iv) in ((f1, (0, 1)), (f2, (2, 3))):
        s = f.surface
        du = s.u_range[1] - s.u_range[0]
        ok &= (x[:, iu] > s.u_range[0] - du) & (x[:, iu] < s.u_range[1] + du)
        ok &= (x[:, iv] > s.v_range[0]) & (x[:, iv] < s.v_range[1])
    return ok


DEEP_INSIDE = 0.05  # [mm] a tangency this far inside both working areas must have neighbours
JUMP = 2.0  # [modules] a solution this far (u1, v1) from its continuation guess is another tangency: retried


def _near(x: np.ndarray, guess: np.ndarray, jump: float) -> np.ndarray:
    """Solutions (n, 5) within `jump` [mm] of their guesses on flank 1 (u1, v1): a nearly singular system
    (a crowned helical pair) lets Newton run along the near-line of contact to a far tangency of the
    extended surfaces, off the teeth (then the sections fallback starts from the guess)."""
    return np.hypot(x[:, 0] - guess[:, 0], x[:, 1] - guess[:, 1]) <= jump


def solve_reference_pair(pair: GearPair, opts: TCAOptions = TCAOptions(), span_cycles: float | None = None,
                         bounded: str = "all") -> "ReferencePairSolution":
    """Contact of the reference pair of teeth over phi1_0 +- span (in cycles) on the TCA grid.

    With ``bounded="all"`` every position whose tangency is not inside both working areas gets an
    edge/corner search; with ``"none"`` only the tangency pass is done (see :func:`bounded_pass`).
    """
    f1, f2 = pair.flanks()
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
    prefer = PreferredPoint(_centre_preference(f1), PREFER_WEIGHTS)
    X = np.full((n, 5), np.nan)
    tan_ok = np.zeros(n, bool)
    beyond = np.zeros(n, bool)  # past the point where the pair left its mesh
    total_its = 0

    out_of_mesh = max(pair.gear1.module, pair.gear2.module)
    jump = JUMP * out_of_mesh

    relief_u = [(k, f.gear.rack.relief_start - 0.5 * f.gear.module) for k, f in ((0, f1), (2, f2))
                if f.gear.tip_relief is not None]

    def deep(x):
        # near a tip relief the tangency may end at its kink (tca.pair.relief takes over there)
        if any(x[k] > u_near for k, u_near in relief_u):
            return False
        return bool(np.all(_constraints(f1, f2, x[None])[0] < -DEEP_INSIDE))

    # ---- tangency: coarse continuation from the pitch point in both directions
    x0 = np.array([0.0, 0.0, 0.0, 0.0, ratio * phi1_0])
    xs, conv, res, its = _solve_one(tangency_system(f1, f2, np.array([phi1_0])), x0, opts.tol, prefer, 60)
    total_its += its
    i0 = J
    if not (conv and in_domain(f1, f2, xs[None])[0]):
        # the start needs a tangency near the teeth (one far off them on the extended surfaces, on a misaligned
        # helical pair, says nothing of the mesh: the search for edge contacts takes over, as when Newton fails)
        xs = _by_sections(f1, f2, phi1_0, (x0,), opts.tol, reach=RESCUE_REACH)
        conv = xs is not None
    if conv and in_domain(f1, f2, xs[None])[0]:
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
                r = newton(tangency_system(f1, f2, phis[targets]), guess,
                           NewtonOptions(tol=opts.tol, maxiter=20, max_backtracks=8), prefer=prefer,
                           raise_on_failure=False)
                total_its += int(r.iterations.sum())
                good = r.converged & in_domain(f1, f2, r.x) & _near(r.x, guess, jump)
                for q, i in enumerate(targets):
                    if not good[q]:
                        # retry once from the last solution; then the pair has left its mesh (or raise)
                        xs, conv, res, its = _solve_one(tangency_system(f1, f2, np.array([phis[i]])), X[hist[-1]],
                                                        opts.tol, prefer, maxiter=10)
                        total_its += its
                        conv = conv and bool(_near(xs[None], guess[q][None], jump)[0])
                        if not (conv and in_domain(f1, f2, xs[None])[0]):
                            xs = _by_sections(f1, f2, phis[i], (guess[q], X[hist[-1]]), opts.tol)
                            conv = xs is not None
                            if conv:
                                res = 0.0
                        if not (conv and in_domain(f1, f2, xs[None])[0]):
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
            r = newton(tangency_system(f1, f2, phis[fine]), guess, NewtonOptions(tol=opts.tol, maxiter=40),
                       prefer=prefer, raise_on_failure=False)
            total_its += int(r.iterations.sum())
            good = r.converged & in_domain(f1, f2, r.x) & _near(r.x, guess, jump)
            X[fine[good]], tan_ok[fine[good]] = r.x[good], True
            for q in np.flatnonzero(~good):
                i = fine[q]
                nb = coarse[np.argmin(np.abs(coarse - i))]
                # second chance by sections (near-line contacts), then from the nearest solved neighbour
                xs = _by_sections(f1, f2, phis[i], (guess[q], X[nb]), opts.tol)
                if xs is not None:
                    X[i], tan_ok[i] = xs, True
                    continue
                if not deep(X[nb]):
                    continue  # near the end of the mesh: the bounded search takes over
                # a failure here is an error
                xs, conv, res, its = _solve_one(tangency_system(f1, f2, np.array([phis[i]])), X[nb], opts.tol, prefer)
                if not (conv and in_domain(f1, f2, xs[None])[0]):
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
    classify_tangency(f1, f2, X, tan_ok, opts.area_tol, kind, phi2)

    ref = ReferencePairSolution(phis, phi2, X, kind, resid, where, js, total_its, tan_ok, beyond)
    if bounded == "all":
        bounded_pass(pair, ref, np.flatnonzero((ref.kind == ContactKind.NONE) & ~ref.out_of_mesh), opts)
        relief_pass(pair, ref, opts)  # end relief: relieved zones and ridges that touch first
    return ref

