r"""First touch of flanks with end relief: the relieved zones searched by sampling, the ridge as an inner boundary.

An end relief (:mod:`tca.end_relief`) makes a flank piecewise smooth in :math:`z`: unmodified in the
middle, relieved from :math:`z_s` to the face end. Under a misalignment the pair then touches
where the tangency solve of :mod:`tca.pair_reference` does not look:

* inside a relieved zone, at a point of tangency far from the start guess of the continuation
  (the middle part of a misaligned flank has no tangency at all, so Newton has nowhere to go);
* on the ridge :math:`z = z_s` of a linear relief, where the slope of the flank jumps: no point
  of tangency exists there, the ridge touches the other flank like an edge (section 1.4, step 2:
  a boundary curve tangent to the other surface), so it is treated as an inner boundary with the
  edge equations of :mod:`tca.contact` (:math:`c = z - z_s` on the relieved side).

For every position, points of each relieved flank on the ridge line and on levels across its
relieved zones (``levels`` x ``samples`` points) are put on the other flank by turning gear 2 (three
position equations, :func:`tca.contact.corner_system`, as :mod:`tca.pair_bounded` does for the
boundaries). The first touch is the largest :math:`\phi_2`; where it beats what the pair TCA knows (the
contact found, or, where the edge search was skipped, the tangency of the extended surfaces, an upper
bound of the bounded contact on which the sampled points also lie: the ridge crossing the contact
line of an aligned pair is no news), it replaces it: refined by the edge equations on the ridge of a linear relief (kind EDGE,
boundary code ``10 flank + 4`` for the ridge at the z_max end, ``+ 5`` at the z_min end), otherwise by
the tangency equations (kind SURFACE). A maximum that the refinement cannot confirm stays the sampled
point (it lies on both flanks; its :math:`\phi_2` is below the true first touch by at most the
sampling error, reported in the residual-free record as the sampled value).
"""

from __future__ import annotations

import numpy as np

import math

from .contact import corner_system, edge_system, tangency_system
from .errors import ConvergenceError
from .newton import newton
from .pair import GearPair
from .pair_bounded import _tip_points, _u_of_radius
from .pair_result import ContactKind, ReferencePairSolution, TCAOptions, _flanks

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
    fo = (f1, f2)[2 - fl]
    flat = uv.reshape(-1, 2)
    ph1 = np.repeat(phi1, m)
    ph2 = np.repeat(ph2g, m)
    if fl == 1:
        pw, _, _ = f1.world(flat[:, 0], flat[:, 1], ph1)
        Rf, _, tf, _ = f2.frame(ph2)
    else:
        pw, _, _ = f2.world(flat[:, 0], flat[:, 1], ph2)
        Rf, _, tf, _ = f1.frame(ph1)
    loc = np.einsum("nji,nj->ni", Rf, pw.r - tf)
    guess = np.stack([_u_of_radius(fo)(np.hypot(loc[:, 0], loc[:, 1])), loc[:, 2], ph2], -1)
    rr = newton(corner_system(f1, f2, ph1, fl, flat), guess, tol=opts.tol, maxiter=15, raise_on_failure=False,
                max_backtracks=6)
    con = fo.constraints(fo.surface.evaluate(rr.x[:, 0], rr.x[:, 1]), rr.x[:, 0])
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
    u_tip = _tip_points(fi, np.full(len(zl), ar.u_tip), zl)[:, 0]
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


def relief_pass(pair: GearPair, ref: ReferencePairSolution, opts: TCAOptions, levels: int = 8,
                samples: int = 11) -> None:
    """Replace the contact of positions where a relieved zone or a ridge touches first (in place)."""
    f1, f2 = _flanks(pair)
    flanks = (f1, f2)
    relieved = [fl for fl in (1, 2) if flanks[fl - 1].gear.end_relief is not None]
    if not relieved:
        return
    sel = np.flatnonzero(~ref.out_of_mesh)
    if not len(sel):
        return
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
    done: dict[int, dict[int, np.ndarray]] = {fl: {} for fl in relieved}  # refined x per flank and position
    failed = []
    for q in upd:
        i = sel[q]
        found = []
        for fl in relieved:
            val, x, code, end = (c[q] for c in cands[fl])
            if not np.isfinite(val):
                continue
            res = _settle(f1, f2, ref.phi1[i], x, fl, int(code), int(end), val, opts)
            if res is None and done[fl]:  # second chance: from the refined contact of the nearest position
                nb = min(done[fl], key=lambda j: abs(j - i))
                x0 = done[fl][nb].copy()
                x0[4] += ratio * (ref.phi1[i] - ref.phi1[nb])
                res = _settle(f1, f2, ref.phi1[i], x0, fl, int(code), int(end), val, opts)
            if res is not None:
                done[fl][i] = res[0]
                found.append(res)
        if not found:
            failed.append(i)
            continue
        x, kind, where, resid = max(found, key=lambda f: f[0][4])
        if x[4] > ref.phi2[i] + 1e-12:
            ref.x[i], ref.kind[i], ref.where[i], ref.phi2[i], ref.residual[i] = x, kind, where, x[4], resid
    if failed:
        i = failed[0]
        raise ConvergenceError("end-relief contact (refinement of the sampled first touch)",
                               f"phi1 = {math.degrees(ref.phi1[i]):.6f} deg", float("nan"), 40)


def _settle(f1, f2, phi1: float, x0: np.ndarray, fl: int, code: int, end: int, sampled: float, opts: TCAOptions):
    """The contact near a sampled touch x0 of relieved flank fl: (x, kind, where, residual) or None.

    The ridge of a linear relief meeting the tip or the fillet limit is a corner, exact as sampled; the
    ridge elsewhere, or the tip / fillet limit across a relieved zone, is an edge (edge equations);
    a sample inside a relieved zone is refined by the tangency equations. A refined contact must touch
    no later than the sample (phi2 >= sampled).
    """
    ridge = bool(code) and (f1, f2)[fl - 1].gear.end_relief.power == 1
    if ridge and end >= 0:
        return x0, ContactKind.CORNER, 100 * fl + 10 * code + (9 if end else 0), 0.0
    which = code if ridge else (-1 if end < 0 else end)
    xr, res = _refine(f1, f2, phi1, x0, fl, which, opts)
    if xr is None or xr[4] < sampled - 1e-12:
        return None
    return (xr, ContactKind.EDGE, 10 * fl + which, res) if which >= 0 else (xr, ContactKind.SURFACE, 0, res)


def _refine(f1, f2, phi1: float, x0: np.ndarray, fl: int, which: int, opts: TCAOptions):
    """Tangency (which = -1) or edge equations (boundary `which` of flank fl, :func:`tca.contact.boundary_derivs`)
    from x0; (x, residual) if converged inside both areas, else (None, nan)."""
    ph = np.array([phi1])
    system = edge_system(f1, f2, ph, fl, which) if which >= 0 else tangency_system(f1, f2, ph)
    r = newton(system, x0[None], tol=opts.tol, maxiter=40, raise_on_failure=False)
    xr = r.x[0]
    if not (r.converged[0] and r.residual[0] <= opts.max_residual):
        return None, float("nan")
    c1 = f1.constraints(f1.surface.evaluate(xr[0], xr[1]), xr[0])
    c2 = f2.constraints(f2.surface.evaluate(xr[2], xr[3]), xr[2])
    if np.all(c1 <= opts.area_tol) and np.all(c2 <= opts.area_tol):
        return xr, float(r.residual[0])
    return None, float("nan")
