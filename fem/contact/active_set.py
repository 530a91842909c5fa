"""The penalty contact problem reduced to the candidate gaps and the free rigid DOFs, and its active-set solution.

Reduced problem (``ReducedContact``, built by ``fem.analysis``). The reduced stiffness bordered by the gap rows of the k
candidate nodes is factored once with its Schur complement on the free rigid DOFs F and the gap
rows, which gives directly

    W = G K_RR^-1 G^T         (gap compliance with the free rigid DOFs clamped),
    B = G K_RR^-1 K_RF - G_F  (gap change per free rigid DOF, sign as below),
    H = K_FF - K_FR K_RR^-1 K_RF,
    g^ = g0 + G u_p + G K_RR^-1 f_R,   f^_F = f_F - K_FR K_RR^-1 f_R,

so that the gaps and the equilibrium of the free rigid DOFs read

    g = g^ + W lambda - B u_F,         H u_F + B^T lambda = f^_F.

H is singular for a body that is free before contact closes (a free planet); the bordered system
on an active set A,

    [ W_AA + K_A^-1   -B_A ] [lambda_A]   [ -g^_A ]
    [ -B_A^T          -H   ] [  u_F   ] = [ -f^_F ],

is regular once the active contacts hold the free rotations. Primal-dual active set iteration
(semismooth Newton on the penalty law): A <- {g < 0} until A repeats. Each iteration costs a
dense solve of the size of A: no sparse refactorization. The penalty may then be raised (no
refactorization either) until the largest penetration is below the tolerance, and the peak
pressure is compared with a solve at twice the penalty.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from fem.errors import FEConvergenceError, FEError
from fem.model import ContactOptions

try:
    from threadpoolctl import threadpool_limits
except ImportError:  # pragma: no cover - optional: without it the dense solves use the BLAS default threads
    threadpool_limits = None

__all__ = ["ReducedContact", "ActiveSetSolution", "active_set", "penalty_active_set"]


@dataclass(frozen=True, eq=False)
class ReducedContact:
    """The contact problem on the k candidate gaps and the n_F free rigid DOFs (module docstring).

    W (k, k) gap compliance [mm/N], B (k, n_F) gap change per free rigid DOF, H (n_F, n_F) their
    condensed stiffness, ghat (k,) the gaps [mm] and fhat (n_F,) the loads with the free rigid DOFs
    clamped; h_scale (n_F,) the diagonal of the reduced stiffness at the free rigid DOFs (the scale
    below which a condensed stiffness is round-off).
    """

    W: np.ndarray
    B: np.ndarray
    H: np.ndarray
    ghat: np.ndarray
    fhat: np.ndarray
    h_scale: np.ndarray


@dataclass(frozen=True, eq=False)
class ActiveSetSolution:
    """Contact forces lambda [N], free rigid DOFs, gaps [mm], active set, iterations, penalty scale."""

    lam: np.ndarray
    u_free: np.ndarray
    gap: np.ndarray
    active: np.ndarray
    iterations: int
    scale: float = 1.0
    penalty_change: float = float("nan")


def _solve_set(p: ReducedContact, k, A):
    W, B, H, ghat, fhat = p.W, p.B, p.H, p.ghat, p.fhat
    a = np.flatnonzero(A)
    nF = len(fhat)
    lam = np.zeros(len(ghat))
    if len(a):
        P = W[np.ix_(a, a)] + np.diag(1.0 / k[a])
        try:
            cf = sla.cho_factor(P)
        except np.linalg.LinAlgError:
            raise FEError("contact compliance matrix is not positive definite on the active set") from None
        Ba = B[a]
        Z = sla.cho_solve(cf, np.column_stack([Ba, ghat[a]])) if nF else sla.cho_solve(cf, ghat[a][:, None])
    else:
        Ba = np.zeros((0, nF))
        Z = np.zeros((0, nF + 1))
    uF = np.zeros(nF)
    if nF:
        Hs = H + Ba.T @ Z[:, :nF]
        # a free rigid DOF is held if its condensed stiffness is not round-off of its own
        # stiffness with everything else clamped (h_scale = diag of the reduced K there)
        loose = np.diag(Hs) <= 1e-9 * p.h_scale
        if loose.any():
            raise FEError(
                f"free rigid DOF(s) {np.flatnonzero(loose).tolist()} are not held by any active contact: "
                "the contact does not close (check the contact seed, the search gap and the load direction)"
            )
        uF = np.linalg.solve(Hs, fhat + Ba.T @ Z[:, nF])
    if len(a):
        # lambda_A = P^-1 (B_A u_F - g^_A)
        lam[a] = (Z[:, :nF] @ uF if nF else 0.0) - Z[:, -1]
    return lam, uF


def active_set(p: ReducedContact, k, active0, max_iterations: int) -> ActiveSetSolution:
    """Primal-dual active-set iteration of the penalty contact problem, penalty stiffnesses k [N/mm] (module docstring)."""
    A = np.asarray(active0, bool).copy()
    seen = {A.tobytes()}
    for it in range(1, max_iterations + 1):
        lam, uF = _solve_set(p, k, A)
        g = p.ghat + p.W @ lam - (p.B @ uF if len(uF) else 0.0)
        A_new = g < 0.0
        changed = A_new != A
        if not changed.any():
            return ActiveSetSolution(lam, uF, g, A, it)
        viol = float(np.abs(g[changed]).max())  # [mm] gap of the nodes that switch
        key = A_new.tobytes()
        if key in seen:
            raise FEConvergenceError("contact active set", "a repeated set (cycling)", viol, it)
        seen.add(key)
        A = A_new
    raise FEConvergenceError("contact active set", f"{int(changed.sum())} nodes still switching", viol, max_iterations)


def penalty_active_set(p: ReducedContact, k, area, active0, opts: ContactOptions, peak=None) -> ActiveSetSolution:
    """Active set, with the penalty raised until penetration <= tolerance, then the doubling check.

    ``k`` [N/mm] the penalty stiffnesses and ``area`` [mm^2] the areas of the constraints;
    ``peak(lam)`` [MPa]: the peak pressure the doubling check compares (default max lambda / area)."""
    peak = peak or (lambda lam: float(np.max(lam / area)))
    # the dense active-set matrices are small (hundreds of rows): threaded BLAS only adds synchronization,
    # which on a loaded machine costs seconds per Cholesky factorization (measured 0.3 s against 0.1 ms at 150 rows)
    with threadpool_limits(1, user_api="blas") if threadpool_limits else contextlib.nullcontext():
        return _penalty_active_set(p, k, active0, opts, peak)


def _penalty_active_set(p: ReducedContact, k, active0, opts: ContactOptions, peak) -> ActiveSetSolution:
    scale = 1.0
    sol = active_set(p, k, active0, opts.max_iterations)
    pen = float(np.max(-sol.gap[sol.active], initial=0.0))
    raises = 0
    while pen > opts.max_penetration:
        raises += 1
        if raises > 12:
            raise FEConvergenceError("penalty penetration", f"max_penetration = {opts.max_penetration} mm", pen, raises)
        scale *= max(2.0, 1.5 * pen / opts.max_penetration)
        sol = active_set(p, scale * k, sol.active, opts.max_iterations)
        pen = float(np.max(-sol.gap[sol.active], initial=0.0))
    change = float("nan")
    if opts.penalty_check and sol.active.any():
        for _ in range(8):
            sol2 = active_set(p, 2.0 * scale * k, sol.active, opts.max_iterations)
            p1, p2 = peak(sol.lam), peak(sol2.lam)
            change = abs(p2 - p1) / p1
            if change < opts.penalty_check_tol:
                break
            scale, sol = 2.0 * scale, sol2
        else:
            raise FEConvergenceError("penalty doubling check", f"penalty_check_tol = {opts.penalty_check_tol}", change, 8)
    return ActiveSetSolution(sol.lam, sol.u_free, sol.gap, sol.active, sol.iterations, scale, change)
