"""Global assembly of element matrices into a sparse matrix with 3x3 node blocks.

Element matrices (m, 3k, 3k), DOFs interleaved per node (global DOF 3 n + i), are summed into
node blocks: the (row node, column node) pairs are made unique once (one sort of m k^2 keys) and
each of the 9 block components is accumulated by ``np.bincount``. The block matrix (BSR) is then
converted to CSR. This avoids the COO -> CSR conversion of m (3k)^2 scalar entries.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["assemble_blocks", "surface_load", "face_node_areas"]


def assemble_blocks(Ke: np.ndarray, conn: np.ndarray, n_nodes: int) -> sp.csr_matrix:
    """Sum element matrices (m, 3k, 3k) over connectivity (m, k) into a (3n, 3n) CSR matrix."""
    m, k = conn.shape
    rows = np.broadcast_to(conn[:, :, None], (m, k, k)).ravel().astype(np.int64)
    cols = np.broadcast_to(conn[:, None, :], (m, k, k)).ravel().astype(np.int64)
    keys, inv = np.unique(rows * n_nodes + cols, return_inverse=True)
    blocks = Ke.reshape(m, k, 3, k, 3).transpose(0, 1, 3, 2, 4).reshape(m * k * k, 9)
    data = np.empty((len(keys), 9))
    for c in range(9):
        data[:, c] = np.bincount(inv, weights=blocks[:, c], minlength=len(keys))
    brow = keys // n_nodes
    indptr = np.searchsorted(brow, np.arange(n_nodes + 1)).astype(np.int64)
    K = sp.bsr_matrix((data.reshape(-1, 3, 3), keys % n_nodes, indptr), shape=(3 * n_nodes, 3 * n_nodes))
    return K.tocsr()


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
