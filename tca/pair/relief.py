r"""First touch of flanks with end relief: the relieved zones searched by sampling, the ridge as an inner boundary.

An end relief (:mod:`tca.geometry.modifications.end_relief`) makes a flank piecewise smooth in :math:`z`: unmodified in the
middle, relieved from :math:`z_s` to the face end. Under a misalignment the pair then touches
where the tangency solve of :mod:`tca.pair.reference` does not look:

* inside a relieved zone, at a point of tangency far from the start guess of the continuation
  (the middle part of a misaligned flank has no tangency at all, so Newton has nowhere to go);
* on the ridge :math:`z = z_s` of a linear relief, where the slope of the flank jumps: no point
  of tangency exists there, the ridge touches the other flank like an edge (section 1.4, step 2:
  a boundary curve tangent to the other surface), so it is treated as an inner boundary with the
  edge equations of :mod:`tca.contact.systems` (:math:`c = z - z_s` on the relieved side).

For every position, points of each relieved flank on the ridge line and on levels across its
relieved zones (``levels`` x ``samples`` points) are put on the other flank by turning gear 2 (three
position equations, :func:`tca.contact.systems.corner_system`, as :mod:`tca.pair.bounded` does for the
boundaries), and the best point of each flank is sampled again between its neighbours. The first
touch is the largest :math:`\phi_2`; where it beats what the pair TCA knows (the contact found, or,
where the edge search was skipped, the tangency of the extended surfaces, an upper bound of the
bounded contact on which the sampled points also lie: the ridge crossing the contact line of an
aligned pair is no news), it replaces it, refined: on the ridge of a linear relief by the edge
equations (kind EDGE, boundary code ``10 flank + 4`` for the ridge at the z_max end, ``+ 5`` at the
z_min end; a corner ``100 flank + 10 code + 0|9`` where the ridge meets the fillet limit or the tip),
inside a relieved zone by the tangency equations (kind SURFACE), from the best sample or, failing
that, from the refined contact of the nearest position. Where the refined point leaves a working area
through one boundary, the contact is on that boundary (edge-to-edge with the ridge, ``1000 + 10 b1 +
b2``, or an edge of the other flank). A refined contact must touch no later than the best sample.
Where no refinement succeeds the sample itself is kept, as :mod:`tca.pair.bounded` keeps an
unconfirmed boundary maximum: it lies on both flanks (its projection converged), so it is a touch,
later than the true first touch by at most the sampling error of the second level.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tca.contact.systems import edge_edge_system, edge_system, tangency_system
from tca.numerics.newton import NewtonOptions, newton
from tca.pair.gear_pair import GearPair
from tca.pair.bounded import onto_other_flank, tip_points
from tca.pair.result import ContactKind, ReferencePairSolution, TCAOptions

__all__ = ["relief_pass", "RIDGE_Z_MAX", "RIDGE_Z_MIN"]

RIDGE_Z_MAX, RIDGE_Z_MIN = 4, 5  # boundary codes of the ridges (after 1 tip, 2 z_max, 3 z_min)


def _levels(flank, levels: int):
    """(z, ridge code) of the sampled levels of a relieved flank: the ridge first, then across the zone."""
    g = flank.gear
    top, bot = g.end_relief.starts(g.face_width)
    out = []
    for zs, ze, code in ((top, 0.5 * g.face_width, RIDGE_Z_MAX), (bot, -0.5 * g.face_width, RIDGE_Z_MIN)):
        if zs is None:
            continue
        out.append((zs, code))
        out += [(zs + (ze - zs) * q / levels, 0) for q in range(1, levels)]
    return out


def _project(f1, f2, fl: int, phi1: np.ndarray, ph2g: np.ndarray, uv: np.ndarray, opts: TCAOptions):
    """Points uv (n, m, 2) of flank fl put on the other flank at phi1 (n,): x (n, m, 5) and phi2 (n, m),
    -inf where the solve failed or the point lands outside the other working area."""
    n, m = uv.shape[:2]
    flat = uv.reshape(-1, 2)
    with np.errstate(divide="ignore", invalid="ignore"):  # points run off the other flank: not converged
        rr, con = onto_other_flank(f1, f2, fl, flat, np.repeat(phi1, m), np.repeat(ph2g, m), opts.tol)
    ok = rr.converged & np.all(con <= opts.area_tol, -1)
    x = np.empty((n * m, 5))
    own, oth = (slice(0, 2), slice(2, 4)) if fl == 1 else (slice(2, 4), slice(0, 2))
    x[:, own], x[:, oth], x[:, 4] = flat, rr.x[:, :2], rr.x[:, 2]
    return x.reshape(n, m, 5), np.where(ok, rr.x[:, 2], -np.inf).reshape(n, m)


def _candidates(f1, f2, fl: int, phi1, ph2g, opts, levels: int, samples: int):
    """Best sampled touch of relieved flank fl per position: phi2 (n,), x (n, 5), ridge code (n,), end (n,)
    (-1 inside the sampled line, 0 at the fillet limit, 1 at the tip); two levels of sampling along u."""
    fi = (f1, f2)[fl - 1]
    n = len(phi1)
    ar = fi.gear.area(fi.side)
    lev = _levels(fi, levels)
    zl = np.array([z for z, _ in lev])
    code_l = np.array([c for _, c in lev])
    u_tip = tip_points(fi, np.full(len(zl), ar.u_tip), zl)[:, 0]
    t = np.linspace(0.0, 1.0, samples)
    U = ar.u_form + (u_tip - ar.u_form)[:, None] * t  # (levels, samples)
    uv = np.broadcast_to(np.stack([U, np.broadcast_to(zl[:, None], U.shape)], -1).reshape(1, -1, 2), (n, U.size, 2))
    x1, v1 = _project(f1, f2, fl, phi1, ph2g, uv, opts)
    k = np.argmax(v1, 1)
    li, si = k // samples, k % samples
    # level 2: the sampled line of the best point, refined between its neighbours
    lo = U[li, np.clip(si - 1, 0, samples - 1)]
    hi = U[li, np.clip(si + 1, 0, samples - 1)]
    u2 = lo[:, None] + (hi - lo)[:, None] * t
    uv2 = np.stack([u2, np.broadcast_to(zl[li][:, None], u2.shape)], -1)
    g2 = np.where(np.isfinite(v1[np.arange(n), k]), v1[np.arange(n), k], ph2g)
    x2, v2 = _project(f1, f2, fl, phi1, g2, uv2, opts)
    k2 = np.argmax(v2, 1)
    r = np.arange(n)
    use2 = v2[r, k2] > v1[r, k]
    val = np.where(use2, v2[r, k2], v1[r, k])
    x = np.where(use2[:, None], x2[r, k2], x1[r, k])
    u_best = x[:, 0] if fl == 1 else x[:, 2]
    end = np.where(np.abs(u_best - ar.u_form) < 1e-12, 0, np.where(np.abs(u_best - u_tip[li]) < 1e-12, 1, -1))
    return val, x, code_l[li], end


@dataclass(frozen=True, eq=False)
class _Touch:
    """The best sampled touch of relieved flank `flank` (1 or 2) at one position (:func:`_candidates`)."""

    flank: int
    x: np.ndarray  # (5,) u1, v1, u2, v2, phi2
    phi2: float  # [rad]
    ridge: int  # ridge code (RIDGE_Z_MAX, RIDGE_Z_MIN), 0 off the ridge
    end: int  # -1 inside the sampled line, 0 at the fillet limit, 1 at the tip


def relief_pass(pair: GearPair, ref: ReferencePairSolution, opts: TCAOptions, levels: int = 8,
                samples: int = 11) -> tuple[int, int]:
    """Replace the contact of positions where a relieved zone or a ridge touches first (in place).

    Returns (positions replaced, of which kept as sampled points: no refinement converged)."""
    f1, f2 = pair.flanks()
    flanks = (f1, f2)
    relieved = [fl for fl in (1, 2) if flanks[fl - 1].gear.end_relief is not None]
    if not relieved:
        return 0, 0
    sel = np.flatnonzero(~ref.out_of_mesh)
    if not len(sel):
        return 0, 0
    ratio = pair.ratio
    fin = np.isfinite(ref.phi2)
    te = ref.phi2 - ratio * ref.phi1
    te_guess = np.interp(ref.j, ref.j[fin], te[fin]) if fin.any() else np.zeros(len(ref.j))
    phi1 = ref.phi1[sel]
    ph2g = ratio * phi1 + te_guess[sel]
    cands = {fl: _candidates(f1, f2, fl, phi1, ph2g, opts, levels, samples) for fl in relieved}
    top = np.max([c[0] for c in cands.values()], 0)
    # what the pair TCA knows: the contact found, or where it skipped the edge search, the tangency of
    # the extended surfaces (an upper bound of the bounded contact; the relieved points lie on those
    # surfaces, so a sample at or below it is no news, e.g. the ridge line crossing a line contact)
    known = np.where(ref.tangency & (ref.kind == ContactKind.NONE), ref.x[:, 4], ref.phi2)[sel]
    upd = np.flatnonzero(np.isfinite(top) & (top > known + 1e-12))
    replaced = sampled = 0
    done: dict[int, dict[int, np.ndarray]] = {fl: {} for fl in relieved}  # refined x per flank and position
    for q in upd:
        i = sel[q]
        found = []
        for fl in relieved:
            val, x, code, end = (c[q] for c in cands[fl])
            if not np.isfinite(val):
                continue
            touch = _Touch(fl, x, val, int(code), int(end))
            res = _settle(f1, f2, ref.phi1[i], touch, touch.x, opts)
            if not res[4] and done[fl]:  # second chance: from the refined contact of the nearest position
                nb = min(done[fl], key=lambda j: abs(j - i))
                x0 = done[fl][nb].copy()
                x0[4] += ratio * (ref.phi1[i] - ref.phi1[nb])
                again = _settle(f1, f2, ref.phi1[i], touch, x0, opts)
                res = again if again[4] else res
            if res[4]:
                done[fl][i] = res[0]
            found.append(res)
        x, kind, where, resid, refined = max(found, key=lambda f: f[0][4])
        if x[4] > ref.phi2[i] + 1e-12:
            ref.x[i], ref.kind[i], ref.where[i], ref.phi2[i], ref.residual[i] = x, kind, where, x[4], resid
            replaced += 1
            sampled += not refined
    return replaced, sampled


def _settle(f1, f2, phi1: float, touch: _Touch, x0: np.ndarray, opts: TCAOptions):
    """The contact near a sampled touch of a relieved flank, refined from x0: (x, kind, where, residual, refined).

    The ridge of a linear relief meeting the tip or the fillet limit is a corner, exact as sampled; the
    ridge elsewhere, or the tip / fillet limit across a relieved zone, is an edge (edge equations);
    a sample inside a relieved zone is refined by the tangency equations. Where the refined point leaves
    a working area through one boundary, the contact is on that boundary: edge-to-edge (an edge before)
    or an edge of that flank (a tangency before). A refined contact must touch no later than the sample
    (phi2 >= sampled); where no refinement does, the sample itself is returned (refined False): it lies
    on both flanks (its projection converged), so it is a touch, at most the sampling error later than
    the first one.
    """
    fl, code, end, sampled = touch.flank, touch.ridge, touch.end, touch.phi2
    ridge = bool(code) and (f1, f2)[fl - 1].gear.end_relief.power == 1
    if ridge and end >= 0:
        return x0, ContactKind.CORNER, 100 * fl + 10 * code + (9 if end else 0), 0.0, True
    which = code if ridge else (-1 if end < 0 else end)
    ph = np.array([phi1])
    if which >= 0:
        first = (edge_system(f1, f2, ph, fl, which), ContactKind.EDGE, 10 * fl + which, {(fl, which)})
    else:
        first = (tangency_system(f1, f2, ph), ContactKind.SURFACE, 0, set())
    xr, res, out = _refine(f1, f2, first[0], x0, first[3], opts)
    if xr is not None and out is None and xr[4] >= sampled - 1e-12:
        return xr, first[1], first[2], res, True
    if xr is not None and out is not None:  # left a working area through one boundary: contact on it
        fo, bo = out
        if which >= 0 and fo != fl:
            b1, b2 = (which, bo) if fl == 1 else (bo, which)
            second = (edge_edge_system(f1, f2, ph, b1, b2), ContactKind.EDGE, 1000 + 10 * b1 + b2, {(1, b1), (2, b2)})
        elif which < 0:
            second = (edge_system(f1, f2, ph, fo, bo), ContactKind.EDGE, 10 * fo + bo, {(fo, bo)})
        else:
            second = None
        if second is not None:
            x2, res2, out2 = _refine(f1, f2, second[0], xr, second[3], opts)
            if x2 is not None and out2 is None and x2[4] >= sampled - 1e-12:
                return x2, second[1], second[2], res2, True
    return x0, first[1], first[2], 0.0, False


def _refine(f1, f2, system, x0: np.ndarray, on: set, opts: TCAOptions):
    """Newton on `system` from x0: (x, residual, None) if converged inside both working areas (the
    boundaries `on` = {(flank, boundary)} it lies on excepted), (x, residual, (flank, boundary)) if it
    converged outside exactly one boundary, (None, nan, None) otherwise."""
    with np.errstate(divide="ignore", invalid="ignore"):
        r = newton(system, x0[None], NewtonOptions(tol=opts.tol, maxiter=40), raise_on_failure=False)
    xr = r.x[0]
    if not (r.converged[0] and r.residual[0] <= opts.max_residual):
        return None, float("nan"), None
    with np.errstate(divide="ignore", invalid="ignore"):  # a run-off to a singular point of a flank
        c = np.stack([f1.constraints(f1.surface.evaluate(xr[0], xr[1]), xr[0]),
                      f2.constraints(f2.surface.evaluate(xr[2], xr[3]), xr[2])])
    if not np.all(np.isfinite(c)):
        return None, float("nan"), None
    for fl, b in on:
        if b < 4:
            c[fl - 1, b] = 0.0
    bad = np.argwhere(c > opts.area_tol)
    if not len(bad):
        return xr, float(r.residual[0]), None
    if len(bad) == 1:
        return xr, float(r.residual[0]), (int(bad[0, 0]) + 1, int(bad[0, 1]))
    return None, float("nan"), None
