"""Single subgear drives of the planetary train (section 1.4): mounts, composition of the two meshes."""

import math

import numpy as np
import pytest

from tca.pair.gear_pair import GearPair, Misalignment
from tca.pair.analysis import ARCSEC, TCAOptions, run_pair_tca
from tca.planetary.train import ShaftErrors
from tca.planetary.subgear import MeshTE, member_pose, phi1_grid, run_subgear_tca, subgear_meshes, subgear_pairs
from tca.report_data import table_1_1_train

d = math.radians
FAST = TCAOptions(cycles=1, steps_per_cycle=10)


@pytest.fixture(scope="module")
def involute_train():
    # conventional involute double-helical train, all helix angles 10 deg: conjugate, zero TE everywhere
    return table_1_1_train(beta_sun_deg=10.0, beta_ring_deg=10.0, crowned=False)


@pytest.fixture(scope="module")
def train():
    # Table 1.1 with beta1 = 10.25, beta2 = 10, beta3 = 9.75 deg (transverse geometry of the 10 deg design)
    return table_1_1_train(beta_sun_deg=10.25, beta_ring_deg=9.75)


def test_ideal_train_has_zero_ring_te_at_every_planet(involute_train):
    # the zero-backlash configuration is common to all planets (Eq. 1.3): |Delta phi3| < 1e-6 arcsec,
    # i.e. the Newton tolerance (1e-11 mm) over the ring radius, for both members of every shaft
    cache = {}
    for i in range(5):
        for m in "ab":
            r = run_subgear_tca(involute_train, i, m, opts=FAST, cache=cache)
            assert np.abs(r.te3_arcsec).max() < 1e-6


@pytest.mark.parametrize("d_ex", [0.02, -0.005])
def test_installment_error_of_an_involute_train_closed_form(involute_train, d_ex):
    # a tangential shift Delta E_x turns the ring by 2 Delta E_x / r3 (the planet turns to keep contact):
    # +74.5436 arcsec for 20 um; second-order terms (Delta E_x^2 / E) stay below 1e-4 arcsec
    r = run_subgear_tca(involute_train, 2, "a", ShaftErrors(d_ex=d_ex), opts=FAST)
    expected = 2 * d_ex / involute_train.ring.r_p / ARCSEC
    assert np.abs(r.te3_arcsec - expected).max() < 1e-4


def test_explicit_mounts_equal_the_pair_misalignment(train):
    # shaft 0, member a, Delta E_x = 20 um: in both pair frames the planet is displaced by -/+ 20 um along y;
    # the same pairs built with tca.pair.gear_pair's Misalignment give the same TE (to the Newton tolerance)
    e = ShaftErrors(d_ex=0.02)
    p1, p2 = subgear_pairs(train, 0, "a", e)
    sun, planet, ring = train.gears("a")
    q1 = GearPair(sun, planet, Misalignment(d_ex=-0.02))
    q2 = GearPair(planet, ring, Misalignment(d_ex=-0.02))  # the ring displaced opposite to the planet
    for ma, mb in zip(p1.mounts(), q1.mounts()):  # pair 1: the same mounts
        np.testing.assert_allclose(ma.origin, mb.origin, atol=1e-12)
        np.testing.assert_allclose(ma.R0, mb.R0, atol=1e-12)
    (a1, a2), (b1, b2) = p2.mounts(), q2.mounts()  # pair 2: the same relative position of ring and planet
    np.testing.assert_allclose(a2.origin - a1.origin, b2.origin - b1.origin, atol=1e-12)
    for p, q in ((p1, q1), (p2, q2)):
        ra, rb = run_pair_tca(p, FAST), run_pair_tca(q, FAST)
        assert np.abs(ra.te_arcsec - rb.te_arcsec).max() < 1e-6


def test_pair_frames_turn_with_the_shaft(train):
    # the pair TCAs of a member depend on its errors only, not on the shaft's place on the carrier
    e = ShaftErrors(d_ex=0.005, d_gamma=d(3 / 60))
    ref = subgear_pairs(train, 0, "b", e, dz=1.5)
    for i in (1, 3):
        for pa, pb in zip(subgear_pairs(train, i, "b", e, dz=1.5), ref):
            for ma, mb in zip(pa.mounts(), pb.mounts()):
                np.testing.assert_allclose(ma.origin, mb.origin, atol=1e-12)
                np.testing.assert_allclose(ma.R0, mb.R0, atol=1e-12)
                assert ma.phase == mb.phase


def test_member_pose_shaft_angle_about_the_shaft_centre(train):
    # Delta gamma turns the shaft about e_r through its centre: member a (z_m = +20 mm) moves by -z_m sin(dg)
    # along e_theta (= +Delta E_x), member b the other way; the axis tilts by dg
    dg = d(3 / 60)
    th = train.carrier_angle(1)
    et = np.array([-math.sin(th), math.cos(th), 0.0])
    oa, Ra = member_pose(train, 1, "a", ShaftErrors(d_gamma=dg))
    ob, _ = member_pose(train, 1, "b", ShaftErrors(d_gamma=dg))
    oa0, _ = member_pose(train, 1, "a")
    assert np.dot(oa - oa0, et) == pytest.approx(-20 * math.sin(dg), abs=1e-12)
    assert np.dot(ob - member_pose(train, 1, "b")[0], et) == pytest.approx(20 * math.sin(dg), abs=1e-12)
    assert math.acos(-Ra[2, 2]) == pytest.approx(dg, abs=1e-12)  # planet axis -z_f tilted by dg
    assert np.dot(oa - ob, Ra[:, 2]) == pytest.approx(-40.0, abs=1e-12)  # members stay 2 z_m apart on the axis


def test_members_are_mirror_images(train):
    # members a and b of a shaft with Delta E_x and a mirror-symmetric regulation have the same TE
    # (the shortcut of tca.planetary.regulation); residual = Newton tolerance, < 1e-6 arcsec
    e = ShaftErrors(d_ex=0.02)
    a = run_subgear_tca(train, 1, "a", e, dz=-2.0, opts=FAST)
    b = run_subgear_tca(train, 1, "b", e, dz=-2.0, opts=FAST)
    assert np.abs(a.te3_arcsec - b.te3_arcsec).max() < 1e-6
    assert np.ptp(a.te3_arcsec) > 5  # not trivially flat


def test_planets_repeat_the_same_function_shifted_in_phase(train):
    # error-free planets: Delta phi3^(i)(phi1) = Delta phi3^(1)(phi1 - theta_i), theta_i = i 41/5 pitches,
    # i.e. i * 41 * s / 5 grid steps modulo one cycle (s = steps per cycle)
    opts = TCAOptions(cycles=1, steps_per_cycle=10)
    cache = {}
    r0 = run_subgear_tca(train, 0, "a", opts=opts, cache=cache)
    y0 = r0.te3[:-1]
    for i in range(1, 5):
        ri = run_subgear_tca(train, i, "a", opts=opts, cache=cache)
        shift = (i * 41 * 10 // 5) % 10
        np.testing.assert_allclose(ri.te3[:-1], np.roll(y0, shift), atol=1e-9 * ARCSEC)
    assert len(cache) == 1  # one pair of mesh TCAs served all five planets


def test_mesh_te_interpolation_error(train):
    # the ring mesh is evaluated between TCA grid points by interpolating each tooth pair's branch linearly
    # and taking the largest (kinks between pairs exact); against a TCA on a grid 4x finer the error obeys the
    # interpolation bound h^2 max|f''| / 8 (f'' of the branch from the fine grid; ~0.05 arcsec at 20 steps)
    coarse = TCAOptions(cycles=1, steps_per_cycle=20)
    _, m23 = subgear_meshes(train, "a", opts=coarse)
    fine = run_pair_tca(subgear_pairs(train, 0, "a")[1], TCAOptions(cycles=1, steps_per_cycle=80))
    err = np.abs(m23(fine.phi1) - fine.te) / ARCSEC
    br = MeshTE.from_result(fine).branch
    hf, hc = m23.h / 4, m23.h
    f2 = np.diff(br[np.isfinite(br)], 2) / hf**2 / ARCSEC
    bound = hc**2 * np.abs(f2).max() / 8
    assert 0.02 < bound < 0.1
    assert err.max() <= 1.05 * bound
    # periodic with the planet's pitch
    p = 2 * math.pi / 34
    np.testing.assert_allclose(m23(fine.phi1 + 3 * p), m23(fine.phi1), atol=1e-12)


def test_grid_must_sample_all_planets_alike(train):
    from tca.errors import InputError

    with pytest.raises(InputError, match=r"tca\.steps_per_cycle.*multiple of the number of planets n = 5"):
        phi1_grid(train, TCAOptions(steps_per_cycle=12))


def test_mesh_te_from_result_keeps_the_envelope(train):
    # at the TCA's own grid points the max over shifted branches equals the pair TCA's transmission errors
    r = run_pair_tca(subgear_pairs(train, 0, "a")[0], FAST)
    m = MeshTE.from_result(r)
    np.testing.assert_allclose(m(r.phi1), r.te, atol=1e-15)


def test_pair_explicit_mounts_are_checked(train):
    # tca.pair.gear_pair accepts explicit mounts (both, and no Misalignment on top of them)
    from tca.errors import InputError
    from tca.numerics.transforms import Mount

    sun, planet, _ = train.gears("a")
    m = Mount(np.zeros(3), np.eye(3), 0.0)
    with pytest.raises(InputError, match="mount2"):
        GearPair(sun, planet, mount1=m)
    p1, _ = subgear_pairs(train, 0, "a")
    with pytest.raises(InputError, match="misalignment"):
        GearPair(sun, planet, Misalignment(d_ex=0.01), mount1=p1.mounts()[0], mount2=p1.mounts()[1])
    # without errors the explicit mounts are the reference ones of tca.pair.gear_pair
    for ma, mb in zip(p1.mounts(), GearPair(sun, planet).mounts()):
        np.testing.assert_allclose(ma.origin, mb.origin, atol=1e-12)
        np.testing.assert_allclose(ma.R0, mb.R0, atol=1e-12)
        assert ma.phase == pytest.approx(mb.phase, abs=1e-15)
