"""Batched Newton–Raphson with truncated-SVD steps and backtracking line search.

Solves many independent small systems F(x) = 0 at once (one per TCA position). The step is
the minimum-norm solution of J dx = -F with singular values below ``rcond`` times the largest
dropped, so rank-deficient systems (line contact of conjugate surfaces) still converge.

Where a system may be rank-deficient, a *preferred point* selects the solution: a first phase
solves the augmented least-squares problem ``[F(x); w (x - x_pref)] -> min`` by Gauss–Newton (for a
regular system this only shifts the iterate by O(w²), for a line of solutions it picks the point of
the line nearest ``x_pref``), and a second phase polishes with plain Newton to ``tol``. Every
solve reports its iterations and residual; :func:`newton` raises when asked and any system fails.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from tca.errors import ConvergenceError

__all__ = ["NewtonOptions", "PreferredPoint", "NewtonResult", "newton"]


@dataclass(frozen=True)
class NewtonOptions:
    """Stopping rule and step control of a batched solve."""

    tol: float = 1e-11  # converged when max|F| < tol (F in mm for the TCA systems)
    maxiter: int = 40
    rcond: float = 1e-11  # singular values below rcond times the largest are dropped from a step
    max_backtracks: int = 12  # halvings of a step in the line search


@dataclass(frozen=True, eq=False)
class PreferredPoint:
    """The point x_pref = point(x, idx) (k, m) that selects the solution of a rank-deficient system, weighted by
    ``weights`` (m,) (default 1e-3 for every unknown), for the first phase of the module docstring."""

    point: Callable[[np.ndarray, np.ndarray], np.ndarray]
    weights: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class NewtonResult:
    """Solutions x (n, m), residual max-norms (n,), iterations (n,), converged mask (n,)."""

    x: np.ndarray
    residual: np.ndarray
    iterations: np.ndarray
    converged: np.ndarray


def _lstsq(A, b, rcond):
    """Minimum-norm least-squares solutions of batched A (k, r, m) x = b (k, r)."""
    U, s, Vt = np.linalg.svd(A, full_matrices=False)
    keep = s > rcond * s[..., :1]
    inv = np.where(keep, 1.0 / np.where(keep, s, 1.0), 0.0)
    return np.einsum("...ji,...j,...kj,...k->...i", Vt, inv, U, b)


@dataclass(frozen=True)
class _Phase:
    """One phase of the solve: merit(x, F, idx) (k,), step(x, F, J, idx) (k, m) and stop(F, merit) (k,) bool."""

    merit: Callable
    step: Callable
    stop: Callable


def _iterate(x, fun, phase: _Phase, maxiter, its, max_backtracks, skip=None):
    """Damped iterations on members where phase.stop is False; returns (F, J, merit) of the final x."""
    idx_all = np.arange(len(x))
    res_fn, step_fn, stop_fn = phase.merit, phase.step, phase.stop
    F, J = fun(x, idx_all)
    merit = res_fn(x, F, idx_all)
    history = [merit.copy()]
    stalled = np.zeros(len(x), bool)
    for it in range(maxiter):
        # a member whose merit did not halve over the last 4 iterations has stalled (no solution nearby)
        if it >= 4:
            stalled |= merit > 0.5 * history[-4]
        # a member whose residual or Jacobian is not finite has left the surfaces: it fails, others go on
        stalled |= ~(np.isfinite(F).all(-1) & np.isfinite(J).reshape(len(J), -1).all(-1))
        active = ~stop_fn(F, merit) & ~stalled
        if skip is not None:
            active &= ~skip
        if not active.any():
            break
        ia = idx_all[active]
        dx = step_fn(x[ia], F[ia], J[ia], ia)
        alpha = np.ones(len(ia))
        m0 = merit[ia]
        xa = x[ia]
        pending = np.ones(len(ia), dtype=bool)
        Fn, Jn, Mn = np.empty_like(F[ia]), np.empty_like(J[ia]), np.empty_like(m0)
        for _ in range(max_backtracks):  # backtracking: accept the first step that reduces the merit function
            p = np.flatnonzero(pending)
            xt = xa[p] + alpha[p, None] * dx[p]
            Ft, Jt = fun(xt, ia[p])
            mt = res_fn(xt, Ft, ia[p])
            finite = np.isfinite(Ft).all(-1) & np.isfinite(Jt).reshape(len(Jt), -1).all(-1)
            ok = ((mt < m0[p] * (1 - 1e-4 * alpha[p]) + 1e-300) | stop_fn(Ft, mt)) & finite
            good = p[ok]
            xa[good], Fn[good], Jn[good], Mn[good] = xt[ok], Ft[ok], Jt[ok], mt[ok]
            pending[good] = False
            alpha[p[~ok]] *= 0.5
            if not pending.any():
                break
        if pending.any():  # no decrease: take the smallest step (lets a stalled solve be reported)
            p = np.flatnonzero(pending)
            xt = xa[p] + alpha[p, None] * dx[p]
            Ft, Jt = fun(xt, ia[p])
            Mt = res_fn(xt, Ft, ia[p])
            finite = np.isfinite(Ft).all(-1) & np.isfinite(Jt).reshape(len(Jt), -1).all(-1) & np.isfinite(Mt)
            q = p[finite]  # a non-finite trial keeps the last iterate; stall detection ends it
            xa[q], Fn[q], Jn[q], Mn[q] = xt[finite], Ft[finite], Jt[finite], Mt[finite]
            r = p[~finite]
            Fn[r], Jn[r], Mn[r] = F[ia[r]], J[ia[r]], merit[ia[r]]
        x[ia], F[ia], J[ia], merit[ia] = xa, Fn, Jn, Mn
        its[ia] += 1
        history.append(merit.copy())
    return F, J, merit


def newton(
    fun: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
    x0: np.ndarray,
    options: NewtonOptions = NewtonOptions(),
    *,
    prefer: PreferredPoint | None = None,
    raise_on_failure: bool = True,
    what: str = "contact",
    where: Callable[[int], str] | None = None,
) -> NewtonResult:
    """Solve fun(x, idx) = (F (k, m), J (k, m, m)) = 0 for a batch x0 (n, m).

    ``idx`` tells ``fun`` which members of the batch it is given. Converged when max|F| < ``options.tol``
    (F in mm for the TCA systems). ``prefer`` selects the solution of (nearly) rank-deficient members in a
    first phase (module docstring). With ``raise_on_failure`` a member that does not converge raises
    :class:`ConvergenceError` naming ``what`` and ``where(i)`` (default: the batch member).
    """
    tol, maxiter, rcond, max_backtracks = options.tol, options.maxiter, options.rcond, options.max_backtracks
    x = np.array(x0, dtype=float, copy=True)
    n = len(x)
    idx_all = np.arange(n)
    its = np.zeros(n, dtype=int)

    if prefer is not None:
        w = np.asarray(prefer.weights if prefer.weights is not None else np.full(x.shape[1], 1e-3), float)
        prefer_point = prefer.point

        def aug_merit(xx, F, ia):
            return np.sqrt(np.sum(F**2, -1) + np.sum((w * (xx - prefer_point(xx, ia))) ** 2, -1))

        def gn_step(xx, F, J, ia):
            A = np.concatenate([J, np.broadcast_to(np.diag(w), (len(ia),) + (len(w), len(w)))], 1)
            b = np.concatenate([-F, -w * (xx - prefer_point(xx, ia))], 1)
            return _lstsq(A, b, rcond)

        def gn_stop(F, m):
            return np.abs(F).max(-1) < 1e-8

        # the preferred point only matters where the Jacobian is (nearly) singular
        F0, J0 = fun(x, idx_all)
        finite = np.isfinite(F0).all(-1) & np.isfinite(J0).reshape(n, -1).all(-1)
        regular = ~finite  # non-finite members fail in the Newton phase
        if finite.any():
            sv = np.linalg.svd(J0[finite], compute_uv=False)
            regular[finite] = sv[:, -1] > 1e-7 * sv[:, 0]
        if not regular.all():
            _iterate(x, fun, _Phase(aug_merit, gn_step, gn_stop), maxiter // 2, its, max_backtracks, skip=regular)

    def plain_merit(xx, F, ia):
        return np.linalg.norm(F, axis=-1)

    def nt_step(xx, F, J, ia):
        return _lstsq(J, -F, rcond)

    def nt_stop(F, m):
        return np.abs(F).max(-1) < tol

    F, _, _ = _iterate(x, fun, _Phase(plain_merit, nt_step, nt_stop), maxiter, its, max_backtracks)
    res = np.abs(F).max(-1)
    converged = res < tol
    if raise_on_failure and not converged.all():
        i = int(np.flatnonzero(~converged)[np.argmax(res[~converged])])
        loc = where(i) if where is not None else f"batch member {i}"
        raise ConvergenceError(what, loc, float(res[i]), int(its[i]))
    return NewtonResult(x, res, its, converged)
