"""Pair models placed at TCA positions: the two loaded flanks touch at the TCA contact point (Step 5)."""

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest

from mesher import MeshOptions, check_conformity, check_quality, mesh_gear, mesh_pair
from mesher.pair_model import member_pair
from pipelines.cases.reader import CASES_DIR, load_case, read_gears, read_misalignment
from tca import GearPair, InputError, Misalignment, run_pair_tca

from tests.mesher.gears import gear

from tca.units import ARCMIN


@lru_cache(maxsize=None)
def _pair(which):
    if which == "sun-planet":  # Table 1.1 case file: sun 10 deg, double-crowned planet, delta gamma = 3 arcmin
        c = load_case(CASES_DIR / "part1_sun_planet.toml")
        g = read_gears(c)
        return GearPair(g["sun"], g["planet"], read_misalignment(c.table("misalignment")))
    if which == "planet-ring":  # internal mesh, ring with the same (left) hand and a 10 deg transverse design
        return GearPair(gear("planet"), replace(gear("ring"), helix=math.radians(10)))
    if which == "table31":
        return GearPair(gear("sun3"), gear("planet3"))
    raise KeyError(which)


@lru_cache(maxsize=None)
def _model(which, position="max_te", gap=None):
    return mesh_pair(_pair(which), position, MeshOptions(gap=gap))


def _flank_normal(mesh, body_set, node):
    """Mean outward normal of the faces of a face set around a node."""
    q = mesh.face_nodes(body_set)
    sel = np.any(q == node, axis=1)
    p = mesh.points[q[sel]]
    n = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    n = n.sum(0)
    return n / np.linalg.norm(n)


@pytest.mark.parametrize("which", ["sun-planet", "planet-ring", "table31"])
def test_loaded_flanks_touch_at_the_tca_point(which):
    pm = _model(which)
    m = pm.mesh
    pos = m.meta["position"]
    assert pos["kind"] == "surface"
    # the contact point is a node of both meshes, evaluated from the exact surfaces at the TCA parameters:
    # they coincide to the TCA residual (< 1e-10 mm) plus rounding
    a, b = pm.contact_nodes
    assert pm.contact_node_gap < 1e-9
    assert np.linalg.norm(m.points[a] - pm.contact_point) < 1e-9
    # the meshed flanks are tangent there: the faces are chords of the surfaces, so their normals
    # deviate from the exact ones by ~ h / (2 rho) (h ~ 0.25 mm, rho >= 5 mm): opposite within 0.02 rad
    j1, j2 = pm.loaded_teeth
    g1, g2 = m.bodies
    n1 = _flank_normal(m, f"{g1}/tooth{j1}/flank_pos", a)
    n2 = _flank_normal(m, f"{g2}/tooth{j2}/flank_neg", b)
    assert np.dot(n1, n2) < -math.cos(0.02)
    check_quality(m)
    check_conformity(m)


def test_tooth_indices_sets_and_reference_points():
    pm = _model("sun-planet")
    m, pair = pm.mesh, _pair("sun-planet")
    i = pm.index
    k = int(pm.tca.active_pair[i])
    # the reference pair solved at phi1 - 2 pi k / N1 is tooth -k of each gear at phi1
    assert pm.loaded_teeth == ((-k) % 41, (-k) % 34)
    assert i == int(np.argmax(pm.tca.te))
    assert m.contact_pairs[0] == (f"sun/tooth{pm.loaded_teeth[0]}/flank_pos", f"planet/tooth{pm.loaded_teeth[1]}/flank_neg")
    assert len(m.contact_pairs) == 3
    m1, m2 = pair.mounts()
    for body, mount in (("sun", m1), ("planet", m2)):
        rp = m.reference_points[body]
        np.testing.assert_allclose(rp.point, mount.origin, atol=1e-12)
        np.testing.assert_allclose(rp.axis, mount.axis, atol=1e-12)
        assert m.meta["bodies"][body]["loaded_side"] == (1 if body == "sun" else -1)
        for s in ("rim_side1", "rim_side2", "rim_bottom", "rim"):
            assert len(m.point_sets[f"{body}/{s}"]) > 0


def test_other_positions_and_bad_positions():
    pair = _pair("table31")
    tca = run_pair_tca(pair)
    for pos in (0, 17, "min_te"):
        pm = mesh_pair(pair, pos, MeshOptions(coarse_size=4.0, contact_size=1.0), tca=tca)
        assert pm.contact_node_gap < 1e-9
    with pytest.raises(InputError, match="position"):
        mesh_pair(pair, 10_000, tca=tca)
    with pytest.raises(InputError, match="position"):
        mesh_pair(pair, "middle", tca=tca)


def test_double_helical_members_touch_with_a_shaft_angle_error():
    # member a's TCA is solved with gear 2 shifted by the member offset through the misaligned mount
    pm = _model("sun-planet", gap=10.0)
    assert pm.member_offset == pytest.approx(20.0)
    assert pm.contact_node_gap < 1e-9
    assert pm.contact_point[2] == pytest.approx(20.0 + pm.mesh.meta["position"]["params_mm"][1], abs=1e-9)
    # both members of each gear are one body; member b is the mirror (opposite hand)
    m = pm.mesh
    z = m.points[m.cells[m.cell_body == 0]][..., 2]
    assert z.min() == pytest.approx(-35.0, abs=1e-9) and z.max() == pytest.approx(35.0, abs=1e-9)
    hands = [mm["hand"] for mm in m.meta["bodies"]["sun"]["members"]]
    assert hands == [1, -1]


def test_member_offset_matters_under_misalignment():
    # placing offset members at the angles of the centred TCA leaves a gap ~ c * delta gamma (20 mm x 3')
    pair = _pair("sun-planet")
    shifted = member_pair(pair, 20.0)
    assert shifted.misalignment.d_ex == pytest.approx(-20.0 * math.sin(3 * ARCMIN), rel=1e-3)
    naive = mesh_pair(pair, "max_te", MeshOptions(gap=10.0), tca=run_pair_tca(pair))
    assert naive.contact_node_gap > 1e-3
    # without misalignment the shift is nothing
    aligned = replace(pair, misalignment=Misalignment())
    ms = member_pair(aligned, 20.0).misalignment
    assert max(abs(ms.d_center), abs(ms.d_ex), abs(ms.d_axial)) < 1e-12


def test_mesh_gear_rejects_bad_options():
    g = gear("sun3")
    with pytest.raises(InputError, match="mesh.teeth"):
        mesh_gear(g, MeshOptions(teeth=66))
    with pytest.raises(InputError, match="contact_size"):
        mesh_gear(g, MeshOptions(coarse_size=1.0, contact_size=2.0))
    with pytest.raises(InputError, match="rim_depth"):
        mesh_gear(g, MeshOptions(rim_depth=-1.0))
