"""Bilinear faces of hexahedra: shape functions, closest-point projection and consistent surface mass.

A face X (4, 3) maps (xi, eta) in [-1, 1]^2 to x = sum_b N_b(xi, eta) X_b; the contact search
(:mod:`fem.contact.search`) projects slave points on master faces with it, and the pressure
recovery uses the consistent mass M_ab = int N_a N_b dA of the slave faces.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["bilinear", "project_to_faces", "surface_mass"]


def bilinear(xi, eta):
    """Shape functions of a 4-node face and their derivatives at (xi, eta): N, dN/dxi, dN/deta (..., 4)."""
    N = 0.25 * np.stack([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)], -1)
    dxi = 0.25 * np.stack([-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)], -1)
    deta = 0.25 * np.stack([-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)], -1)
    return N, dxi, deta


def project_to_faces(xs: np.ndarray, X: np.ndarray, iters: int = 12, limit: float = 2.0):
    """Closest-point projection of points xs (p, 3) on bilinear faces X (p, 4, 3): xi, eta, x_p.

    The face coordinates are kept in [-limit, limit] (1: on the face itself; 2: its extension,
    which lets the contact search slide across face boundaries)."""
    xi = np.zeros(len(xs))
    eta = np.zeros(len(xs))
    for _ in range(iters):
        N, dxi, deta = bilinear(xi, eta)
        x = np.einsum("pa,pai->pi", N, X)
        t1 = np.einsum("pa,pai->pi", dxi, X)
        t2 = np.einsum("pa,pai->pi", deta, X)
        r = x - xs
        a11, a12, a22 = (t1 * t1).sum(1), (t1 * t2).sum(1), (t2 * t2).sum(1)
        b1, b2 = -(t1 * r).sum(1), -(t2 * r).sum(1)
        det = a11 * a22 - a12**2
        xi = np.clip(xi + (a22 * b1 - a12 * b2) / det, -limit, limit)
        eta = np.clip(eta + (a11 * b2 - a12 * b1) / det, -limit, limit)
    N, dxi, deta = bilinear(xi, eta)
    return xi, eta, np.einsum("pa,pai->pi", N, X)


def surface_mass(points: np.ndarray, faces: np.ndarray) -> sp.csr_matrix:
    """Consistent mass M_ab = int N_a N_b dA of bilinear faces (f, 4) [mm^2], 2 x 2 Gauss points; (n, n)."""
    g, wg = np.polynomial.legendre.leggauss(2)
    xi, eta = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    N, dxi, deta = bilinear(xi, eta)
    X = points[faces]
    dA = np.linalg.norm(np.cross(np.einsum("qa,fai->fqi", dxi, X), np.einsum("qa,fai->fqi", deta, X)), axis=-1)
    Me = np.einsum("fq,q,qa,qb->fab", dA, np.outer(wg, wg).ravel(), N, N)
    rows = np.repeat(faces, 4, axis=1).ravel()
    cols = np.tile(faces, (1, 4)).ravel()
    n = len(points)
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(n, n))

