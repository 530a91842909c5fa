"""Planetary train with face gears (Part 2): kinematics (Eqs. 2.1-2.4), two-stage TCA (Steps 1-4), delta."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tca.errors import InputError
from tca.face.face_gear import FaceGear
from tca.face.subgear import ARCSEC, EDGE, _Contacts
from tca.face.train import (FaceTrain, basic_ratio, run_face_train, scan_delta, stage_results, train_efficiency,
                            train_ratio, willis)
from tca.geometry.gear import Gear

d = math.radians
PI17 = math.pi / 17


# ------------------------------------------------------------------------------------------ kinematics
def test_example_2_1_ratio_and_efficiency():
    # Eq. (2.4): 100 / (100 - 88) = 8.333; "about 77.5 percent" with 2 % per mesh (to 0.05 %, rounding of
    # the report); closed form of the reducer: (1 - i0) / (1 - i0 eta0), i0 = 0.88, eta0 = 0.98^2 (1e-12)
    assert train_ratio(100, 17, 17, 88) == pytest.approx(100 / 12, rel=1e-12)
    assert train_ratio(100, 7, 7, 88) == pytest.approx(100 / 12, rel=1e-12)  # the text's N2 = N3 = 7: same ratio
    eta = train_efficiency(100, 17, 17, 88, 0.02)
    assert eta == pytest.approx(0.775, abs=5e-4)
    assert eta == pytest.approx(0.12 / (1 - 0.88 * 0.98**2), rel=1e-12)
    # Eq. (2.2) with N2 != N3
    assert train_ratio(100, 18, 17, 88) == pytest.approx(100 * 17 / (100 * 17 - 18 * 88), rel=1e-12)


def test_uses_of_the_train():
    # multiplier as the report words it (gear 1 fixed, carrier in, gear 4 out) and the reducer run
    # backwards (gear 1 in, carrier out: the speed increaser); differential through the Willis relation
    assert train_ratio(100, 17, 17, 88, "gear1", "carrier", "gear4") == pytest.approx(1 / (1 - 100 / 88), rel=1e-12)
    assert train_ratio(100, 17, 17, 88, "gear4", "gear1", "carrier") == pytest.approx(0.12, rel=1e-12)
    assert train_efficiency(100, 17, 17, 88, 0.0, "gear4", "gear1", "carrier") == pytest.approx(1.0, abs=1e-12)
    assert willis(100, 17, 17, 88, w4=0.0, wc=1.0) == pytest.approx(0.12, rel=1e-12)
    w1 = willis(100, 17, 17, 88, w4=0.3, wc=1.0)
    assert willis(100, 17, 17, 88, w1=w1, wc=1.0) == pytest.approx(0.3, abs=1e-12)
    assert willis(100, 17, 17, 88, w1=w1, w4=0.3) == pytest.approx(1.0, abs=1e-12)


@settings(max_examples=60, deadline=None)
@given(st.integers(20, 200), st.integers(8, 40), st.integers(8, 40), st.integers(20, 200), st.floats(0.001, 0.05))
def test_kinematics_invariants(n1, n2, n3, n4, loss):
    if n1 * n3 == n2 * n4:
        with pytest.raises(InputError, match="N1 N3 != N2 N4"):
            basic_ratio(n1, n2, n3, n4)
        return
    r = train_ratio(n1, n2, n3, n4)
    assert r == pytest.approx(n1 * n3 / (n1 * n3 - n2 * n4), rel=1e-9)
    for members in (("gear4", "carrier", "gear1"), ("gear4", "gear1", "carrier"), ("gear1", "carrier", "gear4")):
        eta = train_efficiency(n1, n2, n3, n4, loss, *members)
        assert eta < 1.0
        assert train_efficiency(n1, n2, n3, n4, 0.0, *members) == pytest.approx(1.0, abs=1e-9)


def test_invalid_tooth_numbers_get_a_clear_error():
    with pytest.raises(InputError, match=r"N1 N3 != N2 N4.*100\*17 = 17\*100"):
        train_ratio(100, 17, 17, 100)
    with pytest.raises(InputError, match="train.fixed"):
        train_ratio(100, 17, 17, 88, "sun", "carrier", "gear1")
    with pytest.raises(InputError, match="three different members"):
        train_ratio(100, 17, 17, 88, "gear4", "gear4", "gear1")


# ------------------------------------------------------------------------------------------ Table 2.1
@pytest.fixture(scope="module")
def table21():
    shaper = Gear("shaper", 20, 5.0, d(20), 120.0, helix=d(10), hand=1, addendum=1.25, tool_addendum=1.3)
    pin = dict(module=5.0, pressure_angle=d(20), face_width=52.0, helix=d(10), hand=1, parabola_pos=0.001,
               parabola_neg=0.001, tool_tip_radius=0.45)
    return (FaceGear("gear1", 100, shaper, d(75), crowning=0.002), FaceGear("gear4", 88, shaper, d(75), crowning=0.002),
            Gear("pinion2", 17, **pin), Gear("pinion3", 17, **pin))


@pytest.fixture(scope="module")
def reducer(table21):
    train = FaceTrain(*table21, delta=PI17, use="reducer")
    ra, rb = stage_results(train, 60)
    return train, ra, rb, scan_delta(train, ra, rb, samples=48)


@pytest.fixture(scope="module")
def multiplier(table21):
    train = FaceTrain(*table21, delta=PI17, use="multiplier")
    ra, rb = stage_results(train, 60)
    return train, ra, rb, scan_delta(train, ra, rb, samples=48)


def test_face_widths_from_undercutting_and_pointing(table21):
    # derived radii bracket the pitch radius; the paths of contact stay on the face (checked in the TCA)
    g1, g4 = table21[:2]
    assert g1.L1 < g1.pitch_radius < g1.L2
    assert g4.L1 < g4.pitch_radius < g4.L2
    assert g1.pitch_radius - g4.pitch_radius == pytest.approx(5.0 / math.cos(d(10)) * 6, rel=1e-12)


def test_steps_1_to_4_pick_the_pair_that_drives_furthest(reducer):
    # Steps 1-4 choose the pairs by the transition angles (Eqs. 2.5-2.12); independently, the pair in
    # contact of each sub-drive is the one giving the largest driven angle. Both agree to 1e-12 rad.
    train, ra, rb, _ = reducer
    res = run_face_train(train, cycles=1, steps_per_cycle=16, stages=(ra, rb))
    ca, cb = train.phase_offsets()

    def brute(r, phi):
        T = r.mesh.pitches[0]
        best = np.full(len(phi), -np.inf)
        for j in range(-2, 3):
            ph = phi - j * T
            ok = (ph > r.phi[0] + 1e-9) & (ph < r.phi[-1] - 1e-9)
            if ok.any():
                best[ok] = np.maximum(best[ok], r.solve(phi[ok], j)[0][:, 4])
        return best

    pa = brute(ra, res.phi_in)
    assert np.abs(pa - ca - res.phi_p).max() < 1e-12
    assert np.abs(brute(rb, res.phi_p + cb) - res.phi_out).max() < 1e-12


def test_reducer_table_2_1(reducer):
    train, ra, rb, scan = reducer
    res = run_face_train(train, cycles=3, steps_per_cycle=30, stages=(ra, rb))
    # delta = pi/17: two parabolic branches per cycle (Fig. 2.4), the middle and the backward pair of sub-drive 2
    assert res.branches_per_cycle == 2
    assert set(np.unique(res.pair_b)) == {0, 1}
    assert not res.edge.any()
    assert res.phi_in[-1] - res.phi_in[0] == pytest.approx(3 * 2 * math.pi / 88, rel=1e-12)
    # one branch where the transitions coincide: report pi/17 - 0.134658; this model 0.010 rad away (the
    # report's figure depends on its TE functions, which it does not list): within 0.012 rad; there the
    # TE is the largest over delta, about 22 arcsec in the report (1.5 arcsec)
    assert scan.delta_single == pytest.approx(PI17 - 0.134658, abs=0.012)
    single = run_face_train(FaceTrain(*_parts(train), delta=scan.delta_single, use="reducer"), 1, 60, stages=(ra, rb))
    assert single.branches_per_cycle == 1
    assert scan.te_single / ARCSEC == pytest.approx(22.0, abs=1.6)
    assert scan.te_single >= scan.te_pp.max() - 1e-9
    # the optimiser: report delta = pi/17 + 0.0518 (two equal branches, ~6 arcsec); delta within 0.01 rad.
    # Its TE (9.0 arcsec here) is not the report's 6: the two sub-drives' parabolas differ (see README)
    assert scan.delta_opt == pytest.approx(PI17 + 0.0518, abs=0.01)
    assert scan.te_opt_exact == pytest.approx(scan.te_opt, abs=1e-3 * ARCSEC)  # spline scan vs exact solves
    assert scan.te_opt < 0.45 * scan.te_single
    assert scan.te_opt / ARCSEC == pytest.approx(8.98, abs=0.02)  # regression pin (report about 6: strict xfail below)
    best = run_face_train(FaceTrain(*_parts(train), delta=scan.delta_opt, use="reducer"), 1, 60, stages=(ra, rb))
    assert best.branches_per_cycle == 2
    assert min(best.branch_fractions) > 0.4  # nearly equal branches at the optimum


def test_multiplier_table_2_1_with_edge_contact_at_the_inner_radius(multiplier):
    train, ra, rb, scan = multiplier
    res = run_face_train(train, cycles=3, steps_per_cycle=30, stages=(ra, rb))
    assert res.branches_per_cycle == 2
    assert scan.delta_single == pytest.approx(PI17 - 0.134658, abs=0.01)
    assert scan.delta_opt == pytest.approx(PI17 + 0.0518, abs=0.01)
    assert scan.te_opt < 0.45 * scan.te_single
    # pinion 3 drives gear 4 on its +y flank: the path reaches the inner radius L1 of gear 4 (set by the
    # undercutting of its other flank) shortly before the transition: edge contact, verified here
    assert rb.edge_fraction > 0
    e = np.flatnonzero(rb.kind == EDGE)
    cts = _Contacts(rb.mesh, 1e-7)
    x = rb.x[e]
    w1, _, _ = cts.f1.world(x[:, 0], x[:, 1], rb.phi[e])
    w2, l2, _ = cts.f2.world(x[:, 2], x[:, 3], x[:, 4])
    assert np.abs(w1.r - w2.r).max() < 1e-9  # the point is on both flanks
    rho = np.hypot(l2.r[:, 0], l2.r[:, 1])
    assert np.abs(rho - rb.mesh.face.L1).max() < 1e-9  # on the inner edge of gear 4
    tang = cts.tangency(rb.phi[e], x)
    assert np.all(tang.x[:, 4] > x[:, 4])  # the bounded flanks touch later than the extended ones


def _parts(train):
    return train.gear1, train.gear4, train.pinion2, train.pinion3


@pytest.mark.xfail(strict=True, reason="measured 9.0 arcsec at the optimum delta (report about 6): the two sub-drives' "
                   "TE parabolas of this model differ from the report's (docs/deviations.md)")
def test_reducer_optimum_te_is_the_reports_6_arcsec(reducer):
    # Report, Part 2 (Example 2.1): at delta = pi/17 + 0.0518 the two equal branches give about 6 arcsec
    _, _, _, scan = reducer
    assert scan.te_opt / ARCSEC == pytest.approx(6.0, abs=1.0)
