"""VTU, ABAQUS .inp and gmsh .msh files read back with meshio / gmsh."""

import meshio
import numpy as np
import pytest

from mesher import Focus, MeshOptions, abaqus_name, mesh_gear, write_inp, write_msh, write_vtu
from mesher.export import gmsh_session
from tca.errors import InputError

from tests.mesher.gears import gear


@pytest.fixture(scope="module")
def model():
    return mesh_gear(gear("sun"), MeshOptions(teeth=3, coarse_size=1.5, contact_size=0.5), focus=Focus(1, 0.3, 2.0))


def test_inp_reads_back_with_meshio(model, tmp_path):
    m = model
    names = write_inp(m, tmp_path / "m.inp", element_type="C3D8I")
    r = meshio.read(tmp_path / "m.inp", file_format="abaqus")
    # 13 significant digits (CalculiX reads fields of at most 20 characters): 1e-12 relative
    np.testing.assert_allclose(r.points[: m.n_points], m.points, rtol=0, atol=1e-12 * np.abs(m.points).max())
    np.testing.assert_allclose(r.points[m.n_points], m.reference_points["sun"].point, atol=1e-15)
    assert r.cells[0].type == "hexahedron"
    np.testing.assert_array_equal(r.cells[0].data, m.cells)
    for k, v in m.point_sets.items():
        np.testing.assert_array_equal(np.sort(r.point_sets[names[k]]), v)
    np.testing.assert_array_equal(np.sort(r.point_sets["SUN_REF"]), [m.n_points])
    text = (tmp_path / "m.inp").read_text()
    assert text.count("*ELEMENT, TYPE=C3D8I") == 1
    # every face set is an element-based *SURFACE over per-face element sets
    for k, fs in m.face_sets.items():
        a = names[k]
        assert f"*SURFACE, NAME={a}, TYPE=ELEMENT" in text
        for f in np.unique(fs[:, 1]):
            el = np.sort(r.cell_sets[f"{a}_S{f + 1}"][0])
            np.testing.assert_array_equal(el, np.unique(fs[fs[:, 1] == f, 0]))
            assert f"{a}_S{f + 1}, S{f + 1}" in text


def test_vtu_carries_the_sets(model, tmp_path):
    m = model
    write_vtu(m, tmp_path / "m.vtu")
    r = meshio.read(tmp_path / "m.vtu")
    np.testing.assert_allclose(r.points, m.points, atol=1e-12)
    np.testing.assert_array_equal(r.cells[0].data, m.cells)
    for k, v in m.point_sets.items():
        np.testing.assert_array_equal(np.flatnonzero(r.point_data[f"nodes:{k}"]), v)
    for k, fs in m.face_sets.items():
        mask = r.cell_data[f"faces:{k}"][0]
        got = {(c, f) for c in np.flatnonzero(mask) for f in range(6) if mask[c] >> f & 1}
        assert got == set(map(tuple, fs))


def test_msh_written_by_gmsh_has_bodies_and_face_sets(model, tmp_path):
    m = model
    write_msh(m, tmp_path / "m.msh")
    with gmsh_session() as gmsh:
        gmsh.open(str(tmp_path / "m.msh"))
        groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
        assert groups["sun"][0] == 3
        d, t = groups["sun"]
        (ent,) = gmsh.model.getEntitiesForPhysicalGroup(d, t)
        types, tags, nodes = gmsh.model.mesh.getElements(3, ent)
        assert list(types) == [5] and len(tags[0]) == m.n_cells
        np.testing.assert_array_equal(np.asarray(nodes[0]).reshape(-1, 8) - 1, m.cells)
        d, t = groups["sun/rim_bottom"]
        (ent,) = gmsh.model.getEntitiesForPhysicalGroup(d, t)
        _, tags, nodes = gmsh.model.mesh.getElements(2, ent)
        np.testing.assert_array_equal(np.asarray(nodes[0]).reshape(-1, 4) - 1, m.face_nodes("sun/rim_bottom"))
        gmsh.model.remove()


def test_abaqus_names():
    assert abaqus_name("planet/tooth33/flank_neg") == "PLANET_TOOTH33_FLANK_NEG"
    assert abaqus_name("3rd/set") == "S_3RD_SET"
    with pytest.raises(InputError):
        abaqus_name("x" * 81)


def test_gmsh_leaves_sigpipe_ignored():
    """gmsh.initialize resets SIGPIPE to terminate the process; the session puts Python's disposition (ignored:
    a closed pipe raises BrokenPipeError) back, inside the block and after it. In a fresh interpreter, so that the
    check does not depend on what ran before in this one."""
    import subprocess
    import sys

    code = """
from mesher.export import gmsh_session
def ignored():
    for line in open('/proc/self/status'):
        if line.startswith('SigIgn'):
            return bool(int(line.split()[1], 16) & (1 << 12))
print(ignored(), end=' ')
with gmsh_session():
    print(ignored(), end=' ')
print(ignored())
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["True", "True", "True"], out
