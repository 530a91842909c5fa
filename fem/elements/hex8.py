"""Element stiffness of 8-node hexahedra, plain (C3D8) or with incompatible modes (C3D8I-like).

Geometry and quadrature come from scikit-fem (``Basis(mesh, ElementHex1(), intorder=3)``: 2x2x2
Gauss points on the reference cube [0, 1]^3); the stiffness is computed by batched numpy kernels.

Isotropic stiffness. With shape-function gradients g_a (at a quadrature point, weight dx),

    K[(a,i),(b,j)] = sum_q dx ( lambda g_ai g_bj + mu g_aj g_bi + mu delta_ij g_a . g_b ),

which is B^T D B with D = lambda 1 1^T + mu diag(2, 2, 2, 1, 1, 1) (Voigt strains, engineering
shears). ``isotropic_stiffness`` evaluates it for any set of functions (nodal or not) as one batched
product per element, K = R^T R, where R stacks, at each Gauss point q, the 7 rows

    sqrt(lambda dx) (div),  sqrt(2 mu dx) (eps_xx, eps_yy, eps_zz),  sqrt(mu dx) (gam_xy, gam_yz, gam_xz)

of the strain operator on the interleaved DOFs (7 q x 3 nf): one BLAS product of (3nf x 7q)(7q x 3nf)
per element, with no strided permutations of the (3nf)^2 entries (3x faster than the split form
above, which it equals to round-off).

Incompatible modes (Wilson, Taylor, Beresford & Wilson 1976, "QM6"). The displacement of each
element is enriched by three bubble modes per component,

    u = sum_a N_a u_a + sum_k P_k(xi) alpha_k,   P_k = 1 - (2 xi_k - 1)^2,   k = 1, 2, 3,

which lets the element bend without parasitic shear. Their gradients use Taylor's correction,

    grad P_k (xi) = det J0 / det J(xi) * J0^-T  dP_k/dxi,

J0 the Jacobian at the element centre, so that  int grad P_k dV = det J0 J0^-T int dP_k/dxi = 0:
a constant strain field produces no work on the modes and the element passes the patch test on
distorted meshes. The 9 mode amplitudes are internal; they are condensed element by element
(batched 9x9 solves):

    K = K_uu - K_ua K_aa^-1 K_au,   alpha = -K_aa^-1 K_au u_e = -X u_e,

and X is kept to recover stresses with the modes included (``fem.recovery``).

Local node order is VTK's (= C3D8's), DOFs interleaved per node: (u_x, u_y, u_z) of node 0, ...
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import Basis, ElementHex1, MeshHex

from fem.errors import FEInputError

__all__ = [
    "SKFEM_FROM_VTK",
    "HexGeometry",
    "hex_geometry",
    "isotropic_stiffness",
    "ElementMatrices",
    "hex8_matrices",
]

# scikit-fem local node k of ElementHex1 sits at reference point doflocs[k]; VTK node P[k] sits there.
SKFEM_FROM_VTK = np.array([6, 2, 5, 7, 1, 3, 4, 0])
_VTK_FROM_SKFEM = np.argsort(SKFEM_FROM_VTK)
# VTK reference coordinates of the 8 nodes in [0, 1]^3
VTK_REF_NODES = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float
)


@dataclass(frozen=True, eq=False)
class HexGeometry:
    """Gradients at Gauss points of the 8 nodal (+ 3 incompatible) functions, and volume weights."""

    grads: np.ndarray  # (m, q, nf, 3) [1/mm], nodal functions in VTK order, then modes
    dx: np.ndarray  # (m, q) [mm^3] quadrature weight x det J
    xq: np.ndarray  # (3, q) reference coordinates of the Gauss points in [0, 1]^3


def hex_geometry(points: np.ndarray, cells: np.ndarray, incompatible: bool) -> HexGeometry:
    """Gauss-point gradients (2x2x2) of VTK-ordered hexahedra, with the Taylor-corrected modes."""
    mesh = MeshHex(np.ascontiguousarray(points.T), np.ascontiguousarray(cells[:, SKFEM_FROM_VTK].T))
    basis = Basis(mesh, ElementHex1(), intorder=3)
    detq = basis.mapping.detDF(basis.X)  # (m, q); basis.dx holds |det J| w
    if np.any(detq <= 0.0):
        bad = int(np.flatnonzero((detq <= 0.0).any(axis=1))[0])
        raise FEInputError("mesh.cells", bad, "the index of a hexahedron with det J > 0 at all Gauss points (VTK node order)",
                         "this cell is inverted or degenerate")
    dx = np.ascontiguousarray(basis.dx)  # (m, q)
    m, q = dx.shape
    nf = 11 if incompatible else 8
    g = np.empty((m, q, nf, 3))
    for k in range(8):
        g[:, :, SKFEM_FROM_VTK[k], :] = np.moveaxis(basis.basis[k][0].grad, 0, -1)
    if incompatible:
        xq = basis.X  # (3, q)
        centre = np.full((3, 1), 0.5)
        inv0 = basis.mapping.invDF(centre)[..., 0]  # (3, 3, m): d xi_k / d x_i
        det0 = basis.mapping.detDF(centre)[:, 0]  # (m,)
        dP = -4.0 * (2.0 * xq - 1.0)  # (3, q): dP_k/dxi_k, other derivatives vanish
        # grad_x P_k = (det0/detq) * sum_k' invDF0[k', i] dP_k/dxi_k' = ratio * inv0[k, i] * dP_k
        ratio = det0[:, None] / detq  # (m, q)
        for k in range(3):
            g[:, :, 8 + k, :] = (ratio[:, :, None] * dP[k][None, :, None]) * inv0[k].T[:, None, :]
    return HexGeometry(grads=g, dx=dx, xq=np.asarray(basis.X))


def isotropic_stiffness(grads: np.ndarray, dx: np.ndarray, lam: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """Element stiffness (m, 3nf, 3nf) [N/mm], DOFs interleaved; lam, mu (m,) [MPa] (K = R^T R, module docstring)."""
    m, q, nf, _ = grads.shape
    g = grads * np.sqrt(dx)[:, :, None, None]  # (m, q, nf, 3)
    sl = np.sqrt(lam)[:, None, None]
    s2 = np.sqrt(2.0 * mu)[:, None, None]
    sm = np.sqrt(mu)[:, None, None]
    R = np.zeros((m, q, 7, nf, 3))
    R[:, :, 0] = sl[..., None] * g  # divergence
    for i in range(3):  # normal strains
        R[:, :, 1 + i, :, i] = s2 * g[:, :, :, i]
    for r, (i, j) in enumerate(((0, 1), (1, 2), (0, 2))):  # engineering shears
        R[:, :, 4 + r, :, i] = sm * g[:, :, :, j]
        R[:, :, 4 + r, :, j] = sm * g[:, :, :, i]
    R = R.reshape(m, 7 * q, 3 * nf)
    return np.matmul(R.transpose(0, 2, 1), R)


@dataclass(frozen=True, eq=False)
class ElementMatrices:
    """Condensed element stiffness (m, 24, 24) and mode recovery X (m, 9, 24) or None."""

    stiffness: np.ndarray
    condensation: np.ndarray | None
    geometry: HexGeometry


def hex8_matrices(points, cells, lam, mu, incompatible: bool = True, chunk: int = 4000) -> ElementMatrices:
    """Stiffness of all cells (C3D8 or C3D8I-like with condensed modes), chunked to bound memory."""
    geo = hex_geometry(points, cells, incompatible)
    m = len(cells)
    Ke = np.empty((m, 24, 24))
    X = np.empty((m, 9, 24)) if incompatible else None
    for s in range(0, m, chunk):
        sl = slice(s, min(s + chunk, m))
        K = isotropic_stiffness(geo.grads[sl], geo.dx[sl], lam[sl], mu[sl])
        if incompatible:
            Kaa, Kau = K[:, 24:, 24:], K[:, 24:, :24]
            Xs = np.linalg.solve(Kaa, Kau)
            Kc = K[:, :24, :24] - np.matmul(K[:, :24, 24:], Xs)
            Ke[sl] = 0.5 * (Kc + Kc.transpose(0, 2, 1))  # symmetric to round-off; exactly, per chunk in cache
            X[sl] = Xs
        else:
            Ke[sl] = K  # R^T R: exactly symmetric
    return ElementMatrices(stiffness=Ke, condensation=X, geometry=geo)
