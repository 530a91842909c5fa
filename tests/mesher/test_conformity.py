"""Conformity of the hexahedra across subvolumes, teeth and rim; named sets; nodes on the exact surfaces."""

import math

import numpy as np
import pytest

from mesher import Focus, MeshOptions, check_conformity, face_counts, mesh_gear, quality
from tca import Gear
from tca.errors import GeometryError

from tests.mesher.gears import gear

BOUNDARY = ("flank_pos", "flank_neg", "fillet_pos", "fillet_neg", "root_pos", "root_neg", "top_land")


def _boundary_faces_are_the_named_sets(m, body):
    """Faces held by one element = union of the named boundary sets, each face named once."""
    _, cnt, where = face_counts(m)
    free = {tuple(x) for x in where[cnt == 1]}
    named = []
    for k, v in m.face_sets.items():
        tail = k.split("/", 1)[1]
        if tail.split("/")[-1] in BOUNDARY or tail in ("rim_side1", "rim_side2", "rim_bottom", "end_zmin", "end_zmax"):
            named.extend(map(tuple, v))
    assert len(named) == len(set(named))  # no face in two boundary sets
    assert set(named) == free  # no crack inside, no unnamed boundary


@pytest.mark.parametrize("name,focus,gap", [("sun", Focus(1, 0.4, 2.0), None), ("ring", Focus(-1, -0.3, -6.0), None),
                                            ("planet", Focus(-1, 0.2, 4.0), 10.0), ("planet3", None, None)])
def test_hexahedra_conform_and_the_boundary_is_exactly_the_named_sets(name, focus, gap):
    g = gear(name)
    m = mesh_gear(g, MeshOptions(teeth=3, gap=gap), focus=focus)
    c = check_conformity(m)
    assert c["duplicate_nodes"] == 0
    _boundary_faces_are_the_named_sets(m, g.name)
    # node sets are the nodes of their face sets
    for k, v in m.face_sets.items():
        np.testing.assert_array_equal(m.point_sets[k], np.unique(m.face_nodes(k)))
    # the loaded tooth (finer) and its coarse neighbours share the space-centre node rows
    teeth = m.meta["bodies"][g.name]["teeth"]
    assert len(teeth) == 3 and all(f"{g.name}/tooth{j}/flank_pos" in m.face_sets for j in teeth)


def test_a_whole_gear_closes_on_itself():
    g = Gear("small", 19, 3.0, math.radians(20), 12.0, helix=math.radians(15), profile_shift=0.3)
    m = mesh_gear(g, MeshOptions(teeth=19))
    check_conformity(m)
    _boundary_faces_are_the_named_sets(m, "small")
    assert "small/rim_side1" not in m.face_sets and "small/rim_side2" not in m.face_sets
    one = mesh_gear(g, MeshOptions(teeth=1))
    assert quality(m).volume.sum() == pytest.approx(19 * quality(one).volume.sum(), rel=1e-10)


def surface_distance(surf, p, u0):
    """Distance from points p (n, 3) to the surface at their own level z (v = z), Newton on u."""
    u = u0.copy()
    z = p[:, 2]
    for _ in range(8):
        s = surf.evaluate(u, z)
        d = s.r - p
        f = np.einsum("ij,ij->i", d, s.r_u)
        df = np.einsum("ij,ij->i", s.r_u, s.r_u) + np.einsum("ij,ij->i", d, s.r_uu)
        u = u - f / df
    return np.linalg.norm(surf.points(u, z) - p, axis=1)


@pytest.mark.parametrize("name", ["sun", "planet", "ring"])
def test_nodes_on_flanks_and_fillets_lie_on_the_exact_tooth_surfaces(name):
    # boundary nodes are evaluated at surface parameters: distance to the surface ~ rounding (1e-9 mm)
    g = gear(name)
    m = mesh_gear(g, MeshOptions(teeth=3), centre=5, focus=Focus(1, 0.3, 1.0))
    for j in (5, m.meta["bodies"][g.name]["teeth"][-1]):  # the loaded tooth and a neighbour
        R, t = g.tooth_transform(j)
        for side, key in ((1, "pos"), (-1, "neg")):
            for piece in ("flank", "fillet"):
                p = (m.points[m.point_sets[f"{g.name}/tooth{j}/{piece}_{key}"]] - t) @ R  # back to the reference tooth
                s = g.surface(side, piece)
                lo, hi = s.u_range
                samples = np.broadcast_to(np.linspace(lo, hi, 100), (len(p), 100))
                grid = s.points(samples, np.broadcast_to(p[:, 2:3], samples.shape))
                guess = samples[0, np.argmin(np.linalg.norm(grid - p[:, None, :], axis=-1), axis=1)]
                assert surface_distance(s, p, guess).max() < 1e-9


def test_a_non_conforming_mesh_is_rejected():
    g = gear("sun3")
    m = mesh_gear(g, MeshOptions(teeth=1))
    pts = np.concatenate([m.points, m.points[:1]])
    cells = m.cells.copy()
    cells[0, 0] = len(pts) - 1  # a second node at the place of node 0
    from mesher import HexMesh

    bad = HexMesh(pts, cells, m.cell_body, m.bodies)
    with pytest.raises(GeometryError, match="duplicate nodes"):
        check_conformity(bad)
