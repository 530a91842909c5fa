r"""Pairs of teeth of a gear pair with run-out: each pair sees the eccentricity at its own angle (Eqs. 3.5–3.6).

Without run-out, neighbouring pairs of teeth repeat the reference pair shifted by one pitch
(:mod:`tca.pair.analysis`, step 3). An eccentric toothed body breaks that symmetry: tooth :math:`k` of a
gear turned by :math:`\phi` is placed by :math:`R_m(\phi)\,[R(2\pi k/N)\,x + e]`, with :math:`e` the
eccentricity fixed in the gear frame (:meth:`tca.geometry.gear.Gear.tooth_transform`). Candidate pair
:math:`k` of the pair TCA (tooth :math:`-k` of both gears) at :math:`\phi_i` is therefore

.. math::
    R_m(\phi_i)\,[R(-k p_i)\,x + e] = R_m(\phi_i - k p_i)\,[x + R(k p_i)\,e],

the reference tooth at the shifted angle :math:`\phi_i - k p_i` of a gear whose run-out phase is
turned by :math:`+k p_i` (:math:`p_i = 2\pi/N_i`). The eccentricity thus keeps its direction in
space over one revolution instead of restarting at every tooth, and the TE of an eccentric gear
driving a perfect one is once per revolution of the eccentric gear, of amplitude
:math:`e / r_{b2}` in :math:`\Delta\phi_2` (the body shifted along the line of action by
:math:`e\sin(\cdot)`, Eq. 3.6).

Each candidate pair is solved from the reference pair's solution at the same reference index
(Newton; the eccentricity is a perturbation of the reference geometry), classified against both
working areas like the reference pair, and searched for edge contact where its tangency lies
outside them and could be the pair in contact (:func:`tca.pair.bounded.bounded_pass`, called by
:func:`tca.pair.analysis.run_pair_tca` as for the reference pair).
"""

from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from tca.contact.systems import tangency_system
from tca.errors import ConvergenceError
from tca.numerics.newton import NewtonOptions, newton
from tca.pair.gear_pair import GearPair
from tca.pair.bounded import bounded_pass
from tca.pair.reference import classify_tangency, in_domain  # the reference pair's classification
from tca.pair.relief import relief_pass
from tca.pair.result import ContactKind, ReferencePairSolution, TCAOptions

__all__ = ["has_runout", "turned_pair", "solve_candidate_pair", "CandidateTable", "candidate_table"]


def has_runout(pair: GearPair) -> bool:
    """True when either gear's toothed body is eccentric."""
    return pair.gear1.runout > 0.0 or pair.gear2.runout > 0.0


def turned_pair(pair: GearPair, k: int) -> GearPair:
    """The pair whose reference teeth stand for candidate pair k: run-out phases turned by +k pitches."""
    if k == 0:
        return pair
    return dataclasses.replace(pair, gear1=_turned(pair.gear1, k), gear2=_turned(pair.gear2, k))


def _turned(g, k: int):
    """Gear g with its run-out phase turned by k pitches; shares g's checked geometry and caches.

    The run-out does not enter the tooth surfaces, working areas or design checks (only
    :meth:`~tca.geometry.gear.Gear.tooth_transform`), so a shallow copy is the same gear, validated.
    """
    if g.runout == 0.0:
        return g
    c = copy.copy(g)
    object.__setattr__(c, "runout_phase", g.runout_phase + k * 2 * math.pi / g.teeth)
    return c


def solve_candidate_pair(pair: GearPair, ref: ReferencePairSolution, k: int, idx: np.ndarray,
                         opts: TCAOptions) -> ReferencePairSolution:
    """Contact of candidate pair k at reference indices idx (elsewhere: no contact).

    ``ref`` is the reference pair of the pair *without* turned run-out (its solution is the
    Newton guess); the returned solution lives on the same grid as ``ref``.
    """
    pk = turned_pair(pair, k)
    f1, f2 = pk.flanks()
    n = len(ref.j)
    idx = np.asarray(idx, int)
    X = np.full((n, 5), np.nan)
    tan_ok = np.zeros(n, bool)
    t = idx[ref.tangency[idx]]
    if len(t):
        r = newton(tangency_system(f1, f2, ref.phi1[t]), ref.x[t], NewtonOptions(tol=opts.tol, maxiter=40),
                   raise_on_failure=False)
        good = r.converged & in_domain(f1, f2, r.x)
        X[t[good]], tan_ok[t[good]] = r.x[good], True
    kind = np.zeros(n, int)
    phi2 = np.full(n, -np.inf)
    resid = np.full(n, np.nan)
    it = np.flatnonzero(tan_ok)
    if len(it):
        Fv, _ = tangency_system(f1, f2, ref.phi1[it])(X[it], np.arange(len(it)))
        resid[it] = np.abs(Fv).max(-1)
        if np.any(resid[it] > opts.max_residual):
            q = it[np.argmax(resid[it])]
            raise ConvergenceError(f"pair TCA with run-out (pair {k})", f"phi1 = {math.degrees(ref.phi1[q]):.6f} deg",
                                   float(resid[q]), 0)
    classify_tangency(f1, f2, X, tan_ok, opts.area_tol, kind, phi2)
    # positions the reference pair found out of mesh stay out of mesh (20 um of eccentricity does
    # not bring a pair a module closer); positions not asked for are marked out of mesh too
    oom = ref.out_of_mesh.copy()
    asked = np.zeros(n, bool)
    asked[idx] = True
    oom |= ~asked
    sol = ReferencePairSolution(ref.phi1, phi2, np.where(np.isnan(X), ref.x, X), kind, resid, np.zeros(n, int), ref.j,
                                0, tan_ok, oom)
    return sol


@dataclass(frozen=True, eq=False)
class CandidateTable:
    """Contact of every candidate pair (columns, ``ks``) at every output position (rows) of a pair TCA."""

    pairs: dict  # k -> the turned GearPair standing for candidate pair k
    te: np.ndarray  # (n, K) Delta phi2 [rad], -inf where no contact
    kind: np.ndarray  # (n, K) ContactKind
    x: np.ndarray  # (n, K, 5) u1, v1, u2, v2, phi2
    residual: np.ndarray  # (n, K) [mm]
    where: np.ndarray  # (n, K) boundary codes of edge and corner contacts


def candidate_table(pair: GearPair, ref: ReferencePairSolution, ks: np.ndarray, rjc: np.ndarray, valid: np.ndarray,
                    opts: TCAOptions) -> CandidateTable:
    """Candidate pairs ks at the reference indices rjc (n, K) where valid, each with its own run-out.

    Edge contacts are searched, as for the reference pair, only where a pair's tangency lies above
    the envelope of the others (bounded contacts can only lower a pair's phi2).
    """
    n = rjc.shape[0]
    ratio = pair.ratio
    turned = {int(k): turned_pair(pair, int(k)) for k in ks}
    col = [solve_candidate_pair(pair, ref, int(k), np.unique(rjc[valid[:, q], q]), opts) if valid[:, q].any() else None
           for q, k in enumerate(ks)]

    def pick(attr, fill):
        return np.stack([getattr(c, attr)[rjc[:, q]] if c is not None else np.full(n, fill) for q, c in enumerate(col)], 1)

    env = np.where(valid, pick("phi2", -np.inf) - ratio * ref.phi1[rjc], -np.inf).max(1)
    for q, c in enumerate(col):
        if c is None:
            continue
        jj = rjc[:, q]
        te_t = np.where(c.tangency, c.x[:, 4] - ratio * c.phi1, np.inf)[jj]
        sel = valid[:, q] & (c.kind[jj] == ContactKind.NONE) & ~c.out_of_mesh[jj] & (
            (te_t > env + 1e-10) | ~np.isfinite(env))
        bounded_pass(turned[int(ks[q])], c, np.unique(jj[sel]), opts)
        relief_pass(turned[int(ks[q])], c, opts)
    x = np.stack([c.x[rjc[:, q]] if c is not None else ref.x[rjc[:, q]] for q, c in enumerate(col)], 1)
    return CandidateTable(turned, pick("phi2", -np.inf) - ratio * ref.phi1[rjc], pick("kind", 0), x,
                          pick("residual", np.nan), pick("where", 0))
