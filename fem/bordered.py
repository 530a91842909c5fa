r"""The bordered matrix of the contact solve as PARDISO takes it: the pattern of its upper triangle from the
connectivity, the supports and the contact set alone, and then its values gathered from K.

With the supports eliminated (:mod:`fem.constraints`), u = T q + u_p, T = [S  R]: S selects the n_f DOFs that are
neither fixed nor tied (in their order, value 1), R (3n, n_g) holds the columns of the free rigid DOFs (rows at
tied DOFs only). The reduced stiffness and the bordered matrix of :mod:`fem.analysis` are

.. math::
    K_r = T^T K T = \begin{bmatrix} K_{ff} & X_f \\ X_f^T & X_g \end{bmatrix}, \qquad
    X = T^T K R = (R^T K\, T)^T \quad (n_r \times n_g)                                                      (B1)

.. math::
    A = \begin{bmatrix} K_r & G_r^T \\ G_r & 0 \end{bmatrix}, \qquad G_r^T = T^T G^T                      (B2)

K_ff = K[free][:, free] is a selection: its entries are K's, at places of K's CSR arrays known from the pattern.
Row by row, the upper triangle of A holds (i) the upper entries of K_ff (columns below n_f, K's order kept since
the free DOFs keep theirs), (ii) the upper entries of X (columns n_f + j) with the diagonal of the rigid rows always
stored, (iii) G_r^T's row (columns n_r + l); a gap row holds its zero diagonal only. The pattern (every value 1, so
that no product cancels) is known before any element matrix, so PARDISO's symbolic analysis can start while K is
assembled; the values then take no sparse product over K: (i) is a gather, X = (R^T K) T reads only the tied rows
of K (K symmetric), put on the pattern of (ii) (an entry that cancels to exactly zero stays a stored zero), and
(iii) is known with the contact set.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from fem.assembly import BlockPattern
from fem.constraints import Reduction
from fem.errors import FEError
from fem.la.pardiso import on_pattern, triu_csr

__all__ = ["BorderedLayout", "bordered_layout"]


def _rows(indptr: np.ndarray, indices: np.ndarray, data: np.ndarray, rows: np.ndarray, n_cols: int) -> sp.csr_matrix:
    """Rows ``rows`` of the CSR matrix (data, indices, indptr) with ``n_cols`` columns, as CSR (len(rows), n_cols)."""
    starts = indptr[rows].astype(np.int64)
    lengths = np.diff(indptr)[rows].astype(np.int64)
    out_ptr = np.zeros(len(rows) + 1, np.int64)
    np.cumsum(lengths, out=out_ptr[1:])
    pos = np.arange(out_ptr[-1], dtype=np.int64) + np.repeat(starts - out_ptr[:-1], lengths)
    return sp.csr_matrix((data[pos], indices[pos], out_ptr), shape=(len(rows), n_cols))


def _ones(M: sp.csr_matrix) -> sp.csr_matrix:
    """M's pattern with every stored entry 1 (a product of such patterns cancels nowhere)."""
    return sp.csr_matrix((np.ones(len(M.data)), M.indices, M.indptr), shape=M.shape)


def _upper_x(Xt: sp.spmatrix, n_f: int) -> sp.csr_matrix:
    """The entries (i, j) of X = Xt^T with i <= n_f + j (upper triangle of A), sorted CSR."""
    return triu_csr(Xt.T.tocsr(), -n_f)


@dataclass(frozen=True, eq=False)
class BorderedLayout:
    """Where the entries of the bordered matrix's upper triangle (B2) come from (module docstring).

    ``pattern``: the upper triangle of A (n_r + k, n_r + k) with every entry 1, CSR as PARDISO takes it (each row
    starting at its diagonal entry); :meth:`values` gives A with K's values on it."""

    pattern: sp.csr_matrix
    n_free: int
    src: np.ndarray  # (i): positions in K.data ...
    dst: np.ndarray  # ... and in A.data
    x_pattern: sp.csr_matrix  # (ii): pattern of the upper entries of X (n_r, n_g)
    x_dst: np.ndarray  # ... their positions in A.data
    g_data: np.ndarray  # (iii): the values of G_r^T ...
    g_dst: np.ndarray  # ... and their positions in A.data
    k_nnz: int  # entries of K's pattern (a K of another pattern is refused)
    tied: np.ndarray  # the tied DOFs (rows of R that hold entries)
    Rt: sp.csr_matrix  # R[tied]^T (n_g, len(tied))
    T: sp.csr_matrix

    def values(self, K: sp.csr_matrix) -> sp.csr_matrix:
        """The upper triangle of A with the values of K (sorted CSR on the pattern of the connectivity: the matrix
        :meth:`fem.assembly.BlockAssembly.assemble` gives)."""
        if K.nnz != self.k_nnz:
            raise FEError(f"the stiffness has {K.nnz} entries, its layout was made for a pattern of {self.k_nnz}")
        data = np.zeros(self.pattern.nnz)
        data[self.dst] = K.data[self.src]
        if self.x_pattern.nnz:
            Kt = _rows(K.indptr, K.indices, K.data, self.tied, K.shape[1])
            data[self.x_dst] = on_pattern(_upper_x(self.Rt @ Kt @ self.T, self.n_free), self.x_pattern).data
        data[self.g_dst] = self.g_data
        A = sp.csr_matrix((data, self.pattern.indices, self.pattern.indptr), shape=self.pattern.shape)
        A.has_sorted_indices = True
        return A


def bordered_layout(pattern: BlockPattern, red: Reduction, GrT: sp.csr_matrix | None) -> BorderedLayout:
    """The layout of A (B2) for K's pattern, the supports and the gap rows' G_r^T (n_r, k), sorted CSR, or None."""
    n_r, n_g = red.n, len(red.free_rigid)
    n_f = n_r - n_g
    k = GrT.shape[1] if GrT is not None else 0
    free = red.free_dof
    col = np.cumsum(free) - 1  # reduced column of a free DOF
    # (i) upper entries of K_ff, in K's order
    row = np.repeat(np.arange(len(free), dtype=pattern.indices.dtype), np.diff(pattern.indptr))
    idx = pattern.indices
    src = np.flatnonzero(free[row] & free[idx] & (idx >= row))
    r_ff = col[row[src]]
    c_ff = col[idx[src]]
    del row
    n_ff = np.bincount(r_ff, minlength=n_r)
    # (ii) upper entries of X = (R^T K T)^T, and the rigid rows' diagonal
    R = red.T[:, n_f:].tocsr()
    tied = np.flatnonzero(np.diff(R.indptr) > 0)
    Rt = R[tied].T.tocsr()
    Kt = _rows(pattern.indptr, idx, np.broadcast_to(1.0, idx.shape), tied, len(free))  # the pattern's tied rows
    diag = sp.csr_matrix((np.ones(n_g), (np.arange(n_g), n_f + np.arange(n_g))), shape=(n_g, n_r))
    Xp = _upper_x(_ones(Rt) @ Kt @ _ones(red.T) + diag, n_f)
    Xp.data[:] = 1.0
    n_x = np.diff(Xp.indptr)
    # (iii) G_r^T
    G = GrT if GrT is not None else sp.csr_matrix((n_r, 0))
    n_gr = np.diff(G.indptr)
    counts = np.concatenate([n_ff + n_x + n_gr, np.ones(k, np.int64)])
    indptr = np.zeros(n_r + k + 1, np.int64)
    np.cumsum(counts, out=indptr[1:])
    indices = np.empty(int(indptr[-1]), np.int64)
    start_ff = np.concatenate([[0], np.cumsum(n_ff)])
    dst = indptr[r_ff] + np.arange(len(src)) - start_ff[r_ff]
    indices[dst] = c_ff
    x_rows = np.repeat(np.arange(n_r), n_x)
    x_dst = indptr[x_rows] + n_ff[x_rows] + np.arange(Xp.nnz) - Xp.indptr[x_rows]
    indices[x_dst] = n_f + Xp.indices
    g_rows = np.repeat(np.arange(n_r), n_gr)
    g_dst = indptr[g_rows] + n_ff[g_rows] + n_x[g_rows] + np.arange(G.nnz) - G.indptr[g_rows]
    indices[g_dst] = n_r + G.indices
    indices[indptr[n_r:-1]] = n_r + np.arange(k)  # the gap rows' zero diagonal
    idt = np.int32 if max(len(indices), n_r + k) < np.iinfo(np.int32).max else np.int64
    P = sp.csr_matrix((np.ones(len(indices)), indices.astype(idt), indptr.astype(idt)), shape=(n_r + k, n_r + k))
    P.has_sorted_indices = True
    return BorderedLayout(P, n_f, src, dst, Xp, x_dst, np.asarray(G.data, float), g_dst, len(idx), tied, Rt, red.T)
