"""Sparse solves: a factorization with a dense Schur complement on a small set of rows C.

Contact couples the stiffness only through a few hundred gap rows and the free rigid-body DOFs
(the set C). A symmetric matrix A (the stiffness bordered by the gap rows, ``fem.analysis``) is
factored once with C eliminated last,

    [A_RR A_RC] [x_R]   [b_R]          S = A_CC - A_CR A_RR^-1 A_RC         (dense)
    [A_CR A_CC] [x_C] = [b_C],         b~_C = b_C - A_CR A_RR^-1 b_R,

the caller chooses x_C from (S, b~_C) (the contact problem), and x_R = A_RR^-1 (b_R - A_RC x_C)
follows by one back substitution. A_RR must be nonsingular: every body is held when its free
rigid DOFs (in C) are clamped.

Backends, chosen by measurement (MEASURED.md and ``benchmarks.fem``):
- ``pardiso``: MKL PARDISO, Schur mode: one factorization of A_RR (Cholesky when A_RR is positive
  definite, also when A_CC is not, e.g. the zero diagonal of gap rows; else symmetric indefinite),
  a forward and a backward substitution.
- ``superlu``: pure scipy fallback; factors A_RR with SuperLU and forms S with |C| solves.
``linear_solve`` also offers ``amg`` (pyamg smoothed aggregation + rigid-body modes, CG) for
solves without contact.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from fem.errors import FEConvergenceError, FEError, FEInputError

from fem.la import pardiso

__all__ = ["choose_solver", "SchurSystem", "schur_system", "PendingSchur", "schur_analysis", "linear_solve",
           "rigid_body_modes"]


def choose_solver(name: str) -> str:
    """Resolve 'auto' to 'pardiso' when MKL loads, else 'superlu'."""
    if name == "auto":
        return "pardiso" if pardiso.available() else "superlu"
    if name == "pardiso" and not pardiso.available():
        raise FEInputError("solver.solver", name, "'superlu' or 'auto' (MKL PARDISO could not be loaded)")
    return name


@dataclass(eq=False)
class SchurSystem:
    """A factored symmetric matrix with its dense Schur complement on rows ``C``."""

    method: str
    C: np.ndarray
    schur: np.ndarray
    factor_s: float
    _solve: Callable = field(repr=False)

    def solve(self, f: np.ndarray, solve_c: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """Full solution for load f, with u_C = solve_c(condensed load f~_C) chosen by the caller."""
        return self._solve(f, solve_c)


def _pardiso_system(fac: pardiso.Pardiso, C: np.ndarray, factor_s: float) -> SchurSystem:
    """The SchurSystem of a factored PARDISO matrix with Schur rows C."""
    if len(C):
        def solve(f, solve_c):
            y = fac.forward(f)
            y[C] = solve_c(y[C].copy())
            return fac.backward(y)
    else:
        def solve(f, solve_c):
            return fac.solve(f)
    return SchurSystem("pardiso", C, fac.schur if len(C) else np.zeros((0, 0)), factor_s, solve)


class PendingSchur:
    """The symbolic analysis of a symmetric matrix's pattern running on a thread while its values are computed.

    Made by :func:`schur_analysis`; :meth:`factor` waits for the analysis and factors the values (the same
    Schur complement and solution as :func:`schur_system` of that matrix, which PARDISO's phases 11 and 22 give
    like its phase 12). The analysis (ordering and symbolic factorization) reads no values and runs on one core,
    so the caller can assemble the values on the other meanwhile. ``close`` waits for the thread and frees
    PARDISO's memory when the values never come (an error on the way); use it in a ``finally``."""

    def __init__(self, U: sp.spmatrix, C: np.ndarray, method: str, definite: bool):
        self.method = choose_solver(method)
        self.C = np.asarray(C, np.int64)
        self.definite = definite
        self.analysis_s = 0.0
        self._fac = None
        self._thread = None
        self._error: BaseException | None = None
        if self.method == "pardiso":
            self._fac = pardiso.Pardiso(U, self.C if len(self.C) else None, mtype=2 if definite else -2, upper=True,
                                        factor=False)
            self._thread = threading.Thread(target=self._analyse, name="pardiso-analysis", daemon=True)
            self._thread.start()

    def _analyse(self):
        t0 = time.perf_counter()
        try:
            self._fac.analyse()
        except BaseException as exc:  # re-raised by factor()
            self._error = exc
        self.analysis_s = time.perf_counter() - t0

    def _join(self):
        if self._thread is not None:
            self._thread.join()
            self._thread = None

    def factor(self, U: sp.spmatrix) -> SchurSystem:
        """Factor the matrix whose upper triangle U has the pattern given at construction (CSR, same arrays)."""
        t0 = time.perf_counter()
        if self.method != "pardiso":
            return schur_system(U, self.C, self.method, self.definite, upper=True)
        self._join()
        if self._error is not None:
            raise self._error
        self._fac.factorize(U.data)
        return _pardiso_system(self._fac, self.C, time.perf_counter() - t0)

    def close(self):
        """Wait for the analysis; free PARDISO's memory unless the matrix was factored."""
        self._join()
        if self._fac is not None and self._fac.schur is None and self._fac.nnz_factor == 0:
            self._fac.free()


def schur_analysis(U: sp.spmatrix, C: np.ndarray, method: str = "auto", definite: bool = True) -> PendingSchur:
    """Start the symbolic analysis of the upper-triangle pattern U (the form of :func:`fem.la.pardiso.upper_csr`)
    with Schur rows C on a thread; :meth:`PendingSchur.factor` finishes it with the values (SuperLU: all then)."""
    return PendingSchur(U, C, method, definite)


def schur_system(K: sp.spmatrix, C: np.ndarray, method: str = "auto", definite: bool = True,
                 upper: bool = False) -> SchurSystem:
    """Factor symmetric K once, with the dense Schur complement on sorted rows C (may be empty).

    ``definite``: K_RR (the rows outside C, the only block that is factored) is positive definite, so
    PARDISO's Cholesky (mtype 2) applies even when the C block is not (the zero diagonal of gap rows);
    otherwise the symmetric indefinite factorization (mtype -2, Bunch-Kaufman with pivot perturbation).
    ``upper``: K holds only the upper triangle, in the form of :func:`fem.la.pardiso.upper_csr` (every row
    starting at its stored diagonal entry), which PARDISO takes as it is (no copy of the whole matrix)."""
    method = choose_solver(method)
    C = np.asarray(C, np.int64)
    t0 = time.perf_counter()
    if method == "pardiso":
        fac = pardiso.Pardiso(K, C if len(C) else None, mtype=2 if definite else -2, upper=upper)
        return _pardiso_system(fac, C, time.perf_counter() - t0)
    if method != "superlu":
        raise FEInputError("solver.solver", method, "'pardiso', 'superlu' or 'auto'")
    K = sp.csr_matrix(K)
    if upper:
        K = (K + sp.triu(K, 1, format="csr").T).tocsr()
    R = np.setdiff1d(np.arange(K.shape[0]), C)
    KRR = K[R][:, R].tocsc()
    try:
        lu = spla.splu(KRR, permc_spec="MMD_AT_PLUS_A")
    except RuntimeError as exc:  # singular
        raise FEError(f"stiffness matrix is singular ({exc}): a body is not supported") from None
    KRC = K[R][:, C].tocsc()
    KCR = K[C][:, R].tocsr()
    S = K[C][:, C].toarray()
    for s in range(0, len(C), 256):
        S[:, s:s + 256] -= KCR @ lu.solve(KRC[:, s:s + 256].toarray())

    def solve(f, solve_c):
        u = np.empty_like(f)
        fC = f[C] - KCR @ lu.solve(f[R]) if len(C) else f[C]
        u[C] = solve_c(fC)
        u[R] = lu.solve(f[R] - KRC @ u[C])
        return u

    return SchurSystem("superlu", C, S, time.perf_counter() - t0, solve)


def rigid_body_modes(points: np.ndarray) -> np.ndarray:
    """The six rigid-body modes (3n, 6) of interleaved nodal DOFs (near null space for AMG)."""
    n = len(points)
    B = np.zeros((n, 3, 6))
    c = points - points.mean(axis=0)
    for i in range(3):
        B[:, i, i] = 1.0
    B[:, 1, 3], B[:, 2, 3] = -c[:, 2], c[:, 1]
    B[:, 0, 4], B[:, 2, 4] = c[:, 2], -c[:, 0]
    B[:, 0, 5], B[:, 1, 5] = -c[:, 1], c[:, 0]
    return B.reshape(3 * n, 6)


def linear_solve(K: sp.spmatrix, f: np.ndarray, method: str = "auto", *, modes: np.ndarray | None = None,
                 tol: float = 1e-8) -> tuple[np.ndarray, dict]:
    """Solve K u = f by 'pardiso', 'superlu' or 'amg' (CG); returns u and timing/iteration info."""
    t0 = time.perf_counter()
    info: dict = {"method": method}
    if method in ("auto", "pardiso", "superlu"):
        sys_ = schur_system(K, np.zeros(0, np.int64), method)
        u = sys_.solve(f, lambda fc: fc)
        info["method"] = sys_.method
    elif method == "amg":
        import pyamg

        A = sp.csr_matrix(K)
        ml = pyamg.smoothed_aggregation_solver(A.tobsr(blocksize=(3, 3)), B=modes, symmetry="symmetric", strength="symmetric")
        res: list[float] = []
        u = ml.solve(f, tol=tol, accel="cg", maxiter=2000, residuals=res)
        info["iterations"] = len(res) - 1
        rel = np.linalg.norm(f - A @ u) / max(np.linalg.norm(f), 1e-300)
        if rel > 10 * tol:
            raise FEConvergenceError("AMG-preconditioned CG", "linear solve", rel, len(res) - 1)
    else:
        raise FEInputError("method", method, "'auto', 'pardiso', 'superlu' or 'amg'")
    info["seconds"] = time.perf_counter() - t0
    return u, info
