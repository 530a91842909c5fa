"""Regulation of backlash and integrated TE (Numerical Examples 1.1, 1.2; Table 1.2; Figs. 1.4, 1.5)."""

import math

import numpy as np
import pytest

from tca.errors import ConvergenceError
from tca.pair.analysis import ARCSEC, TCAOptions
from tca.planetary.train import ShaftErrors
from tca.planetary.regulation import (RegulationOptions, nominal_peak, periodic_peak, regulate_member, regulate_train,
                                     twin_te)
from tca.report_data import table_1_1_train

d = math.radians
# 20 steps per cycle (the case files use 40): the peaks are refined by a parabola through three samples
OPTS = TCAOptions(cycles=1, steps_per_cycle=20)
TABLE_1_2 = [(0, 0.0, 0.0), (20, -4.44, -4.6), (-20, 4.44, 4.6), (5, -1.11, -1.15), (-5, 1.11, 1.15)]


@pytest.fixture(scope="module")
def train():
    return table_1_1_train(beta_sun_deg=10.25, beta_ring_deg=9.75)


@pytest.fixture(scope="module")
def example_1_1(train):
    return regulate_train(train, [ShaftErrors(d_ex=x * 1e-3) for x, _, _ in TABLE_1_2], OPTS)


def test_table_1_2_axial_displacements(example_1_1):
    # Delta Z^(1) against the report's Table 1.2 (Eq. 1.16) to 0.01 mm. Our TCA balances the maxima at
    # Delta Z^(2) = Delta Z^(1) to better than 0.5 % (closed form: the sensitivities of the TE maximum to
    # Delta E_x (2/r3) and to Delta Z ((tan b1 - tan b3)/r3) are first-order exact here, see
    # test_sensitivities_are_first_order), so the report's 3.5 % larger Delta Z^(2) is not reproduced:
    # test_table_1_2_delta_z2_is_the_reports asserts the report's value under a strict xfail.
    for (ra, rb), (dex, dz1, dz2) in zip(example_1_1.members, TABLE_1_2):
        assert ra.dz1 == pytest.approx(dz1, abs=0.01)
        assert rb is ra  # no shaft-angle error: member b is the mirror image, same Delta Z
        if dex == 0:
            assert ra.dz2 == 0.0
            continue
        assert ra.dz2 == pytest.approx(ra.dz1, rel=0.005)


def test_before_regulation_a_single_planet_is_in_mesh(train, example_1_1):
    # Fig. 1.4(a): planet 2^(2) (Delta E_x = +20 um, ahead by 2 Delta E_x / r3 = 74.5 arcsec) drives at every
    # phi1, with a clear margin over the next planet; the others have backlash |M2 Mi|
    b = example_1_1.before
    assert set(b.in_mesh.tolist()) == {1}
    s = b.summary()
    assert s["min_margin_to_next_planet_arcsec"] > 20
    # planet 2 is ahead of the error-free planet 1 by 2 Delta E_x / r3 (to 0.2 %: crowning, tilt-free)
    assert b.peaks[1] - b.peaks[0] == pytest.approx(2 * 0.02 / train.ring.r_p, rel=2e-3)


def test_after_regulation_the_spread_is_10x_smaller(example_1_1):
    # issue 3: spread of the planets' TE functions (of their maxima) at least 10x smaller after regulation;
    # the secant stops at |max - target| < 1e-3 arcsec, so the spread is below 2e-3 arcsec
    before, after = example_1_1.before.spread, example_1_1.after.spread
    assert before / ARCSEC > 140  # 74.5 + 74.5 arcsec
    assert after < before / 10
    assert after / ARCSEC < 2e-3
    # Delta Z^(1) alone balances to within 0.2 arcsec here; all planets now take turns in mesh (Fig. 1.4(b))
    assert example_1_1.first_order.spread / ARCSEC < 0.2
    assert set(example_1_1.after.in_mesh.tolist()) == {0, 1, 2, 3, 4}
    # the integrated TE of the train is much smaller than any single planet's function
    assert np.ptp(example_1_1.after.integrated) < 0.3 * np.ptp(example_1_1.before.integrated)


def test_sensitivities_are_first_order(train):
    # the TE maximum moves by 2/r3 per mm of Delta E_x and by (tan b1 - tan b3)/r3 per mm of Delta Z: checked by
    # finite differences on the TCA (to 0.5 %), the reason Delta Z^(2) = Delta Z^(1) in our TCA
    cache = {}
    p0 = nominal_peak(train, OPTS, cache)
    pz = periodic_peak(twin_te(train, 0, ShaftErrors(), (1.0, 1.0), OPTS, cache).te)
    px = periodic_peak(twin_te(train, 0, ShaftErrors(d_ex=0.01), (0.0, 0.0), OPTS, cache).te)
    r3 = train.ring.r_p
    assert (pz - p0) == pytest.approx((math.tan(d(10.25)) - math.tan(d(9.75))) / r3, rel=5e-3)
    assert (px - p0) / 0.01 == pytest.approx(2 / r3, rel=5e-3)


@pytest.fixture(scope="module")
def example_1_2(train):
    errors = [ShaftErrors(d_gamma=d(3 / 60))] + [ShaftErrors()] * 4
    return regulate_train(train, errors, OPTS)


def test_shaft_angle_error_members_a_and_b(example_1_2):
    # Numerical Example 1.2 (Fig. 1.5): Delta gamma = 3 arcmin turns the shaft about e_r through its centre, so
    # member a moves by +17.45 um (in the sense of Delta E_x) and b by -17.45 um, and both tilt. Before
    # regulation a and b differ by ~150 arcsec; after their independent axial regulation their maxima coincide
    # (< 1e-2 arcsec). Their functions stay shifted in phase (the tilt shifts the parabolas; each mm of Delta Z
    # shifts a function by tan(b1)/r1 = 0.25 deg of phi1), so pointwise they still differ by ~20 arcsec.
    ra, rb = example_1_2.members[0]
    assert rb is not ra
    a0, b0 = ra.before.te3 / ARCSEC, rb.before.te3 / ARCSEC
    a1, b1 = ra.after.te3 / ARCSEC, rb.after.te3 / ARCSEC
    assert abs(periodic_peak(a0) - periodic_peak(b0)) > 100
    assert abs(periodic_peak(a1) - periodic_peak(b1)) < 1e-2
    assert np.abs(a1 - b1).max() < np.abs(a0 - b0).max() / 5
    # the members move in opposite senses relative to the mirror convention (a retarded, b advanced)
    assert ra.dz2 < 0 < rb.dz2
    # the twin now engages together with the error-free planets
    assert example_1_2.after.spread / ARCSEC < 2e-3
    assert set(example_1_2.before.in_mesh.tolist()) == {0}


def test_regulation_failure_names_the_member(train):
    # two TCA evaluations allowed, a target 50 arcsec away cannot be met: ConvergenceError names the member
    with pytest.raises(ConvergenceError, match="shaft 2 member a"):
        regulate_member(train, 1, "a", ShaftErrors(d_ex=0.02), 50 * ARCSEC, OPTS, RegulationOptions(maxiter=2))


@pytest.mark.xfail(strict=True, reason="measured Delta Z(2) 3.4 % below the report's 4.6 and 1.15 mm (equal to Delta Z(1) "
                   "to 0.5 %: first-order exact sensitivities here; docs/deviations.md)")
def test_table_1_2_delta_z2_is_the_reports(example_1_1):
    # Report Table 1.2: Delta Z^(2) = -4.6, 4.6, -1.15, 1.15 mm (given to 2-3 digits: 1 % tolerance)
    for (ra, _), (dex, _, dz2) in zip(example_1_1.members, TABLE_1_2):
        if dex:
            assert ra.dz2 == pytest.approx(dz2, rel=0.01)
