r"""Transitions between pairs of teeth: where the next pair's :math:`\Delta\phi_2` overtakes the current one, and the TE extremes.

Neighbouring pairs repeat the reference pair shifted by one pitch; the transmission function is
:math:`\max_k \phi_2^{(k)}(\phi_1)` (section 1.4, step 3), so a transition is the crossing of two
branches, located by Newton on the difference of the two pairs' tangency systems.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.contact.systems import tangency_system
from tca.numerics.newton import NewtonOptions, newton
from tca.pair.result import ContactKind

__all__ = ["Branches", "transitions", "extremes"]


@dataclass(frozen=True, eq=False)
class Branches:
    """Every pair of teeth within reach on the output grid of a pair TCA (section 1.4, step 3).

    Column q holds the pair at tooth offset ``offsets[q]`` (tooth -k of each gear), whose contact is
    the reference pair's at grid index j - k s; ``te`` is -inf where that pair is out of reach.
    """

    phi1: np.ndarray  # (n,) driving-gear angles [rad]
    te: np.ndarray  # (n, K) Δφ2 of each pair [rad]
    kind: np.ndarray  # (n, K) ContactKind of each pair
    offsets: np.ndarray  # (K,) tooth offset k of each column
    active: np.ndarray  # (n,) column of the pair in contact (largest Δφ2)


def transitions(pair, flanks: tuple, ref, opts, br: Branches, exact: bool = True) -> tuple[list, list]:
    """phi1 and TE at each change of the pair in contact (exact where both contacts are surface contacts).

    Between grid points i and i+1 the pair in contact changes from ka to kb; the transition is the
    root of g(phi) = TE_ka(phi) - TE_kb(phi), where TE_k(phi) is the reference pair's TE at
    phi - k p (p the angular pitch). Regula falsi (Illinois) on batched tangency solves.
    With ``exact=False`` (pairs that are not shifted copies of the reference pair: run-out) the
    crossing is interpolated linearly on the grid.
    """
    f1, f2 = flanks
    phi1, cand, a, ks, kind_c = br.phi1, br.te, br.active, br.offsets, br.kind
    J, s = (len(ref.j) - 1) // 2, opts.steps_per_cycle
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
    exact_ok = exact
    exact = np.zeros(n, bool)
    for q in range(n):
        i = idx[q]
        exact[q] = all(kind_c[i + di, col] == ContactKind.SURFACE for di in (0, 1) for col in (ka[q], kb[q]))
    if not (exact_ok and exact.any()):
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
        r = newton(tangency_system(f1, f2, phr), guess, NewtonOptions(tol=opts.tol, maxiter=30), raise_on_failure=False)
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


def extremes(te, kk, kind, trans_te):
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

