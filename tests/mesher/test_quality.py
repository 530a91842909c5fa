"""Positive Jacobians at every Gauss point for the gears of Tables 1.1 and 3.1, coarse to fine."""

import numpy as np
import pytest

from mesher import Focus, HexMesh, MeshOptions, check_quality, gmsh_quality, mesh_gear, quality
from tca.errors import GeometryError

from tests.mesher.gears import ALL, gear

# (coarse, contact) sizes in modules: coarse, default, fine
LEVELS = {"coarse": (1.0, 0.25), "default": (0.5, 0.125), "fine": (0.25, 0.0625)}


@pytest.mark.parametrize("level", list(LEVELS))
@pytest.mark.parametrize("name", ALL)
def test_positive_jacobians_from_coarse_to_fine(name, level):
    g = gear(name)
    c, h = LEVELS[level]
    m = mesh_gear(g, MeshOptions(teeth=3, coarse_size=c * g.module, contact_size=h * g.module),
                  centre=2, focus=Focus(1, 0.2 * g.module, 0.2 * g.face_width))
    q = check_quality(m)  # raises on any det J <= 0
    assert q.min_det.min() > 0
    # measured 0.59-0.72 at these levels: a drop below 0.5 means the block layout has degraded
    assert q.min_scaled_jacobian.min() > 0.5
    assert q.aspect_ratio.max() < 25


def test_gmsh_agrees_on_validity_and_volumes():
    # gmsh's own scaled Jacobian (from Jacobian bounds) is positive everywhere; its element volumes
    # equal our 2x2x2 Gauss volumes, exact for trilinear hexahedra (1e-12 relative)
    g = gear("planet")
    m = mesh_gear(g, MeshOptions(teeth=3), focus=Focus(-1, -0.5, -3.0))
    sj = gmsh_quality(m, "minSJ")
    assert sj.min() > 0.3
    np.testing.assert_allclose(gmsh_quality(m, "volume"), quality(m).volume, rtol=1e-12)


def test_an_inverted_element_is_an_error_naming_it():
    g = gear("sun3")
    m = mesh_gear(g, MeshOptions(teeth=1))
    cells = m.cells.copy()
    cells[17] = cells[17][[4, 5, 6, 7, 0, 1, 2, 3]]  # element 17 turned inside out
    bad = HexMesh(m.points, cells, m.cell_body, m.bodies)
    with pytest.raises(GeometryError, match=r"sun3: inverted element: element 17 "):
        check_quality(bad)


def test_scaled_jacobian_of_a_unit_cube_and_a_sheared_brick():
    pts = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    m = HexMesh(pts, np.arange(8)[None], np.zeros(1, int))
    q = quality(m)
    assert q.min_scaled_jacobian[0] == pytest.approx(1.0, abs=1e-14)
    assert q.volume[0] == pytest.approx(1.0, abs=1e-14)
    sheared = pts.copy()
    sheared[4:, 0] += 1.0  # top face shifted by the height: 45 deg shear, SJ = sin(45 deg), volume 1
    s = quality(HexMesh(sheared, np.arange(8)[None], np.zeros(1, int)))
    assert s.min_scaled_jacobian[0] == pytest.approx(np.sin(np.pi / 4), abs=1e-12)
    assert s.volume[0] == pytest.approx(1.0, abs=1e-12)
    assert s.aspect_ratio[0] == pytest.approx(np.sqrt(2))
