"""Element kernels: assembly against scikit-fem, patch test of the incompatible-mode hexahedron,
and a short cantilever against beam theory."""

import numpy as np
from skfem import Basis, ElementHex1, ElementVector, MeshHex, asm
from skfem.models.elasticity import linear_elasticity

from fem import STEEL, SolverOptions, solve
from fem.assembly import assemble_blocks
from fem.elements.hex8 import SKFEM_FROM_VTK, hex8_matrices
from fem.recovery import gauss_stress
from fem.verification import ModelSetup, cantilever
from fem.mesh import primitives as prim
from fem.mesh.hexmesh import HEX_FACES


def _distorted_box(seed=1):
    m = prim.box("b", np.linspace(0, 3, 4), np.linspace(0, 2, 3) ** 1.3, np.linspace(0, 1, 3))
    rng = np.random.default_rng(seed)
    return m, m.points + 0.05 * rng.standard_normal(m.points.shape)


def _lame(m):
    return np.full(m.n_cells, STEEL.lam), np.full(m.n_cells, STEEL.mu)


def test_hex8_assembly_matches_scikit_fem():
    m, pts = _distorted_box()
    lam, mu = _lame(m)
    K = assemble_blocks(hex8_matrices(pts, m.cells, lam, mu, incompatible=False).stiffness, m.cells, len(pts))
    sm = MeshHex(pts.T.copy(), m.cells[:, SKFEM_FROM_VTK].T.copy())
    Ks = asm(linear_elasticity(STEEL.lam, STEEL.mu), Basis(sm, ElementVector(ElementHex1()), intorder=3))
    # same quadrature, same DOF order (interleaved): equal to round-off (1e-12 of the largest entry)
    assert abs(K - Ks).max() < 1e-12 * abs(Ks).max()


def test_hex8i_patch_test_on_distorted_mesh():
    m, pts = _distorted_box()
    lam, mu = _lame(m)
    em = hex8_matrices(pts, m.cells, lam, mu, incompatible=True)
    K = assemble_blocks(em.stiffness, m.cells, len(pts))
    A = np.array([[1e-3, 2e-4, 0], [3e-4, -5e-4, 1e-4], [0, 2e-4, 7e-4]])
    u = pts @ A.T
    r = (K @ u.ravel()).reshape(-1, 3)
    bf = prim.boundary_faces(m)
    boundary = np.unique(m.cells[bf[:, 0][:, None], HEX_FACES[bf[:, 1]]])
    inner = np.setdiff1d(np.arange(len(pts)), boundary)
    assert len(inner) > 0
    # a linear field is reproduced: no out-of-balance force at interior nodes (round-off of K ~ 1e6)
    assert np.abs(r[inner]).max() < 1e-9 * np.abs(K).max()
    # the condensed modes stay at zero (Taylor's correction) and the stress is exact everywhere
    alpha = np.matmul(em.condensation, u[m.cells].reshape(-1, 24, 1))
    assert np.abs(alpha).max() < 1e-14
    eps = 0.5 * (A + A.T)
    sig = STEEL.lam * np.trace(eps) * np.eye(3) + 2 * STEEL.mu * eps
    ref = np.array([sig[0, 0], sig[1, 1], sig[2, 2], sig[0, 1], sig[1, 2], sig[0, 2]])
    sq = gauss_stress(em.geometry, m.cells, u, em.condensation, lam, mu)
    assert np.abs(sq - ref).max() < 1e-9 * np.abs(ref).max()


def _beam(element, n_depth):
    mesh, model, ref = cantilever(length=12.0, depth=4.0, width=4.0, n_depth=n_depth,
                                  setup=ModelSetup(solver=SolverOptions(element=element)))
    r = solve(mesh, model)
    p = mesh.points
    top = np.flatnonzero(np.isclose(p[:, 0], ref["length"] / 2) & np.isclose(p[:, 1], ref["depth"] / 2))
    tip = r.displacement[mesh.face_set_points("beam/xmax"), 1].mean()
    return r.stress[top, 0].mean() / ref["sigma_mid"], -tip / ref["tip_timoshenko"]


# Tip deflection of the 3D clamped solid relative to Timoshenko (kappa = 5/6), C3D8I-like:
# 0.9686, 0.9762, 0.9782 with 4, 8, 12 elements through the depth -> about 0.980 converged. The
# clamped face also holds the warping and Poisson contraction of the section, which beam theory
# leaves free: the solid is 2 % stiffer than the beam. The band [0.96, 1.0] takes that 2 % and
# the 1.2 % discretization error at 4 elements through the depth.
DEFLECTION_BAND = (0.96, 1.0)


def test_cantilever_hex8i_against_beam_theory():
    """L/h = 3 cantilever (a stubby, tooth-like beam), 4 elements through the depth."""
    s, d = _beam("hex8i", 4)
    # mid-span bending stress: the Saint-Venant flexure solution is exact there (1.5 depths from
    # the clamp and the load); measured 1.00002, 0.5 % allows the remaining end effects
    assert abs(s - 1.0) < 0.005
    assert DEFLECTION_BAND[0] < d < DEFLECTION_BAND[1]


def test_cantilever_plain_hex8_fails_the_same_tolerance():
    """Plain 8-node hexahedra on the same mesh are too stiff in bending (measured 0.937)."""
    s, d = _beam("hex8", 4)
    assert not (DEFLECTION_BAND[0] < d < DEFLECTION_BAND[1])


def test_hex8_job_equals_hex8_matrices_and_reports_an_inverted_cell():
    """Hex8Job (a background thread joined by the caller, chunks taken one at a time): the matrices of
    hex8_matrices exactly; an inverted cell raises from result() as from hex8_matrices; cancel() stops it."""
    import pytest
    from fem.elements.hex8 import Hex8Job
    from fem.errors import FEInputError

    from threadpoolctl import threadpool_info

    def blas():
        return [i["num_threads"] for i in threadpool_info() if i.get("user_api") == "blas"]

    before = blas()
    m, pts = _distorted_box()
    lam, mu = _lame(m)
    ref = hex8_matrices(pts, m.cells, lam, mu, chunk=2)
    job = Hex8Job(pts, m.cells, lam, mu, chunk=2)
    em = job.result()
    np.testing.assert_array_equal(em.stiffness, ref.stiffness)
    np.testing.assert_array_equal(em.condensation, ref.condensation)
    np.testing.assert_array_equal(em.geometry.dx, ref.geometry.dx)
    bad = m.cells.copy()
    bad[5] = bad[5][[4, 5, 6, 7, 0, 1, 2, 3]]  # top and bottom faces swapped: inside out
    with pytest.raises(FEInputError) as e_ref:
        hex8_matrices(pts, bad, lam, mu, chunk=2)
    with pytest.raises(FEInputError) as e_job:
        Hex8Job(pts, bad, lam, mu, chunk=2).result()
    assert str(e_job.value) == str(e_ref.value)
    job = Hex8Job(pts, m.cells, lam, mu, chunk=1)
    job.cancel()
    job.cancel()
    assert blas() == before  # the BLAS limit held meanwhile is lifted again
