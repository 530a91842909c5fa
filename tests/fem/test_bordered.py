"""fem.bordered: the bordered matrix's upper triangle from its layout equals the one made by sparse products."""

import numpy as np
import pytest
import scipy.sparse as sp

from fem.analysis import _cell_materials, _contact
from fem.assembly import block_assembly, block_pattern
from fem.bordered import bordered_layout
from fem.constraints import reduction
from fem.errors import FEError
from fem.elements.hex8 import hex8_matrices
from fem.la.pardiso import upper_csr
from fem.mesh.primitives import SplineMesh
from fem.verification import block_chain, cantilever, gear_like, hertz_line

COARSE = SplineMesh(h=1.0, fine_width=1.0, hz=2.5, z_fine_width=5.0, growth=1.8, h_max=5.0)


def _models():
    yield "gear_like", gear_like(sizes=COARSE)[:2]  # rigid ties with free rz, a fixed sleeve, three contacts
    yield "block_chain", block_chain()[:2]  # a body held by contact alone (free rigid DOFs in the Schur rows)
    yield "hertz_line", hertz_line(elements_per_halfwidth=3.0)[:2]  # a rigid punch on a fixed block
    yield "cantilever", cantilever()[:2]  # no contact


@pytest.mark.parametrize("name, mesh_model", list(_models()), ids=lambda x: x if isinstance(x, str) else "")
def test_layout_values_equal_the_bordered_product(name, mesh_model):
    mesh, model = mesh_model
    lam, mu, E = _cell_materials(mesh, model)
    red = reduction(mesh, model)
    Tt = red.T.T.tocsr()
    bp = block_pattern(mesh.cells, mesh.n_points)
    cs, cand, C, GrT = _contact(mesh, model, red, Tt, E)
    em = hex8_matrices(mesh.points, mesh.cells, lam, mu)
    K = block_assembly(mesh.cells, mesh.n_points, bp).assemble(em.stiffness)
    layout = bordered_layout(bp, red, GrT)
    A = layout.values(K)
    Kr = (Tt @ K @ red.T).tocsr()
    k = len(cand)
    full = sp.bmat([[Kr, GrT], [GrT.T, sp.csr_matrix((k, k))]], format="csr") if k else Kr
    ref = upper_csr(full)
    assert A.shape == ref.shape
    np.testing.assert_allclose(A.toarray(), ref.toarray(), rtol=0, atol=1e-12 * abs(ref.data).max())
    # the layout's pattern holds every entry of the values, each row starts at its diagonal (PARDISO's form)
    assert np.array_equal(layout.pattern.indptr, A.indptr) and np.array_equal(layout.pattern.indices, A.indices)
    assert np.array_equal(A.indices[A.indptr[:-1]], np.arange(A.shape[0]))
    assert all(np.all(np.diff(A.indices[A.indptr[i]:A.indptr[i + 1]]) > 0) for i in range(A.shape[0]))
    with pytest.raises(FEError, match="layout was made for"):
        layout.values(upper_csr(K))
    if name == "cantilever":  # the case without rigid columns (X empty) and without gap rows
        assert len(red.free_rigid) == 0 and k == 0
