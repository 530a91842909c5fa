r"""Tooth contact analysis of a gear pair over several cycles of meshing (Eqs. 1.9–1.14).

Procedure (section 1.4):

1. The reference pair of teeth (tooth 0 of each gear) is solved over a grid of :math:`\phi_1`
   commensurate with the angular pitch :math:`2\pi/N_1`: a coarse continuation from the pitch
   point outward (Newton from the previous solutions, quadratic predictor), then the fine grid in
   one batched Newton solve from spline-interpolated guesses (Eq. 1.12).
2. Each point is classified. If the point of tangency lies inside both working areas it is the
   contact; otherwise the bounded surfaces first touch along a boundary (edge contact) or at a
   corner of a working area, found by :mod:`tca.contact.systems`; the first touch is the largest
   :math:`\phi_2` among the valid ones. A point of tangency below the start of the fillet marks
   contact with the fillet (interference).
3. Neighbouring pairs of identical teeth repeat the reference pair shifted by one pitch, so the
   transmission function of the drive is :math:`\phi_2(\phi_1) = \max_k \phi_2^{(k)}(\phi_1)`:
   the pair with the largest :math:`\Delta\phi_2` is in contact (the others have backlash).
   Transmission errors follow Eq. (1.13), :math:`\Delta\phi_2 = \phi_2 - (N_1/N_2)\phi_1`, in the
   absolute sense of :mod:`tca.pair.gear_pair`; paths of contact are Eq. (1.14). With run-out (Eqs.
   3.5–3.6) the pairs are not shifted copies of the reference pair: each is solved with the
   eccentricity at its own angle (:mod:`tca.pair.runout`), and the transitions are interpolated
   on the grid.

The algorithms live in one module each: :mod:`tca.pair.result` (options, contact kinds, result
types), :mod:`tca.pair.reference` (continuation of the reference pair), :mod:`tca.pair.bounded`
(edge and corner contacts of the bounded surfaces), :mod:`tca.pair.transitions` (transitions and
extremes); this module runs them in order.

Every converged point is verified: max residual < ``max_residual`` (1e-10 mm by default), or a
:class:`~tca.errors.ConvergenceError` names the position.
"""

from __future__ import annotations

import math
import time

import numpy as np

from tca.contact.ellipse import contact_ellipse
from tca.errors import GeometryError
from tca.pair.gear_pair import GearPair
from tca.pair.memo import Memo
from tca.pair.bounded import bounded_pass
from tca.pair.reference import solve_reference_pair
from tca.pair.relief import relief_pass
from tca.pair.runout import candidate_table, has_runout
from tca.pair.result import ContactKind, PairTCAResult, ReferencePairSolution, TCAOptions, ellipse_outlines
from tca.pair.transitions import Branches, extremes, transitions
from tca.units import ARCSEC

__all__ = ["TCAOptions", "ContactKind", "ReferencePairSolution", "PairTCAResult", "run_pair_tca", "pair_tca_memo", "solve_reference_pair", "bounded_pass", "ellipse_outlines",
           "ARCSEC"]



# ---------------------------------------------------------------------------------------------


# weights of the preferred point (centre of flank 1's working area) in the first Newton phase


# ---------------------------------------------------------------------------------------------
def run_pair_tca(pair: GearPair, opts: TCAOptions = TCAOptions()) -> PairTCAResult:
    """TCA of a gear pair over opts.cycles cycles of meshing; see the module docstring.

    Computed once per process for a pair and options of equal value (:mod:`tca.pair.memo`: the last
    eight results are kept, read-only; ``elapsed`` is the time of the computation)."""
    return _MEMO(pair, opts)


def _compute_pair_tca(pair: GearPair, opts: TCAOptions) -> PairTCAResult:
    t0 = time.perf_counter()
    f1, f2 = pair.flanks()
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
    rjc = np.clip(rj + J, 0, 2 * J)
    if has_runout(pair):
        # every pair of teeth sees the eccentricity at its own angle (tca.pair.runout)
        tab = candidate_table(pair, ref, ks, rjc, valid, opts)
        turned, kind_all, x_all, res_all, where_all = tab.pairs, tab.kind, tab.x, tab.residual, tab.where
        te_c = tab.te
        cand = np.where(valid, te_c, -np.inf)
    else:
        bounded_pass(pair, ref, np.flatnonzero(need), opts)
        relief_pass(pair, ref, opts)  # end relief: relieved zones and ridges that touch first
        te_ref = ref.phi2 - ratio * ref.phi1
        cand = np.where(valid, te_ref[rjc], -np.inf)
    if not np.all(np.isfinite(cand.max(1))):
        i = int(np.flatnonzero(~np.isfinite(cand.max(1)))[0])
        raise GeometryError("pair", "no contact",
                            f"no pair of teeth is in contact at phi1 = "
                            f"{math.degrees(ref.phi1[J] + out_j[i] * (2 * math.pi / pair.gear1.teeth) / s):.4f} deg "
                            "(contact ratio below 1, or working areas that do not overlap)")
    best = cand.max(1, keepdims=True)
    tie = cand >= best - 1e-10
    kind_c = np.where(valid, kind_all if has_runout(pair) else ref.kind[rjc], 0)
    pref = np.where(tie, (kind_c == ContactKind.SURFACE) * 1e6 - np.abs(rj), -np.inf)
    a = np.argmax(pref, 1)
    jr = rj[np.arange(len(out_j)), a] + J
    pitch1 = 2 * math.pi / pair.gear1.teeth
    kk = ks[a]
    phi1 = ref.phi1[J] + out_j * (pitch1 / s)
    rows = np.arange(len(out_j))
    te = cand[rows, a]
    phi2 = te + ratio * phi1
    kind = kind_c[rows, a]
    if np.any(kind == ContactKind.FILLET):
        i = int(np.flatnonzero(kind == ContactKind.FILLET)[0])
        raise GeometryError("pair", "interference",
                            f"at phi1 = {math.degrees(phi1[i]):.4f} deg the tooth in contact touches below the start of "
                            f"the fillet of its mate (tip interference); reduce the addendum or change the profile shifts")
    if has_runout(pair):
        X, residual, where = x_all[rows, a], res_all[rows, a], where_all[rows, a]
        # contact points with each pair's own placement of the eccentric bodies
        fs = [turned[int(k)].flanks() for k in kk]
        w1 = _stack_points([f[0].world(X[i:i + 1, 0], X[i:i + 1, 1], ref.phi1[jr[i:i + 1]])[0] for i, f in enumerate(fs)])
        w2 = _stack_points([f[1].world(X[i:i + 1, 2], X[i:i + 1, 3], X[i:i + 1, 4])[0] for i, f in enumerate(fs)])
        l1 = _stack_points([f[0].world(X[i:i + 1, 0], X[i:i + 1, 1], ref.phi1[jr[i:i + 1]])[1] for i, f in enumerate(fs)])
        l2 = _stack_points([f[1].world(X[i:i + 1, 2], X[i:i + 1, 3], X[i:i + 1, 4])[1] for i, f in enumerate(fs)])
    else:
        X, residual, where = ref.x[jr], ref.residual[jr], ref.where[jr]
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
    trans, trans_te = transitions(pair, (f1, f2), ref, opts, Branches(phi1, cand, kind_c, ks, a),
                                  exact=not has_runout(pair))
    ext = extremes(te, kk, kind, trans_te)
    return PairTCAResult(
        pair, opts, phi1, phi2, te, kk, kind, w1.r,
        X[:, :4], l1.r, l2.r, ea, eb, eang, residual, ref, np.array(trans), time.perf_counter() - t0,
        where, np.array(trans_te), ext,
    )


def _stack_points(pts):
    """Concatenate SurfacePoints records of single points."""
    return type(pts[0])(*(np.concatenate(f) for f in zip(*pts)))


_MEMO = Memo(_compute_pair_tca, size=8)


def pair_tca_memo() -> Memo:
    """The memo of :func:`run_pair_tca` (to share it between processes: :meth:`tca.pair.memo.Memo.share`)."""
    return _MEMO
