r"""Contact of bounded tooth surfaces: edge and corner contacts where the point of tangency leaves a working area.

The bounded surfaces first touch along a boundary of a working area (edge contact: the boundary
curve of one flank tangent to the other surface) or at a corner (two boundary curves); the first
touch is the largest :math:`\phi_2` among the valid candidates (section 1.4, step 2). The three
boundaries of a flank are projected in one batched Newton solve per level.
"""

from __future__ import annotations

import math

import numpy as np

from tca.contact.systems import PlacedFlank, corner_system, edge_edge_system, edge_system
from tca.errors import ConvergenceError
from tca.numerics.newton import NewtonOptions, NewtonResult, newton
from tca.pair.gear_pair import GearPair
from tca.pair.result import ContactKind, ReferencePairSolution, TCAOptions

__all__ = ["bounded_pass", "boundary_curve", "onto_other_flank", "tip_points"]


def bounded_pass(pair: GearPair, ref: "ReferencePairSolution", sel: np.ndarray, opts: TCAOptions) -> None:
    """Edge, edge-to-edge and corner contact at reference positions `sel` (tangency not inside); in place."""
    sel = np.asarray(sel, int)
    if not len(sel):
        return
    f1, f2 = pair.flanks()
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


def boundary_curve(flank: PlacedFlank, b: int):
    """Boundary b (1 tip, 2 z_max, 3 z_min) of a flank's working area: the range (t0, t1) of its parameter
    (z for the tip, u for a face end) [mm] and the map t -> (u, v) (..., 2) on it."""
    return _boundary_param(flank, b)


def _boundary_param(flank: PlacedFlank, b: int):
    """Range (t0, t1) of the parameter along boundary b, and a map t -> (u, v) on it."""
    ar = flank.gear.area(flank.side)
    if b == 1:  # tip: parameter is z
        return (ar.z_min, ar.z_max), lambda t: tip_points(flank, np.full(np.shape(t), ar.u_tip), t)
    zb = ar.z_max if b == 2 else ar.z_min
    u_end = tip_points(flank, np.array([ar.u_tip]), np.array([zb]))[0, 0]
    return (ar.u_form, u_end), lambda t: np.stack([np.asarray(t, float), np.full(np.shape(t), zb)], -1)


def onto_other_flank(f1: PlacedFlank, f2: PlacedFlank, fl: int, uv: np.ndarray, ph1: np.ndarray, ph2: np.ndarray,
                     tol: float, u_of_r=None):
    """Points uv (N, 2) [mm] of flank fl (1 or 2) put on the other flank by turning gear 2 (three position
    equations, :func:`tca.contact.systems.corner_system`), gear 1 at ph1 (N,) and gear 2 starting at ph2 (N,) [rad].

    Returns the :class:`tca.numerics.newton.NewtonResult` (x: u, v on the other flank and phi2; not raising where a
    point runs off) and the other flank's working-area constraints (N, 4). ``u_of_r``: the other flank's
    u(radius) for the guesses (:func:`_u_of_radius`; built here when not given).
    """
    fo = (f1, f2)[2 - fl]
    if fl == 1:
        pw, _, _ = f1.world(uv[:, 0], uv[:, 1], ph1)
        Rf, _, tf, _ = f2.frame(ph2)
    else:
        pw, _, _ = f2.world(uv[:, 0], uv[:, 1], ph2)
        Rf, _, tf, _ = f1.frame(ph1)
    loc = np.einsum("nji,nj->ni", Rf, pw.r - tf)
    u_of_r = u_of_r or _u_of_radius(fo)
    g = np.stack([u_of_r(np.hypot(loc[:, 0], loc[:, 1])), loc[:, 2], ph2], -1)
    rr = newton(corner_system(f1, f2, ph1, fl, uv), g, NewtonOptions(tol=tol, maxiter=15, max_backtracks=6),
                raise_on_failure=False)
    return rr, fo.constraints(fo.surface.evaluate(rr.x[:, 0], rr.x[:, 1]), rr.x[:, 0])


def _bounded_contacts(pair, f1, f2, phis, sel, phi2_guess, opts, samples: int = 9):
    """First touch of the bounded flanks along their boundaries, where tangency is not inside.

    For every physical boundary (tip, z_max, z_min) of both flanks, points sampled along it are
    put on the other flank by turning gear 2 (three position equations, well conditioned); the
    first touch along that boundary is the largest phi2 among the points that land inside the
    other working area. An interior maximum is refined by the edge-tangency equations
    (:func:`tca.contact.systems.edge_system`); a maximum at an end of the boundary is a corner contact.
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
            rr, con = onto_other_flank(f1, f2, fl, uv, ph1, ph2, opts.tol, u_of_r)
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
                ree = newton(edge_edge_system(f1, f2, phis[sel][pi], *bb), g, NewtonOptions(tol=opts.tol, maxiter=40),
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
                re = newton(edge_system(f1, f2, phis[sel][ii], fl, b), cand_x[ii],
                            NewtonOptions(tol=opts.tol, maxiter=40), raise_on_failure=False)
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


def tip_points(fi, u, v):
    """(u, v) on the tip boundary of flank fi at axial positions v (vectorized Newton in u)."""
    from tca.contact.systems import boundary_derivs

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

