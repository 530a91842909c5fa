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


def project_to_faces(xs: np.ndarray, X: np.ndarray, iters: int = 12, limit: float = 2.0, tol: float = 1e-13):
    """Closest-point projection of points xs (p, 3) on bilinear faces X (p, 4, 3): xi, eta, x_p.

    Newton iterations on (xi, eta), at most ``iters``; a point stops once its step is below ``tol``
    (in face coordinates; Newton converges quadratically, most points in 3-4 steps), so later steps
    only run on the points still moving. The face coordinates are kept in [-limit, limit] (1: on the
    face itself; 2: its extension, which lets the contact search slide across face boundaries)."""
    xi = np.zeros(len(xs))
    eta = np.zeros(len(xs))
    idx = np.arange(len(xs))
    Xa, xa = X, xs
    for _ in range(iters):
        if not len(idx):
            break
        N, dxi, deta = bilinear(xi[idx], eta[idx])
        r = np.matmul(N[:, None, :], Xa)[:, 0] - xa
        t1 = np.matmul(dxi[:, None, :], Xa)[:, 0]
        t2 = np.matmul(deta[:, None, :], Xa)[:, 0]
        a11, a12, a22 = (t1 * t1).sum(1), (t1 * t2).sum(1), (t2 * t2).sum(1)
        b1, b2 = -(t1 * r).sum(1), -(t2 * r).sum(1)
        det = a11 * a22 - a12**2
        x_new = np.clip(xi[idx] + (a22 * b1 - a12 * b2) / det, -limit, limit)
        e_new = np.clip(eta[idx] + (a11 * b2 - a12 * b1) / det, -limit, limit)
        moving = np.maximum(np.abs(x_new - xi[idx]), np.abs(e_new - eta[idx])) > tol
        xi[idx], eta[idx] = x_new, e_new
        idx, Xa, xa = idx[moving], Xa[moving], xa[moving]
    N = bilinear(xi, eta)[0]
    return xi, eta, np.matmul(N[:, None, :], X)[:, 0]


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

