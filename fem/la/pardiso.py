"""Thin ctypes interface to MKL PARDISO for symmetric matrices, with its Schur-complement mode.

pypardiso (a declared dependency) locates and loads MKL's ``mkl_rt``; it exposes only the plain
solve, so the library handle is reused here to call ``pardiso`` directly:

    mtype = 2 (real SPD) or -2 (real symmetric indefinite), upper triangle with every diagonal
    entry stored, 0-based CSR, METIS ordering.
    Schur mode (iparm[35] = 1): rows marked in ``perm`` are eliminated last; phase 12 returns the
    dense Schur complement  S = K_CC - K_CR K_RR^-1 K_RC  in ``x`` and keeps the factor of K_RR
    (mode 2 would also factor S, which fails when S is singular: a body free before contact).
    Phase 331 (forward substitution) of a right-hand side f leaves the condensed load
    f_C - K_CR K_RR^-1 f_R in the C rows; after the caller has solved S u_C = (that) and written
    u_C into the C rows, phase 333 (backward substitution) gives the whole solution.

This was checked against dense algebra (Schur complement to 1e-14, partial solves to 1e-15) and is
checked again by the tests of ``fem.la.linsolve``.
"""

from __future__ import annotations

import ctypes

import numpy as np
import scipy.sparse as sp

from fem.errors import FEError

__all__ = ["available", "triu_csr", "upper_csr", "on_pattern", "Pardiso"]

_P = ctypes.POINTER
_I32 = ctypes.c_int32
_ERRORS = {
    -1: "input inconsistent",
    -2: "not enough memory",
    -3: "reordering problem",
    -4: "zero pivot (the matrix is singular: a body is not supported)",
    -7: "diagonal matrix is singular",
    -8: "32-bit integer overflow",
    -11: "read/write problem with the out-of-core data file",
}


def _load():
    try:
        import pypardiso  # noqa: F401  (loads mkl_rt)
        from pypardiso.pardiso_wrapper import PyPardisoSolver
    except Exception:  # pragma: no cover - depends on the platform
        return None
    try:
        lib = PyPardisoSolver().libmkl
    except Exception:  # pragma: no cover
        return None
    f = lib.pardiso
    f.argtypes = [_P(ctypes.c_int64), _P(_I32), _P(_I32), _P(_I32), _P(_I32), _P(_I32), ctypes.c_void_p,
                  _P(_I32), _P(_I32), _P(_I32), _P(_I32), _P(_I32), _P(_I32), ctypes.c_void_p, ctypes.c_void_p, _P(_I32)]
    f.restype = None
    return f


_PARDISO = _load()


def triu_csr(K: sp.spmatrix, k: int = 0) -> sp.csr_matrix:
    """The entries (i, j) of K with j - i >= k, sorted CSR (``scipy.sparse.triu`` without its COO round trip): a
    canonical CSR matrix is cut by a mask on its column indices."""
    K = sp.csr_matrix(K)
    if not K.has_canonical_format:
        K = K.copy()
        K.sum_duplicates()  # also sorts the indices
    n = K.shape[0]
    row = np.repeat(np.arange(n, dtype=K.indices.dtype), np.diff(K.indptr))
    keep = K.indices.astype(np.int64) - row >= k
    indptr = np.zeros(n + 1, np.int64)
    np.cumsum(np.bincount(row[keep], minlength=n), out=indptr[1:])
    U = sp.csr_matrix((K.data[keep], K.indices[keep], indptr), shape=K.shape)
    U.has_sorted_indices = True
    return U


def upper_csr(K: sp.spmatrix) -> sp.csr_matrix:
    """The upper triangle of symmetric K as sorted CSR with every diagonal entry stored (zeros included).

    PARDISO wants the diagonal of every row, also the zero diagonal of the gap rows of a bordered
    matrix. A canonical CSR matrix that already stores its diagonal is cut by a mask on its column
    indices (:func:`triu_csr`); otherwise the missing diagonal entries are added."""
    U = triu_csr(K)
    n = U.shape[0]
    counts = np.diff(U.indptr)
    first = U.indices[U.indptr[:-1][counts > 0]]
    if np.count_nonzero(counts) == n and np.array_equal(first, np.flatnonzero(counts)):
        return U  # sorted rows whose first entry is the diagonal: all diagonal entries stored
    C = U.tocoo()
    U = sp.coo_matrix((np.concatenate([C.data, np.zeros(n)]), (np.concatenate([C.row, np.arange(n)]),
                       np.concatenate([C.col, np.arange(n)]))), shape=U.shape).tocsr()
    U.sum_duplicates()
    U.sort_indices()
    return U


def on_pattern(A: sp.csr_matrix, P: sp.csr_matrix) -> sp.csr_matrix:
    """A's values on the pattern P that contains A's (both sorted CSR): P's arrays, A's values, zeros elsewhere.

    A sparse product drops the entries that cancel to exactly zero, so the values' pattern may be smaller than
    the pattern analysed beforehand; the factorization needs the analysed one. A row with as many entries as
    P's row has the same columns; only the other rows are searched."""
    cA, cP = np.diff(A.indptr), np.diff(P.indptr)
    pos = np.arange(A.nnz, dtype=np.int64) + np.repeat(P.indptr[:-1].astype(np.int64) - A.indptr[:-1], cA)
    for i in np.flatnonzero(cA != cP):
        a, p = slice(A.indptr[i], A.indptr[i + 1]), P.indptr[i]
        pos[a] = p + np.searchsorted(P.indices[p:P.indptr[i + 1]], A.indices[a])
    if len(pos) and (pos.max() >= P.nnz or not np.array_equal(P.indices[pos], A.indices)):
        raise FEError("the assembled matrix has entries outside the pattern analysed for it")
    if A.nnz == P.nnz:
        data = A.data
    else:
        data = np.zeros(P.nnz)
        data[pos] = A.data
    out = sp.csr_matrix((data, P.indices, P.indptr), shape=P.shape)
    out.has_sorted_indices = True
    return out


def _checked_upper(U: sp.spmatrix) -> sp.csr_matrix:
    """U itself when it is an upper triangle in PARDISO's form (CSR, rows sorted and duplicate-free, each row
    starting at its diagonal entry); FEError otherwise."""
    if not (sp.issparse(U) and U.format == "csr"):
        raise FEError("an upper-triangle matrix for PARDISO must be CSR")
    n = U.shape[0]
    starts = U.indptr[:-1]
    ok = U.shape[1] == n and bool(np.all(np.diff(U.indptr) > 0)) and np.array_equal(U.indices[starts], np.arange(n))
    if ok:
        inc = np.diff(U.indices) > 0
        inc[starts[1:] - 1] = True  # a row's first index may be below the previous row's last
        ok = bool(inc.all())
    if not ok:
        raise FEError("the matrix given as an upper triangle is not one: every row must start at its diagonal entry "
                      "and have increasing column indices")
    U.has_sorted_indices = True
    return U


def available() -> bool:
    """True when MKL PARDISO could be loaded."""
    return _PARDISO is not None


class Pardiso:
    """PARDISO factorization of a symmetric matrix (mtype 2: SPD, -2: indefinite), optional Schur rows."""

    def __init__(self, K: sp.spmatrix, schur_rows: np.ndarray | None = None, mtype: int = 2, upper: bool = False,
                 factor: bool = True):
        """``upper``: K already holds only the upper triangle (CSR, sorted rows, each starting at its diagonal
        entry), as :func:`upper_csr` gives; it is checked, not cut again. ``factor`` = False: nothing is computed
        yet; :meth:`analyse` (phase 11) then reads only K's pattern, and :meth:`factorize` the values of a matrix
        with that pattern (phase 22), so that the analysis can run while the values are being computed."""
        if _PARDISO is None:  # pragma: no cover
            raise FEError("MKL PARDISO is not available (pypardiso/mkl could not be loaded)")
        U = _checked_upper(K) if upper else upper_csr(K)
        self.mtype = int(mtype)
        self.n = U.shape[0]
        self._a = np.ascontiguousarray(U.data, dtype=np.float64)
        self._ia = np.ascontiguousarray(U.indptr, dtype=np.int32)
        self._ja = np.ascontiguousarray(U.indices, dtype=np.int32)
        self._pt = np.zeros(64, np.int64)
        self._iparm = np.zeros(64, np.int32)
        ip = self._iparm
        ip[0] = 1  # user-supplied iparm (scaling and matching, iparm[10] and [12], off: phase 11 reads no values)
        ip[1] = 2  # METIS nested dissection
        ip[9] = 8  # pivot perturbation 1e-8
        ip[17] = -1  # report nnz(L)
        ip[34] = 1  # zero-based indexing
        self._perm = np.zeros(self.n, np.int32)
        self.n_schur = 0 if schur_rows is None else len(schur_rows)
        self._x = np.zeros(max(self.n_schur**2, 1))
        if self.n_schur:
            self._perm[schur_rows] = 1
            ip[35] = 1  # Schur complement (mode 2 would also factor S, which is singular for free bodies)
        self.schur = None
        self.nnz_factor = 0
        if factor:
            self._call(12, np.zeros(1), self._x)
            self._factored()

    def _factored(self):
        self.schur = self._x.reshape(self.n_schur, self.n_schur) if self.n_schur else None
        self.nnz_factor = int(self._iparm[17])

    def analyse(self):
        """Phase 11: ordering and symbolic factorization of the pattern (no values are read)."""
        self._call(11, np.zeros(1), self._x)

    def factorize(self, data: np.ndarray):
        """Phase 22 after :meth:`analyse`: the numeric factorization of the matrix with the pattern given at
        construction and these values (its CSR data array), and the Schur complement."""
        data = np.ascontiguousarray(data, dtype=np.float64)
        if data.shape != self._a.shape:
            raise FEError(f"PARDISO: {len(data)} values for a pattern of {len(self._a)} entries")
        self._a = data
        self._call(22, np.zeros(1), self._x)
        self._factored()

    def _call(self, phase: int, b: np.ndarray, x: np.ndarray, nrhs: int = 1):
        err = _I32(0)
        _PARDISO(self._pt.ctypes.data_as(_P(ctypes.c_int64)), ctypes.byref(_I32(1)), ctypes.byref(_I32(1)),
                 ctypes.byref(_I32(self.mtype)), ctypes.byref(_I32(phase)), ctypes.byref(_I32(self.n)), self._a.ctypes.data,
                 self._ia.ctypes.data_as(_P(_I32)), self._ja.ctypes.data_as(_P(_I32)), self._perm.ctypes.data_as(_P(_I32)),
                 ctypes.byref(_I32(nrhs)), self._iparm.ctypes.data_as(_P(_I32)), ctypes.byref(_I32(0)),
                 b.ctypes.data, x.ctypes.data, ctypes.byref(err))
        if err.value != 0:
            raise FEError(f"PARDISO phase {phase} failed with error {err.value}: {_ERRORS.get(err.value, 'see MKL documentation')}")

    def solve(self, b: np.ndarray) -> np.ndarray:
        """Solution of K x = b (no Schur rows)."""
        b = np.asfortranarray(b, dtype=np.float64)
        x = np.zeros_like(b)
        self._call(33, b, x, 1 if b.ndim == 1 else b.shape[1])
        return np.ascontiguousarray(x)

    def forward(self, b: np.ndarray) -> np.ndarray:
        """Phase 331: the C rows of the result hold the condensed load f_C - K_CR K_RR^-1 f_R."""
        b = np.ascontiguousarray(b, dtype=np.float64)
        y = np.zeros_like(b)
        self._call(331, b, y)
        return y

    def backward(self, y: np.ndarray) -> np.ndarray:
        """Phase 333 on a forward result whose C rows were replaced by u_C: the full solution."""
        y = np.ascontiguousarray(y, dtype=np.float64)
        x = np.zeros_like(y)
        self._call(333, y, x)
        return x

    def free(self):
        """Release MKL's memory for this factorization."""
        if self._pt.any():
            self._call(-1, np.zeros(1), np.zeros(1))
            self._pt[:] = 0

    def __del__(self):
        try:
            self.free()
        except Exception:
            pass
