"""Meshed tooth volume against the exact volume of the tooth region (Step 1), and its convergence."""

import math

import numpy as np
import pytest

from mesher import MeshOptions, ToothGeometry, mesh_gear, quality, section_area, tooth_region_volume
from mesher.volume import _tip

from tests.mesher.gears import ALL, gear


def _polygon_area(g, rim, z, n=4000):
    """Shoelace area of the section boundary sampled densely (an independent discretisation)."""
    pts = []
    for side in (-1, 1):
        seq = []
        for piece in ("root", "fillet", "flank"):
            s = g.surface(side, piece)
            lo, hi = s.u_range
            if piece == "flank":
                lo, hi = g.area(side).u_form, _tip(g, side, z)
            u = np.linspace(lo, hi, n)
            seq.append(s.points(u, np.full_like(u, z))[:, :2])
        seq = np.concatenate(seq)
        pts.append(seq if side < 0 else seq[::-1])
    a_minus = math.atan2(pts[0][-1, 1], pts[0][-1, 0])
    a_plus = math.atan2(pts[1][0, 1], pts[1][0, 0])
    top = g.r_tip * np.stack([np.cos(np.linspace(a_minus, a_plus, n)), np.sin(np.linspace(a_minus, a_plus, n))], -1)
    thr = math.atan2(pts[1][-1, 1], pts[1][-1, 0])
    th = np.linspace(thr, thr - g.pitch_angle, n)
    rim_arc = rim * np.stack([np.cos(th), np.sin(th)], -1)
    P = np.concatenate([pts[0], top, pts[1], rim_arc])
    x, y = P[:, 0], P[:, 1]
    return 0.5 * abs(np.sum(x * np.roll(y, -1) - y * np.roll(x, -1)))


@pytest.mark.parametrize("name", ["sun", "planet", "ring"])
def test_exact_section_area_by_green_matches_a_dense_polygon(name):
    # 4000 chords per piece: the polygon's sagitta error is ~ (L/n)^2 / (8 rho) -> below 1e-7 relative
    g = gear(name)
    rim = ToothGeometry(g, 3 * g.module).r_rim
    for z in (-14.0, 0.0, 9.0):
        a = section_area(g, rim, z)
        assert a == pytest.approx(_polygon_area(g, rim, z), rel=1e-7)


def test_section_area_of_a_helicoid_does_not_depend_on_z():
    # a helicoid's sections are one profile turned by k z: the area is the same at every level
    g = gear("sun")
    rim = ToothGeometry(g, 6.0).r_rim
    a = [section_area(g, rim, z) for z in (-15.0, -4.0, 0.0, 11.0, 15.0)]
    np.testing.assert_allclose(a, a[2], rtol=1e-11)
    # the double-crowned planet loses material toward its ends (plunging, Eq. 1.6)
    p = gear("planet")
    rimp = ToothGeometry(p, 6.0).r_rim
    assert section_area(p, rimp, 15.0) < section_area(p, rimp, 0.0)


@pytest.mark.parametrize("name", ALL)
def test_meshed_tooth_volume_within_half_a_percent_at_default_refinement(name):
    g = gear(name)
    m = mesh_gear(g, MeshOptions(teeth=1))
    v = quality(m).volume.sum()
    exact = tooth_region_volume(g, ToothGeometry(g, 3 * g.module).r_rim)
    assert abs(v - exact) / exact < 5e-3


def _volume_error(name, coarse_modules):
    g = gear(name)
    exact = tooth_region_volume(g, ToothGeometry(g, 3 * g.module).r_rim)
    v = quality(mesh_gear(g, MeshOptions(teeth=1, coarse_size=coarse_modules * g.module))).volume.sum()
    return (v - exact) / exact


@pytest.mark.parametrize("name", ["sun", "planet", "ring"])
def test_meshed_volume_converges_on_refinement(name):
    # element faces are chords of the curved tooth surfaces; measured (bench_mesher): sun 1.8e-4 ->
    # 7.7e-5, planet 1.3e-4 -> 5.6e-5, ring 1.8e-4 -> 4.5e-5 from 0.25 m to 0.125 m elements
    e = [abs(_volume_error(name, f)) for f in (0.25, 0.125)]
    assert e[1] < 0.6 * e[0]


def test_volume_error_is_second_order():
    # chords of smooth curves: error ~ h^2, a factor ~4 per halving in the asymptotic range
    # (measured on planet3: 8.6e-5 -> 2.1e-5)
    e = [_volume_error("planet3", f) for f in (0.125, 0.0625)]
    assert e[0] / e[1] > 3.0


def test_three_teeth_hold_three_times_the_volume_of_one():
    # teeth are exact rotations of the reference tooth and conform: volumes add up to rounding
    g = gear("sun")
    v1 = quality(mesh_gear(g, MeshOptions(teeth=1))).volume.sum()
    v3 = quality(mesh_gear(g, MeshOptions(teeth=3))).volume.sum()
    assert v3 == pytest.approx(3 * v1, rel=1e-10)
