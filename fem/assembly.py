"""Global assembly of element matrices into a sparse matrix with 3x3 node blocks.

Element matrices (m, 3k, 3k), DOFs interleaved per node (global DOF 3 n + i), are summed straight into
the CSR arrays of the global matrix, without a COO list of the m (3k)^2 scalar entries:

1. the node-block pattern is N^T N, N the (m, n) cell-node incidence (a sparse product), with sorted
   block columns: block row r holds nb_r blocks starting at bp_r;
2. the element block (e, a, b) (row node r = conn[e, a], column node c = conn[e, b]) is block p of the
   pattern (looked up by sampling the pattern with the block indices as values);
3. in CSR the 3 nb_r entries of scalar row 3 r + i start at 9 bp_r + 3 i nb_r, and the block's column j
   is entry 3 (p - bp_r) + j of that row. The three entries (j = 0, 1, 2) of element row (e, a, i) and
   element column node b are contiguous in ``Ke`` and in the CSR data, so the sum over elements is one
   product of a 0/1 scatter matrix (one entry per element row-triple, at row 2 bp_r + i nb_r + p) with
   ``Ke`` viewed as (m k 3 k, 3): no copy of the element matrices, no sort of their entries.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["BlockPattern", "block_pattern", "BlockAssembly", "block_assembly", "assemble_blocks", "surface_load",
           "face_node_areas"]


@dataclass(frozen=True, eq=False)
class BlockPattern:
    """The CSR pattern (3n, 3n) of a global matrix with 3x3 node blocks, sorted: ``nodes`` the node-block pattern
    N^T N of step (1) (n, n), ``indptr`` and ``indices`` its scalar rows (step 3). Known from the connectivity alone
    (:func:`block_pattern`), cheaply: the scatter of step (2)-(3) is the expensive part of an assembly."""

    nodes: sp.csr_matrix
    indptr: np.ndarray
    indices: np.ndarray

    @property
    def n_nodes(self) -> int:
        return self.nodes.shape[0]

    def csr(self, data: np.ndarray) -> sp.csr_matrix:
        """The (3n, 3n) matrix with these values (one per stored entry) on the pattern."""
        n = 3 * self.n_nodes
        K = sp.csr_matrix((data, self.indices, self.indptr), shape=(n, n))
        K.has_sorted_indices = True
        return K


@dataclass(frozen=True, eq=False)
class BlockAssembly:
    """Where the entries of the element matrices of a connectivity go in the CSR arrays of the global matrix.

    ``scatter`` (nnz / 3, m k 3 k) is the 0/1 matrix of step (3); ``pattern`` the CSR pattern (3n, 3n). Known from
    the connectivity alone, before any element matrix (:func:`block_assembly`)."""

    scatter: sp.csc_matrix
    pattern: BlockPattern

    def assemble(self, Ke: np.ndarray) -> sp.csr_matrix:
        """Sum element matrices (m, 3k, 3k) into the (3n, 3n) CSR matrix (sorted indices)."""
        summed = self.scatter @ np.asarray(Ke, float).reshape(self.scatter.shape[1], 3)
        return self.pattern.csr(np.asarray(summed).ravel())


def _index_type(*sizes: int):
    return np.int32 if max(sizes) < np.iinfo(np.int32).max else np.int64


def block_pattern(conn: np.ndarray, n_nodes: int) -> BlockPattern:
    """Steps (1) and (3) of the module docstring without the scatter: the pattern of connectivity (m, k)."""
    m, k = conn.shape
    c = np.asarray(conn, np.int64)
    N = sp.csr_matrix((np.ones(m * k), c.ravel(), np.arange(0, m * k + 1, k)), shape=(m, n_nodes))
    P = (N.T @ N).tocsr()  # (1) node-block pattern
    P.sort_indices()
    nb = np.diff(P.indptr).astype(np.int64)
    bp = P.indptr[:-1].astype(np.int64)
    nnz = 9 * P.nnz
    idt = _index_type(nnz, 3 * n_nodes, m * k * 3 * k)
    lengths = np.repeat(3 * nb, 3)  # entries of scalar row 3 r + i
    indptr = np.zeros(3 * n_nodes + 1, idt)
    np.cumsum(lengths, out=indptr[1:])
    cols3 = (3 * P.indices.astype(idt)[:, None] + np.arange(3, dtype=idt)).ravel()  # block row r's columns, in order
    shift = (6 * bp[:, None] + 3 * np.arange(3)[None, :] * nb[:, None]).ravel().astype(idt)
    indices = cols3[np.arange(nnz, dtype=idt) - np.repeat(shift, lengths)]  # the same columns for i = 0, 1, 2
    return BlockPattern(P, indptr, indices)


def block_assembly(conn: np.ndarray, n_nodes: int, pattern: BlockPattern | None = None) -> BlockAssembly:
    """Steps (1)-(3) of the module docstring for connectivity (m, k); ``pattern``: its :func:`block_pattern` if
    already known."""
    m, k = conn.shape
    c = np.asarray(conn, np.int64)
    if pattern is None:
        pattern = block_pattern(conn, n_nodes)
    P = pattern.nodes
    nb = np.diff(P.indptr).astype(np.int64)
    bp = P.indptr[:-1].astype(np.int64)
    M = m * k * 3 * k
    idt = _index_type(9 * P.nnz, 3 * n_nodes, M)
    # (2) block index p of each element block (e, a, b): the pattern sampled with values 0, 1, ... (exact in float64)
    Q = sp.csr_matrix((np.arange(P.nnz, dtype=float), P.indices, P.indptr), shape=P.shape)
    r = np.broadcast_to(c[:, :, None], (m, k, k)).ravel()
    p = np.asarray(Q[r, np.broadcast_to(c[:, None, :], (m, k, k)).ravel()]).reshape(m, k, 1, k).astype(np.int64)
    # (3) row (e, a, i, b) of Ke.reshape(-1, 3) goes to row 2 bp_r + i nb_r + p of the CSR data viewed as (nnz / 3, 3)
    rho = p + (2 * bp[c])[:, :, None, None] + np.arange(3)[None, None, :, None] * nb[c][:, :, None, None]
    S = sp.csc_matrix((np.ones(M), rho.ravel().astype(idt), np.arange(M + 1, dtype=idt)), shape=(3 * P.nnz, M))
    return BlockAssembly(S, pattern)


def assemble_blocks(Ke: np.ndarray, conn: np.ndarray, n_nodes: int) -> sp.csr_matrix:
    """Sum element matrices (m, 3k, 3k) over connectivity (m, k) into a (3n, 3n) CSR matrix (sorted indices)."""
    return block_assembly(conn, n_nodes).assemble(Ke)


def surface_load(points: np.ndarray, faces: np.ndarray, traction) -> tuple[np.ndarray, np.ndarray]:
    """Consistent nodal forces [N] of a uniform traction [MPa] on bilinear faces (k, 4): (nodes, forces)."""
    w = face_node_areas(points, faces)  # (k, 4) [mm^2]
    f = w[:, :, None] * np.asarray(traction, float)[None, None, :]
    return faces.ravel(), f.reshape(-1, 3)


_G = np.array([-1.0, 1.0]) / np.sqrt(3.0)
_XI, _ETA = (a.ravel() for a in np.meshgrid(_G, _G, indexing="ij"))
# bilinear shape functions of a face (nodes a, b, c, d at (-,-), (+,-), (+,+), (-,+)) at 2x2 Gauss points
_NF = 0.25 * np.stack([(1 - _XI) * (1 - _ETA), (1 + _XI) * (1 - _ETA), (1 + _XI) * (1 + _ETA), (1 - _XI) * (1 + _ETA)], axis=1)
_DXI = 0.25 * np.stack([-(1 - _ETA), (1 - _ETA), (1 + _ETA), -(1 + _ETA)], axis=1)
_DETA = 0.25 * np.stack([-(1 - _XI), -(1 + _XI), (1 + _XI), (1 - _XI)], axis=1)


def face_node_areas(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Integrals of the 4 bilinear shape functions over each face (k, 4) [mm^2] (2x2 Gauss)."""
    X = points[faces]  # (k, 4, 3)
    t1 = np.einsum("qa,kai->kqi", _DXI, X)
    t2 = np.einsum("qa,kai->kqi", _DETA, X)
    dA = np.linalg.norm(np.cross(t1, t2), axis=-1)  # (k, q); Gauss weights are 1
    return np.einsum("qa,kq->ka", _NF, dA)
