"""Pair TCA (Eqs. 1.7-1.14): the checks of issue 2 with their tolerances."""

import math

import numpy as np
import pytest

from tca.contact.ellipse import contact_ellipse
from tca.geometry.gear import Gear
from tca.pair.gear_pair import GearPair, Misalignment
from tca.pair.analysis import ARCSEC, ContactKind, TCAOptions, run_pair_tca
from tca.report_data import table_1_1_planet, table_1_1_sun
from tca.geometry.surfaces import SurfacePoints

d = math.radians
from tca.units import ARCMIN


def involute_pair(beta, internal=False):
    if internal:
        return GearPair(Gear("planet", 34, 2.0, d(20), 20, helix=d(beta), hand=-1),
                        Gear("ring", 109, 2.0, d(20), 20, helix=d(beta), hand=-1, internal=True))
    return GearPair(Gear("pinion", 21, 2.0, d(20), 20, helix=d(beta), hand=1),
                    Gear("gear", 35, 2.0, d(20), 20, helix=d(beta), hand=-1))


@pytest.fixture(scope="module")
def planet():
    # Table 1.1 planet: a_cd = 0.008, a_cc = 0.005 1/mm, disk r_D = 100 mm, a_pl = 0.002 1/mm
    return table_1_1_planet()


@pytest.mark.parametrize("beta,internal", [(0, False), (10, False), (10, True)])
def test_aligned_involute_pair_has_no_transmission_error(beta, internal):
    # |Delta phi2| < 1e-3 arcsec (issue 2); every point verified below 1e-10 mm
    r = run_pair_tca(involute_pair(beta, internal))
    assert np.abs(r.te_arcsec).max() < 1e-3
    assert not r.edge_contact
    assert r.max_residual < 1e-10
    assert np.all(r.kind == ContactKind.SURFACE)


@pytest.mark.parametrize("beta", [0, 10])
def test_center_distance_error_keeps_the_involute_ratio(beta):
    # Delta E = 50 um: the ratio stays exact (peak-to-peak < 1e-3 arcsec) and the driven gear lags by
    # half the backlash, (inv a_w - inv a_t) (N1 + N2) / N2 (closed form, to 1e-3 arcsec)
    pair = involute_pair(beta).with_misalignment(d_center=0.05)
    r = run_pair_tca(pair)
    assert r.te_peak_to_peak_arcsec < 1e-3
    g1, g2 = pair.gear1, pair.gear2
    at = g1.transverse_pressure_angle
    aw = math.acos(pair.E * math.cos(at) / (pair.E + 0.05))
    inv = lambda a: math.tan(a) - a  # noqa: E731
    lag = (inv(aw) - inv(at)) * (g1.teeth + g2.teeth) / g2.teeth
    assert r.te.mean() / ARCSEC == pytest.approx(-lag / ARCSEC, abs=1e-3)


def _segments(r):
    """Index ranges of the positions between transitions (one pair in contact)."""
    cuts = np.flatnonzero(np.diff(r.active_pair) != 0) + 1
    return [s for s in np.split(np.arange(len(r.phi1)), cuts) if len(s) >= 8]


def test_misaligned_involute_helical_pair_linear_discontinuous_with_edge_contact():
    # Delta gamma = 3 arcmin on involute helical gears: the TE is almost linear within each cycle, jumps
    # at the transitions, and the contact is at the edges of the teeth (Litvin's reason for crowning).
    # Just before a change of pair the tip corner touches (a few positions, kind CORNER).
    r = run_pair_tca(involute_pair(10).with_misalignment(d_gamma=3 * ARCMIN))
    assert r.edge_contact
    te = r.te_arcsec
    pp = r.te_peak_to_peak_arcsec
    assert pp > 1.0
    assert np.mean(r.kind == ContactKind.CORNER) < 0.1
    for s in _segments(r):
        e = s[r.kind[s] == ContactKind.EDGE]
        fit = np.polyval(np.polyfit(r.phi1[e], te[e], 1), r.phi1[e])
        assert np.abs(te[e] - fit).max() < 0.02 * pp  # almost linear: within 2 % of the peak-to-peak
    jumps = np.abs(np.diff(te))
    assert jumps.max() > 0.5 * pp  # discontinuous at the change of the tooth pair
    assert r.max_residual < 1e-10


@pytest.mark.parametrize("dgamma", [0.0, 3 * ARCMIN, -3 * ARCMIN])
def test_double_crowned_planet_with_sun_parabolic_without_edge_contact(planet, dgamma):
    # Table 1.1 (helix 10 deg both): parabolic TE, no edge contact, also with Delta gamma = +-3 arcmin
    # (the linear error absorbed). Parabola fitted to each cycle: residual < 1 % of its amplitude.
    sun = table_1_1_sun(beta_deg=10.0)
    r = run_pair_tca(GearPair(sun, planet, Misalignment(d_gamma=dgamma)))
    assert not r.edge_contact
    assert r.max_residual < 1e-10
    te = r.te_arcsec
    for s in _segments(r):
        c = np.polyfit(r.phi1[s], te[s], 2)
        assert c[0] < 0  # a parabola opening downward: the driven gear lags away from the vertex
        amp = te[s].max() - te[s].min()
        assert np.abs(te[s] - np.polyval(c, r.phi1[s])).max() < 0.01 * amp
    assert 20 < r.te_peak_to_peak_arcsec < 80


def test_contact_ellipse_of_a_sphere_on_a_plane():
    # Hertz geometry: sphere of radius R on a plane, approach delta -> circle of radius sqrt(2 delta R)
    R, delta = 25.0, 0.0065
    z = np.zeros((1, 3))
    ex, ey, ez = np.eye(3)
    plane = SurfacePoints(z, ex[None], ey[None], z, z, z, ez[None])  # body 1 below, normal +z
    # body 2: sphere centred at (0, 0, R), its surface near the origin seen from normal +z: r_uu . n = +1/R
    sphere = SurfacePoints(z, ex[None], ey[None], ez[None] / R, z, ez[None] / R, -ez[None])
    a, b, ang, lam = contact_ellipse(plane, sphere, delta, ex[None])
    assert a[0] == pytest.approx(math.sqrt(2 * delta * R), rel=1e-12)
    assert b[0] == pytest.approx(math.sqrt(2 * delta * R), rel=1e-12)


def test_two_full_cycles_and_transitions(planet):
    sun = table_1_1_sun(beta_deg=10.0)
    r = run_pair_tca(GearPair(sun, planet), TCAOptions(cycles=2, steps_per_cycle=40))
    assert len(r.phi1) == 81
    assert r.phi1[-1] - r.phi1[0] == pytest.approx(2 * 2 * math.pi / 41)
    # one transition per cycle, one pitch apart
    assert len(r.transitions) == 2
    assert r.transitions[1] - r.transitions[0] == pytest.approx(2 * math.pi / 41, rel=1e-3)
    # the contact ellipse exists (point contact) and is a few mm long
    assert np.all(np.isfinite(r.ellipse_a)) and 0.5 < np.nanmax(r.ellipse_a) < 15
