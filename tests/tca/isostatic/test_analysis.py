"""Isostatic planetary train (Part 3, section 3.4): acceptance numbers of issue 4 on the Table 3.1 train.

Every run is one carrier revolution at 720 positions unless stated; case 2 (floating sun, 3 planets).
"""

import dataclasses
import math
import time

import numpy as np
import pytest

from tca.isostatic.dof import TrainConstraints
from tca.isostatic.analysis import ARCSEC, IsostaticOptions, phi1_grid, run_isostatic_tca
from tca.isostatic.flanks import apply, rot2
from tca.isostatic.linear import indexing_closed_form
from tca.isostatic.train import IsostaticTrain
from tca.report_data import indexing_error_placements, table_3_1_gears, table_3_1_planet

d = math.radians
SUN, PLANET, RING = table_3_1_gears()
# Table 3.1 double-crowned planet: a_p = 1.25e-3 1/mm both flanks, a_l read as 6.25e-5 1/mm with r_D = 100 mm
CROWNED = table_3_1_planet(crowned=True)
DET = indexing_error_placements()


def train(planet=PLANET, **kw):
    return IsostaticTrain(SUN, (planet,) * 3, RING, **kw)


def rev(tr, n=720):
    return phi1_grid(tr, n, carrier_revolutions=1.0)


@pytest.fixture(scope="module")
def ideal():
    tr = train()
    t0 = time.perf_counter()
    r = run_isostatic_tca(tr, rev(tr))
    return r, time.perf_counter() - t0


@pytest.fixture(scope="module")
def indexing():
    tr = train(placements=DET)
    return run_isostatic_tca(tr, rev(tr))


@pytest.fixture(scope="module")
def crowned():
    tr = train(CROWNED)
    t0 = time.perf_counter()
    r = run_isostatic_tca(tr, rev(tr))
    return r, time.perf_counter() - t0


@pytest.fixture(scope="module")
def crowned_indexing():
    tr = train(CROWNED, placements=DET)
    return run_isostatic_tca(tr, rev(tr))


def test_ideal_involute_train_has_no_errors(ideal):
    # issue: TE peak-to-peak < 0.01 arcsec, sun centre moves < 0.01 um (measured ~1e-9 arcsec, 0 um)
    r, elapsed = ideal
    assert r.carrier_te_peak_to_peak_arcsec < 0.01
    assert np.abs(r.te_arcsec).max() < 0.01  # absolute TE: the zero-backlash reference of the train is right
    assert np.linalg.norm(r.sun_center_um, axis=1).max() < 0.01
    assert r.all_planets_in_contact
    assert r.residual.max() < 1e-10
    assert elapsed < 30  # issue: one carrier revolution, 720 positions, 3 planets, < 30 s (measured ~0.3 s)


def test_contact_switching_follows_the_tooth_numbering():
    # Over one carrier revolution each mesh passes exactly N3 = 151 pitches ((1 - m_c1)/m_c1 N1 = N3 for the
    # sun mesh), so every tooth index changes 151 times, always by one tooth (Fig. 3.2); no neighbouring
    # pair interferes at the converged positions (backlash >= -1e-8 mm, the tie tolerance).
    tr = train(placements=DET)
    phi = np.linspace(0, 2 * math.pi / tr.ratio, 721)
    r = run_isostatic_tca(tr, phi)
    for i in range(3):
        for k, N in enumerate((65, 43, 43, 151)):
            steps = np.mod(np.diff(r.teeth[:, i, k]), N)
            assert int(np.sum(steps != 0)) == 151
            assert set(np.unique(steps)) <= {0, 1, N - 1}
    assert np.nanmin(r.backlash) >= -1e-8
    assert not np.isnan(r.backlash).any()


def test_indexing_error_involute_matches_section_3_4_2(indexing):
    r = indexing
    cf = indexing_closed_form(SUN.r_b, d(20), r.train.ratio, 0.020)
    c, radius = r.sun_circle
    # issue: circle radius 25 +- 1 um; closed form 2s/3 = 25.058 um, agreement within 0.05 um (second order
    # in the error: (20 um)^2 / r_b1 ~ 3e-6 mm relative terms; measured 0.003 um)
    assert radius == pytest.approx(25.0, abs=1.0)
    assert radius == pytest.approx(cf.dE1 * 1e3, abs=0.05)
    assert np.hypot(*c) < 0.05  # centred on the mechanism's axis
    # issue: lag grows by 6.38 +- 0.2 arcsec and stays constant; closed form m_c1 s / (3 r_b1) = 6.366 arcsec
    # within 0.01 arcsec (second order; measured 0.001)
    assert r.carrier_lag_mean_arcsec == pytest.approx(6.38, abs=0.2)
    assert r.carrier_lag_mean_arcsec == pytest.approx(cf.dphic / ARCSEC, abs=0.01)
    assert r.carrier_te_peak_to_peak_arcsec < 0.01
    assert r.all_planets_in_contact
    # Fig. 3.9: the sun moves along the line of action of planet 1, nu_1 = R(q_1)(sin a, cos a), fixed in the carrier
    ang = np.arctan2(r.sun_center[:, 1], r.sun_center[:, 0])
    assert np.abs(np.angle(np.exp(1j * (ang - (r.phi_c + math.pi / 2 - d(20)))))).max() < 1e-5


def test_direct_solve_agrees_with_fictitious_unknowns():
    # the simultaneous Newton solve of all 18 unknowns and the fictitious-unknowns method (Eqs. 3.21-3.22)
    # converge to the same configuration (1e-8 arcsec, 1e-6 um: both solve to 1e-11 mm)
    tr = train(CROWNED, placements=DET)
    phi = phi1_grid(tr, 60, carrier_revolutions=0.05)
    a = run_isostatic_tca(tr, phi)
    b = run_isostatic_tca(tr, phi, IsostaticOptions(method="direct"))
    assert np.abs(a.te_arcsec - b.te_arcsec).max() < 1e-8
    assert np.abs(a.sun_center_um - b.sun_center_um).max() < 1e-6
    assert np.array_equal(a.teeth, b.teeth)


def test_carrier_centre_error_gives_no_transmission_errors():
    # issue: < 0.05 arcsec peak-to-peak. The sun settles at a fixed point 2 cos(alpha) |dE_c| from the axis
    # (first-order closed form, tca.isostatic.linear; 0.01 um allows the second-order terms)
    tr = train(carrier_center=(0.020, 0.0))
    r = run_isostatic_tca(tr, rev(tr))
    assert r.carrier_te_peak_to_peak_arcsec < 0.05
    assert abs(r.carrier_lag_mean_arcsec) < 0.01
    mag = np.linalg.norm(r.sun_center_um, axis=1)
    assert np.ptp(r.sun_center_um, axis=0).max() < 0.01  # fixed position
    assert mag.mean() == pytest.approx(2 * math.cos(d(20)) * 20.0, abs=0.01)
    assert r.all_planets_in_contact


def test_sun_runout_is_cancelled_by_the_floating_sun():
    # issue: the sun centre runs on a circle of radius 20 um; no TE (< 0.05 arcsec). The axis moves opposite to
    # the eccentricity: the circle repeats every sun revolution (checked at phi1 and phi1 + 2 pi, 1e-6 um).
    tr = train().with_(sun=dataclasses.replace(SUN, runout=0.020, runout_phase=0.4))
    phi = phi1_grid(tr, 721, sun_revolutions=1.0 + 1 / 720)
    r = run_isostatic_tca(tr, phi)
    c, radius = r.sun_circle
    assert radius == pytest.approx(20.0, abs=0.01)
    assert np.hypot(*c) < 0.01
    assert r.carrier_te_peak_to_peak_arcsec < 0.05
    assert np.abs(r.sun_center_um[-1] - r.sun_center_um[0]).max() < 1e-6
    e = np.c_[np.cos(r.phi1 + 0.4), np.sin(r.phi1 + 0.4)] * 20.0  # eccentricity vector in S_f [um]
    assert np.abs(r.sun_center_um + e).max() < 0.01


def test_planet_runout_gives_harmonic_te_with_the_planet_period():
    # issue: TE periodic with a period of 0.9463 sun revolutions, 1 / ((1 - m_c1) N1 / N2); the estimate
    # (least-squares sinusoid over three periods) is within 1e-3 sun revolutions (measured 4e-6).
    # Amplitude: first-order closed form m_c1 2 cos(a) eps / (3 r_b1) = 6.366 arcsec (0.05 arcsec: second order).
    tr = train().with_(planets=(dataclasses.replace(PLANET, runout=0.020), PLANET, PLANET))
    r = run_isostatic_tca(tr, phi1_grid(tr, 720, planet_revolutions=3.0))
    per = r.te_period_sun_rev()
    assert per == pytest.approx(0.9463, abs=1e-3)
    assert per == pytest.approx(1 / tr.planet_ratio, abs=1e-3)
    amp = tr.ratio * 2 * math.cos(d(20)) * 0.020 / (3 * SUN.r_b) / ARCSEC
    assert r.carrier_te_peak_to_peak_arcsec == pytest.approx(2 * amp, abs=0.05)
    assert r.all_planets_in_contact
    # the period in the data itself: TE(phi1 + P) = TE(phi1) within 0.01 arcsec
    P = 2 * math.pi / tr.planet_ratio
    shifted = np.interp(r.phi1[r.phi1 + P <= r.phi1[-1]] + P, r.phi1, r.te_arcsec)
    assert np.abs(shifted - r.te_arcsec[: len(shifted)]).max() < 0.01


def test_double_crowned_planets_give_an_almost_constant_lag(crowned):
    # Report (Fig. 3.6): "the carrier lags ... of about 2 arcsec ... practically constant". Measured: mean lag
    # 1.82 arcsec, peak-to-peak 0.58 arcsec, while one subtrain alone (case 1) fluctuates by 5.4 arcsec.
    r, elapsed = crowned
    assert 1.5 < r.carrier_lag_mean_arcsec < 2.5
    assert r.carrier_te_peak_to_peak_arcsec < 1.0
    assert r.all_planets_in_contact
    assert elapsed < 30
    # The sun moves by 6.29 um: regression pin (the report says "about 1 um", asserted under a strict xfail in
    # test_double_crowned_sun_motion_is_the_reports_1_um; here the first harmonics of the sun-side and ring-side
    # crowning errors of each planet add, see the bench report and docs/deviations.md).
    mag = np.linalg.norm(r.sun_center_um, axis=1)
    assert mag.max() == pytest.approx(6.29, abs=0.02)
    single = run_isostatic_tca(IsostaticTrain(SUN, (CROWNED,), RING, TrainConstraints(1)),
                               phi1_grid(r.train, 200, sun_revolutions=0.05))
    assert single.carrier_te_peak_to_peak_arcsec > 5 * r.carrier_te_peak_to_peak_arcsec


def test_double_crowned_indexing_error_adds_the_same_lag(crowned, crowned_indexing):
    # Report 3.4.2: lag ~8.2 arcsec with double crowning; the increase from case 1 equals the closed form 6.38
    # "for both cases of involute and double crowned gears". Measured: 8.19 arcsec, increase 6.367.
    r0, _ = crowned
    r = crowned_indexing
    cf = indexing_closed_form(SUN.r_b, d(20), r.train.ratio, 0.020).dphic / ARCSEC
    assert r.carrier_lag_mean_arcsec == pytest.approx(8.2, abs=0.2)
    assert r.carrier_lag_mean_arcsec - r0.carrier_lag_mean_arcsec == pytest.approx(cf, abs=0.05)
    assert r.sun_circle[1] == pytest.approx(25.0, abs=1.0)  # "averaged" circle with triangular vibrations
    assert r.all_planets_in_contact


def test_floating_sun_superposes_the_subtrains_to_first_order():
    # The floating sun takes the mean of the three subtrains' carrier errors and moves by
    # e = 2/3 sum_i (s_i - mean s) nu_i (tca.isostatic.linear) where s_i = -(r_b1 / m_c1) dphi_c^(i) are the
    # subtrains' openings computed alone (rigid train). For the double-crowned planets (openings ~10 um) the
    # prediction holds to 0.02 arcsec and 0.05 um (second order; measured 0.004 arcsec, 0.013 um).
    tr = train(CROWNED)
    phi = phi1_grid(tr, 120, carrier_revolutions=0.1)
    fl = run_isostatic_tca(tr, phi)
    rg = run_isostatic_tca(tr.with_(constraints=TrainConstraints(3)), phi)
    assert not rg.all_planets_in_contact  # a rigid hyperstatic train loses contact at some planets
    m, K, al = tr.ratio, SUN.r_b / tr.ratio, d(20)
    te_i = rg.phi_c_planets - m * phi[:, None]
    s = -K * te_i
    q = m * phi[:, None] + tr.theta
    nu = apply(rot2(q), np.array([math.sin(al), math.cos(al)]))  # outward normal of the sun flank, mesh i
    e = (2 / 3) * np.einsum("ni,nij->nj", s - s.mean(1, keepdims=True), nu)
    assert np.abs(fl.te - te_i.mean(1)).max() / ARCSEC < 0.02
    assert np.abs(fl.sun_center - e).max() * 1e3 < 0.05


def test_longitudinal_crowning_does_not_change_the_planar_results():
    # the plunging disk leaves the middle section of the planet unchanged (contact stays there): the
    # train with and without a_l gives the same TE and sun motion (1e-8 arcsec, 1e-8 um: round-off of the
    # Chebyshev deviation fit, < 1e-9 mm)
    tr = train(CROWNED)
    phi = phi1_grid(tr, 40, carrier_revolutions=0.03)
    a = run_isostatic_tca(tr, phi)
    b = run_isostatic_tca(train(dataclasses.replace(CROWNED, plunge=None)), phi)
    assert np.abs(a.te_arcsec - b.te_arcsec).max() < 1e-8
    assert np.abs(a.sun_center_um - b.sun_center_um).max() < 1e-8


@pytest.mark.xfail(strict=True, reason="measured 6.3 um: the first harmonics of the sun-side and ring-side crowning "
                   "errors of each planet add (report: about 1 um; docs/deviations.md)")
def test_double_crowned_sun_motion_is_the_reports_1_um(crowned):
    # Report, Part 3 (Fig. 3.6 discussion): the sun centre moves by "about 1 um" with double-crowned planets
    r, _ = crowned
    assert np.linalg.norm(r.sun_center_um, axis=1).max() == pytest.approx(1.0, abs=0.5)
