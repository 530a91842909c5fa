"""fem.elements.hex8.hex_geometry against scikit-fem's mapping (another code path: skfem's Basis and MappingIsoparametric),
and the element stiffness R^T R against the split form lambda A + mu A^swap + mu (g.g) I of the module docstring."""

import numpy as np
import pytest
from skfem import Basis, ElementHex1, MeshHex

from fem.elements.hex8 import SKFEM_FROM_VTK, hex_geometry, isotropic_stiffness


@pytest.fixture(scope="module")
def distorted():
    """A 4x3x5 box of hexahedra (VTK order) with every node moved at random by up to 15 % of an element."""
    rng = np.random.default_rng(3)
    nx, ny, nz = 5, 4, 6
    g = np.stack(np.meshgrid(np.linspace(0, 4, nx), np.linspace(0, 3, ny), np.linspace(0, 5, nz), indexing="ij"), -1)
    pts = g.reshape(-1, 3) + rng.uniform(-0.15, 0.15, (nx * ny * nz, 3))
    idx = np.arange(nx * ny * nz).reshape(nx, ny, nz)

    def n(a, b, c):
        return idx[a:nx - 1 + a, b:ny - 1 + b, c:nz - 1 + c].ravel()

    cells = np.stack([n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(0, 1, 0), n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1)], 1)
    return pts, cells


def test_gradients_and_weights_equal_scikit_fem(distorted):
    pts, cells = distorted
    basis = Basis(MeshHex(pts.T.copy(), cells[:, SKFEM_FROM_VTK].T.copy()), ElementHex1(), intorder=3)
    geo = hex_geometry(pts, cells, incompatible=False)
    ref = np.empty_like(geo.grads)
    for k in range(8):
        ref[:, :, SKFEM_FROM_VTK[k], :] = np.moveaxis(basis.basis[k][0].grad, 0, -1)
    np.testing.assert_allclose(geo.grads, ref, rtol=0, atol=1e-13 * np.abs(ref).max())
    np.testing.assert_allclose(geo.dx, basis.dx, rtol=1e-13)
    np.testing.assert_array_equal(geo.xq, basis.X)
    # the Taylor-corrected modes integrate to zero over each element (the patch test's condition)
    modes = hex_geometry(pts, cells, incompatible=True).grads[:, :, 8:, :]
    assert np.abs(np.einsum("mq,mqki->mki", geo.dx, modes)).max() < 1e-12


def test_stiffness_equals_the_split_form(distorted):
    pts, cells = distorted
    geo = hex_geometry(pts, cells, incompatible=True)
    m, q, nf, _ = geo.grads.shape
    lam, mu = np.full(m, 1.2e5), np.full(m, 8.0e4)
    G = geo.grads.reshape(m, q, 3 * nf) * np.sqrt(geo.dx)[:, :, None]
    A5 = np.einsum("mqa,mqb->mab", G, G).reshape(m, nf, 3, nf, 3)  # sum_q dx g_ai g_bj
    M = np.einsum("mqak,mqbk,mq->mab", geo.grads, geo.grads, geo.dx)
    K = (lam[:, None, None, None, None] * A5 + mu[:, None, None, None, None] * A5.transpose(0, 1, 4, 3, 2)
         + mu[:, None, None, None, None] * M[:, :, None, :, None] * np.eye(3)[None, None, :, None, :])
    K = K.reshape(m, 3 * nf, 3 * nf)
    np.testing.assert_allclose(isotropic_stiffness(geo.grads, geo.dx, lam, mu), K, rtol=0, atol=1e-12 * np.abs(K).max())


@pytest.mark.parametrize("incompatible", [True, False])
def test_threaded_chunks_equal_serial(distorted, incompatible):
    """The element kernels on two threads give the serial matrices bit for bit (same chunks, same operations)."""
    from fem.elements.hex8 import hex8_matrices, kernel_threads

    pts, cells = distorted
    lam, mu = np.full(len(cells), 1.2e5), np.full(len(cells), 8e4)
    one = hex8_matrices(pts, cells, lam, mu, incompatible, chunk=7, threads=1)
    two = hex8_matrices(pts, cells, lam, mu, incompatible, chunk=7, threads=2)
    np.testing.assert_array_equal(one.stiffness, two.stiffness)
    if incompatible:
        np.testing.assert_array_equal(one.condensation, two.condensation)
    assert kernel_threads() >= 1
