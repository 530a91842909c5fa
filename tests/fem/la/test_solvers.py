"""Sparse backends: PARDISO Schur mode against dense algebra, the scipy fallback, VTU output."""

import meshio
import numpy as np
import pytest
import scipy.sparse as sp

from fem import SolverOptions, solve
from fem.errors import FEError
from fem.la import pardiso
from fem.la.linsolve import linear_solve, rigid_body_modes, schur_system
from fem.verification import ModelSetup, cantilever, hertz_line

needs_mkl = pytest.mark.skipif(not pardiso.available(), reason="MKL PARDISO not loadable here")


def _spd(n=300, seed=0):
    rng = np.random.default_rng(seed)
    A = sp.random(n, n, density=0.02, random_state=seed)
    return (A @ A.T + sp.eye(n) * 5).tocsr(), rng


@needs_mkl
@pytest.mark.parametrize("definite", [True, False])
def test_pardiso_schur_against_dense(definite):
    K, rng = _spd()
    C = np.sort(rng.choice(K.shape[0], 25, replace=False))
    R = np.setdiff1d(np.arange(K.shape[0]), C)
    Kd = K.toarray()
    S_ref = Kd[np.ix_(C, C)] - Kd[np.ix_(C, R)] @ np.linalg.solve(Kd[np.ix_(R, R)], Kd[np.ix_(R, C)])
    f = rng.standard_normal(K.shape[0])
    for method in ("pardiso", "superlu"):
        sysm = schur_system(K, C, method, definite=definite)
        assert np.abs(sysm.schur - S_ref).max() < 1e-10 * np.abs(S_ref).max()
        # solving S u_C = f~_C in the callback must give the solution of the whole system
        u = sysm.solve(f, lambda fc: np.linalg.solve(sysm.schur, fc))
        assert np.abs(Kd @ u - f).max() < 1e-10 * np.abs(f).max()


@needs_mkl
@pytest.mark.parametrize("definite", [True, False])
def test_pardiso_schur_of_bordered_matrix(definite):
    """Stiffness bordered by constraint rows with a zero diagonal, the rows in C: Cholesky of K_RR (mtype 2)
    and the indefinite factorization give the dense Schur complement S = -G K^-1 G^T and the solution."""
    K, rng = _spd()
    G = sp.random(20, K.shape[0], density=0.05, random_state=4, format="csr")
    A = sp.bmat([[K, G.T], [G, sp.csr_matrix((20, 20))]], format="csr")  # no stored diagonal in the gap rows
    C = K.shape[0] + np.arange(20)
    Gd = G.toarray()
    S_ref = -Gd @ np.linalg.solve(K.toarray(), Gd.T)
    sysm = schur_system(A, C, "pardiso", definite=definite)
    assert np.abs(sysm.schur - S_ref).max() < 1e-10 * np.abs(S_ref).max()
    f = rng.standard_normal(A.shape[0])
    u = sysm.solve(f, lambda fc: np.linalg.solve(sysm.schur, fc))
    assert np.abs(A @ u - f).max() < 1e-9 * np.abs(f).max()


@pytest.mark.parametrize("method", [pytest.param("pardiso", marks=needs_mkl), "superlu"])
def test_schur_system_of_an_upper_triangle(method):
    """schur_system(..., upper=True): the bordered matrix given by its upper triangle (as fem.analysis builds it)
    gives the Schur complement and the solution of the whole symmetric matrix."""
    K, rng = _spd()
    G = sp.random(20, K.shape[0], density=0.05, random_state=4, format="csr")
    A = sp.bmat([[K, G.T], [G, sp.csr_matrix((20, 20))]], format="csr")
    C = K.shape[0] + np.arange(20)
    full = schur_system(A, C, method)
    up = schur_system(pardiso.upper_csr(A), C, method, upper=True)
    assert np.abs(up.schur - full.schur).max() <= 1e-12 * np.abs(full.schur).max()
    f = rng.standard_normal(A.shape[0])
    u = up.solve(f, lambda fc: np.linalg.solve(up.schur, fc))
    assert np.abs(A @ u - f).max() < 1e-9 * np.abs(f).max()


@needs_mkl
def test_pardiso_refuses_a_matrix_given_as_upper_that_is_not():
    K, _ = _spd(40, seed=3)
    with pytest.raises(FEError, match="not one"):
        pardiso.Pardiso(K, None, upper=True)  # the whole symmetric matrix: rows do not start at the diagonal


@pytest.mark.parametrize("k", [-3, 0, 2])
def test_triu_csr_equals_scipy_triu(k):
    """triu_csr(K, k): scipy.sparse.triu's entries, sorted CSR, also from a matrix with duplicate entries."""
    K, _ = _spd(60, seed=8)
    K = sp.csr_matrix(K)
    e = K.indptr[5] - 1  # row 4's last entry, stored again at the end of row 4 (unsorted duplicates)
    dup = sp.csr_matrix((np.insert(K.data, e + 1, 1.5), np.insert(K.indices, e + 1, K.indices[e]),
                         K.indptr + (np.arange(len(K.indptr)) >= 5)), shape=K.shape)
    assert not dup.has_canonical_format
    U = pardiso.triu_csr(dup, k)
    assert U.has_sorted_indices
    np.testing.assert_array_equal(U.toarray(), sp.triu(dup, k).toarray())


def test_on_pattern_puts_values_on_a_larger_pattern():
    """on_pattern: the values of a matrix whose product dropped exact zeros, on the pattern analysed before."""
    K, _ = _spd(120, seed=7)
    P = pardiso.upper_csr(K)
    A = P.copy()
    A.data[::5] = 0.0
    A.eliminate_zeros()
    B = pardiso.on_pattern(A, P)
    assert np.array_equal(B.indptr, P.indptr) and np.array_equal(B.indices, P.indices)
    np.testing.assert_array_equal(B.toarray(), A.toarray())
    with pytest.raises(FEError, match="outside the pattern"):
        pardiso.on_pattern(P, A)


@pytest.mark.parametrize("method", [pytest.param("pardiso", marks=needs_mkl), "superlu"])
def test_pending_analysis_then_values_equals_one_factorization(method):
    """schur_analysis on the pattern (all entries 1) while the values are computed, then factor(values): the same
    Schur complement and solution as schur_system of the matrix."""
    from fem.la.linsolve import schur_analysis

    K, rng = _spd()
    G = sp.random(20, K.shape[0], density=0.05, random_state=4, format="csr")
    U = pardiso.upper_csr(sp.bmat([[K, G.T], [G, sp.csr_matrix((20, 20))]], format="csr"))
    C = K.shape[0] + np.arange(20)
    pattern = sp.csr_matrix((np.ones(U.nnz), U.indices, U.indptr), shape=U.shape)
    pending = schur_analysis(pattern, C, method)
    try:
        sysm = pending.factor(U)
    finally:
        pending.close()
    ref = schur_system(U, C, method, upper=True)
    assert np.abs(sysm.schur - ref.schur).max() <= 1e-12 * np.abs(ref.schur).max()
    f = rng.standard_normal(U.shape[0])
    u = sysm.solve(f, lambda fc: np.linalg.solve(sysm.schur, fc))
    u_ref = ref.solve(f, lambda fc: np.linalg.solve(ref.schur, fc))
    assert np.abs(u - u_ref).max() <= 1e-10 * np.abs(u_ref).max()


@pytest.mark.parametrize("case", ["canonical", "no diagonal", "unsorted"])
def test_upper_csr_equals_triu_with_diagonal(case):
    """fem.la.pardiso.upper_csr: the upper triangle, sorted, with every diagonal entry stored (zeros included)."""
    K, _ = _spd(60, seed=2)
    if case == "no diagonal":
        K = K.tolil()
        K.setdiag(0.0)
        K = K.tocsr()
        K.eliminate_zeros()
    if case == "unsorted":
        K = K.tocsc().T.tocsr()  # same matrix (symmetric), built without sorting
        K.indices, K.data = K.indices.copy(), K.data.copy()
        for i in range(K.shape[0]):  # reverse each row
            s = slice(K.indptr[i], K.indptr[i + 1])
            K.indices[s], K.data[s] = K.indices[s][::-1], K.data[s][::-1]
        K.has_sorted_indices = False
    U = pardiso.upper_csr(K)
    ref = (sp.triu(K) + sp.eye(K.shape[0]) * 0.0).toarray()
    np.testing.assert_array_equal(U.toarray(), ref)
    assert U.has_sorted_indices and np.all(np.diff(U.indices[U.indptr[0]:U.indptr[1]]) > 0)
    first = U.indices[U.indptr[:-1]]
    np.testing.assert_array_equal(first, np.arange(K.shape[0]))  # the diagonal is stored, first in each row


@needs_mkl
def test_superlu_fallback_matches_pardiso():
    mesh, model, _ = hertz_line(elements_per_halfwidth=5.0, setup=ModelSetup(solver=SolverOptions("pardiso")))
    r1 = solve(mesh, model)
    mesh, model, _ = hertz_line(elements_per_halfwidth=5.0, setup=ModelSetup(solver=SolverOptions("superlu")))
    r2 = solve(mesh, model)
    assert r2.info.solver == "superlu"
    scale = np.abs(r1.displacement).max()
    assert np.abs(r1.displacement - r2.displacement).max() < 1e-8 * scale
    assert r1.pairs[0].max_pressure == pytest.approx(r2.pairs[0].max_pressure, rel=1e-8)


def test_amg_cg_linear_solve():
    from fem.assembly import assemble_blocks
    from fem.elements.hex8 import hex8_matrices

    mesh, model, _ = cantilever(n_depth=4)
    lam = np.full(mesh.n_cells, 1.2e5)
    mu = np.full(mesh.n_cells, 8e4)
    K = assemble_blocks(hex8_matrices(mesh.points, mesh.cells, lam, mu).stiffness, mesh.cells, mesh.n_points)
    free = np.flatnonzero(mesh.points[:, 0] > 1e-9)
    dofs = (3 * free[:, None] + np.arange(3)).ravel()
    Kf = K[dofs][:, dofs].tocsr()
    f = np.random.default_rng(0).standard_normal(len(dofs))
    u, info = linear_solve(Kf, f, "amg", modes=rigid_body_modes(mesh.points[free]), tol=1e-10)
    u_ref, _ = linear_solve(Kf, f, "superlu")
    assert np.abs(u - u_ref).max() < 1e-6 * np.abs(u_ref).max()
    assert info["iterations"] > 0


def test_vtu_has_all_fields(tmp_path):
    mesh, model, _ = hertz_line(elements_per_halfwidth=5.0)
    r = solve(mesh, model)
    path = tmp_path / "result.vtu"
    r.write_vtu(path)
    m = meshio.read(path)
    for name in ("displacement", "von_mises", "principal_stress", "stress", "contact_pressure", "reaction"):
        assert name in m.point_data
    assert np.allclose(m.point_data["von_mises"], r.von_mises)
    assert np.array_equal(m.cell_data["body"][0], mesh.cell_body)
    assert m.cells[0].data.shape == (mesh.n_cells, 8)


@needs_mkl
def test_overlapped_and_serial_solves_agree(monkeypatch):
    """fem.solve with the symbolic analysis overlapped (more than one kernel thread) and in turn (one): the same
    displacements, pressures and Schur size (the analysed pattern holds every value's entry)."""
    import fem.analysis as analysis

    mesh, model, _ = hertz_line(elements_per_halfwidth=3.0, setup=ModelSetup(solver=SolverOptions("pardiso")))
    runs = {}
    for threads in (1, 2):
        monkeypatch.setattr(analysis, "kernel_threads", lambda threads=threads: threads)
        runs[threads] = solve(mesh, model)
    a, b = runs[1], runs[2]
    assert "analysis_s" in b.info.timings and "analysis_s" not in a.info.timings
    assert a.info.schur_dofs == b.info.schur_dofs
    assert np.abs(a.displacement - b.displacement).max() <= 1e-10 * np.abs(a.displacement).max()
    assert a.pairs[0].max_pressure == pytest.approx(b.pairs[0].max_pressure, rel=1e-10)
