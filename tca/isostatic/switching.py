r"""Switching of the contacting pairs by the backlash of neighbouring teeth (Eqs. 3.19-3.20), planar.

With the poses of a solved position, the backlash of the pairs before and after the contacting pair of
every mesh is computed (:func:`tca.isostatic.subtrain.backlash_solve`). A neighbour with negative backlash
interferes, so it is the contacting pair; pairs within ``tie_tol`` of the smallest backlash touch
together (involute gears) and the one deepest inside both working areas is kept. Neighbours whose
common normal falls outside the working areas are no candidates; their bounded teeth could only touch at
an end of a working area, which is checked (:func:`tca.isostatic.subtrain.corner_gap`) and reported as edge
contact (not modelled by the planar TCA).
"""

from __future__ import annotations

import numpy as np

from tca.errors import GeometryError
from tca.isostatic.flanks import PlacedTeeth
from tca.isostatic.subtrain import (BODY_RING, Members, Poses, backlash_solve, corner_gap, line_crossing, mate_tooth,
                             subtrain_eval)

__all__ = ["switch_pairs"]


def switch_pairs(train, fl, m: Members, x, opts, wpos):
    """Backlash of the neighbouring pairs (Eqs. 3.19-3.20) and the new contacting pairs.

    Returns (teeth (M, 4), x guesses (M, 6), changed (M,), backlash (M, 2, 2)).
    """
    M = len(x)
    Np = train.n_planets
    F, J, P, mesh = subtrain_eval(train, fl, m, x, full=True)
    teeth = m.teeth.copy()
    xn = x.copy()
    changed = np.zeros(M, bool)
    backlash = np.full((M, 2, 2), np.nan)
    specs = (  # (mesh, flank a, pose a, tooth col a, u col a, flank b, pose b, body b, centre b, col b, u col b)
        (0, fl.sun, (P.As, P.cs), 0, 0, fl.planet_s, (P.Ap, P.cp), "planet", P.Op, 1, 1, mesh["point_s"], mesh["normal_s"]),
        (1, fl.planet_r, (P.Ap, P.cp), 2, 2, fl.ring, (P.Ar, P.cr), "ring", m.T[:, BODY_RING], 3, 3, mesh["point_r"],
         mesh["normal_r"]),
    )
    names = ("sun-planet", "planet-ring")
    for (k, fa, (Aa, ca), ta, ua_c, fb, (Ab, cb), body_b, Ob, tb, ub_c, c0, nu) in specs:
        ka = np.concatenate([m.teeth[:, ta] - 1, m.teeth[:, ta] + 1])
        A2a, c2a = np.concatenate([Aa, Aa]), np.concatenate([ca, ca])
        A2b, c2b = np.concatenate([Ab, Ab]), np.concatenate([cb, cb])
        P2 = _stack_poses(P)
        star = fa.place(A2a, c2a, ka, np.zeros(2 * M))[0]
        kb = mate_tooth(train, fb, P2, body_b, np.concatenate([Ob, Ob]), star)
        c02, nu2 = np.concatenate([c0, c0]), np.concatenate([nu, nu])
        ua0 = line_crossing(fa, A2a, c2a, ka, c02, nu2)
        ub0 = line_crossing(fb, A2b, c2b, kb, c02, nu2)
        teeth_a, teeth_b = PlacedTeeth(fa, A2a, c2a, ka), PlacedTeeth(fb, A2b, c2b, kb)
        ua, ub, s, ok, mg = backlash_solve(teeth_a, teeth_b, ua0, ub0, opts.tol)
        s = np.where(ok, s, np.nan).reshape(2, M).T  # (M, 2): previous, next
        mg = mg.reshape(2, M).T
        okk = ok.reshape(2, M).T
        backlash[:, k] = s
        cur_margin = mesh["margin"][:, k]
        S = np.stack([s[:, 0], np.zeros(M), s[:, 1]], -1)
        valid = np.stack([okk[:, 0] & (mg[:, 0] >= -opts.area_tol), cur_margin >= -opts.area_tol,
                          okk[:, 1] & (mg[:, 1] >= -opts.area_tol)], -1)
        marg = np.stack([mg[:, 0], cur_margin, mg[:, 1]], -1)
        Sv = np.where(valid, S, np.inf)
        smin = Sv.min(-1)
        none = ~np.isfinite(smin)
        if none.any():
            i = int(np.flatnonzero(none)[0])
            raise GeometryError(train.planet.name, "contact outside the working areas",
                                f"{wpos(i // Np)}, planet {i % Np + 1}, {names[k]} mesh: the contact point and those "
                                "of the neighbouring pairs leave the working areas (edge contact, not modelled by the "
                                "planar TCA)")
        # Neighbours whose common normal lies outside the working areas (or does not exist: extended profiles
        # past the base circle) are no candidates. The bounded teeth could still touch, but then an end of a
        # working area (tip or start of the fillet) enters the mate (the deepest point of two smooth profiles
        # is a common normal or an end point): that is edge contact, which the planar TCA does not model.
        inval = ~valid[:, [0, 2]]
        if inval.any():
            rows, cols = np.nonzero(inval)
            idx = rows + cols * M
            for own, mate in ((teeth_a, teeth_b), (teeth_b, teeth_a)):
                fo = own.flank
                for ulim in (fo.u_form, fo.u_tip):
                    gap, _ = corner_gap(own.take(idx), np.full(len(idx), ulim), mate.take(idx))
                    bad = gap < -opts.tie_tol
                    if bad.any():
                        i = int(rows[np.argmax(bad)])
                        where_end = "start of the fillet" if ulim == fo.u_form else "tip"
                        raise GeometryError(train.planet.name, "edge contact",
                                            f"{wpos(i // Np)}, planet {i % Np + 1}, {names[k]} mesh: the {where_end} of "
                                            f"the {fo.gear.name}'s flank of a neighbouring pair enters the mate by "
                                            f"{-gap[bad].min() * 1e3:.3f} um (edge contact, not modelled by the planar "
                                            "TCA)")
        tie = valid & (S <= smin[:, None] + opts.tie_tol)
        choice = np.argmax(np.where(tie, marg, -np.inf), -1)
        edge = ~valid[:, 1] & (choice != 1) & (S[np.arange(M), choice] > opts.tie_tol)
        if edge.any():
            i = int(np.flatnonzero(edge)[0])
            raise GeometryError(train.planet.name, "edge contact",
                                f"{wpos(i // Np)}, planet {i % Np + 1}, {names[k]} mesh: the contact leaves the "
                                f"working areas while the next pair still has {S[i, choice[i]] * 1e3:.3f} um backlash "
                                "(tip edge contact, not modelled by the planar TCA)")
        for d, col in ((0, 0), (2, 1)):
            sel = choice == d
            if sel.any():
                idx = np.flatnonzero(sel) + col * M
                rows = np.flatnonzero(sel)
                teeth[rows, ta] = ka[idx]
                teeth[rows, tb] = kb[idx]
                xn[rows, ua_c] = ua[idx]
                xn[rows, ub_c] = ub[idx]
                changed[rows] = True
    return teeth, xn, changed, backlash


def _stack_poses(P: Poses) -> Poses:
    """The poses twice over (for the two neighbours of every member)."""
    return Poses(*(np.concatenate([getattr(P, f), getattr(P, f)]) for f in
                   ("As", "cs", "Ap", "cp", "Op", "Tc", "Ar", "cr", "q", "a")))
