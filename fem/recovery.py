"""Stress recovery: Gauss-point stresses extrapolated to the nodes and averaged.

Method. In each element the strain is evaluated at the 2x2x2 Gauss points, including the
incompatible modes alpha = -X u_e recovered from the condensation,

    grad u (x_q) = sum_a u_a (x) g_a(x_q) + sum_k alpha_k (x) g_k(x_q),

and sigma = lambda tr(eps) I + 2 mu eps. The eight Gauss values are extrapolated to the element's
corner nodes with the trilinear interpolant through them (sigma_a = sum_q [N(x_q)]^-1_aq sigma_q),
and nodal values are averaged over the cells sharing the node. Gauss points are the
superconvergent stress points of the element, so this is the standard (ABAQUS-like) nodal
average; it is exact for a linear stress field on parallelepipeds.

Von Mises stress sqrt(3/2 s:s) with s the deviator; principal stresses are the eigenvalues of the
nodal tensor, sorted sigma_1 >= sigma_2 >= sigma_3. Components are stored in the VTK order
(xx, yy, zz, xy, yz, xz) [MPa].
"""

from __future__ import annotations

import numpy as np

from fem.elements.hex8 import VTK_REF_NODES, HexGeometry, run_chunks

__all__ = ["gauss_stress", "nodal_average", "von_mises", "principal", "tensor"]


def gauss_stress(geo: HexGeometry, cells: np.ndarray, u: np.ndarray, X: np.ndarray | None, lam, mu,
                 chunk: int = 4000) -> np.ndarray:
    """Stresses (m, q, 6) [MPa] at the Gauss points; u (n, 3) [mm]; X the mode recovery or None.

    Chunks of ``chunk`` cells run on the kernel threads (:func:`fem.elements.hex8.run_chunks`; numpy releases the
    GIL in their products); each writes its own rows, so the result does not depend on the threads."""
    m, q = geo.dx.shape
    lam = np.broadcast_to(np.asarray(lam, float), (m,))
    mu = np.broadcast_to(np.asarray(mu, float), (m,))
    s = np.empty((m, q, 6))

    def run(start: int) -> None:
        sl = slice(start, min(start + chunk, m))
        ue = u[cells[sl]]  # (c, 8, 3)
        if X is not None:
            alpha = -np.matmul(X[sl], ue.reshape(-1, 24, 1)).reshape(-1, 3, 3)  # (c, mode k, component i)
            ue = np.concatenate([ue, alpha], axis=1)
        H = np.einsum("mai,mqaj->mqij", ue, geo.grads[sl])  # grad u: H_ij = d u_i / d x_j
        eps = 0.5 * (H + H.transpose(0, 1, 3, 2))
        tr = np.trace(eps, axis1=2, axis2=3)
        la, mu_ = lam[sl, None], mu[sl, None]
        for c, (i, j) in enumerate(((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (0, 2))):
            s[sl, :, c] = 2.0 * mu_ * eps[..., i, j] + (la * tr if i == j else 0.0)

    run_chunks(run, m, chunk)
    return s


def _extrapolation(xq: np.ndarray) -> np.ndarray:
    """(8 nodes, q) matrix taking Gauss values to corner values of the trilinear interpolant."""
    x, y, z = xq
    cols = []
    for a in VTK_REF_NODES:
        cols.append((x if a[0] else 1 - x) * (y if a[1] else 1 - y) * (z if a[2] else 1 - z))
    return np.linalg.inv(np.array(cols).T)  # N[q, a] inverted -> [a, q]


def nodal_average(values_q: np.ndarray, xq: np.ndarray, cells: np.ndarray, n_nodes: int) -> np.ndarray:
    """Gauss values (m, q, c) extrapolated to corners and averaged over the cells of each node: (n, c)."""
    E = _extrapolation(xq)
    corner = np.einsum("aq,mqc->mac", E, values_q)
    nc = values_q.shape[2]
    out = np.zeros((n_nodes, nc))
    flat = cells.ravel()
    for c in range(nc):
        out[:, c] = np.bincount(flat, weights=corner[:, :, c].ravel(), minlength=n_nodes)
    count = np.bincount(flat, minlength=n_nodes)
    return out / np.maximum(count, 1)[:, None]


def tensor(s: np.ndarray) -> np.ndarray:
    """(..., 3, 3) symmetric tensors from (..., 6) VTK-ordered components."""
    T = np.empty(s.shape[:-1] + (3, 3))
    T[..., 0, 0], T[..., 1, 1], T[..., 2, 2] = s[..., 0], s[..., 1], s[..., 2]
    T[..., 0, 1] = T[..., 1, 0] = s[..., 3]
    T[..., 1, 2] = T[..., 2, 1] = s[..., 4]
    T[..., 0, 2] = T[..., 2, 0] = s[..., 5]
    return T


def von_mises(s: np.ndarray) -> np.ndarray:
    """Von Mises equivalent stress [MPa] of (..., 6) components."""
    d = s[..., :3] - s[..., :3].mean(axis=-1, keepdims=True)
    return np.sqrt(1.5 * ((d**2).sum(-1) + 2.0 * (s[..., 3:] ** 2).sum(-1)))


def principal(s: np.ndarray) -> np.ndarray:
    """Principal stresses (..., 3) [MPa], descending."""
    return np.linalg.eigvalsh(tensor(s))[..., ::-1]
