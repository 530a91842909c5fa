"""Numerical stability on hard cases: large misalignment, tip contact, nearly singular systems."""

import math

import numpy as np
import pytest

from tca.geometry.gear import Gear
from tca.pair.gear_pair import GearPair, Misalignment
from tca.pair.analysis import ContactKind, TCAOptions, run_pair_tca
from tca.report_data import table_1_1_planet, table_1_1_sun

d = math.radians
from tca.units import ARCMIN, ARCSEC


@pytest.fixture(scope="module")
def sun_planet():
    return table_1_1_sun(beta_deg=10.0), table_1_1_planet()


@pytest.mark.parametrize(
    "mis,edge",
    [
        (Misalignment(d_gamma=30 * ARCMIN), True),  # large crossing: the contact runs to a face edge
        (Misalignment(d_center=0.6), False),  # large centre distance: the crowned contact stays inside
        (Misalignment(d_gamma_v=10 * ARCMIN), None),  # intersecting axes
        (Misalignment(d_ex=0.05, d_axial=2.0), False),  # installment error and axial shift: no edge contact
    ],
)
def test_crowned_pair_stays_solvable_and_verified(sun_planet, mis, edge):
    r = run_pair_tca(GearPair(*sun_planet, mis), TCAOptions(steps_per_cycle=24))
    assert r.max_residual < 1e-10
    assert np.all(np.isfinite(r.te))
    if edge is not None:
        assert r.edge_contact == edge


def test_tip_contact_when_the_contact_ratio_drops_to_one():
    # addendum 0.5 m: the active profile is shorter than one base pitch, so the pair in contact runs
    # off its tooth tip before the next pair meets: edge contact at the tip (boundary 1)
    g1 = Gear("pinion", 30, 2.0, d(20), 20, parabola_pos=0.004, addendum=0.5)
    g2 = Gear("gear", 45, 2.0, d(20), 20, addendum=0.5)
    r = run_pair_tca(GearPair(g1, g2), TCAOptions(steps_per_cycle=24))
    assert r.edge_contact and 1 in r.edge_boundaries()
    assert r.max_residual < 1e-10
    # with the full addendum the same pair has no edge contact
    g1 = Gear("pinion", 30, 2.0, d(20), 20, parabola_pos=0.004)
    g2 = Gear("gear", 45, 2.0, d(20), 20)
    assert not run_pair_tca(GearPair(g1, g2), TCAOptions(steps_per_cycle=24)).edge_contact


def test_coarse_grid_matches_fine_grid(sun_planet):
    # the TE on common positions does not depend on the grid (each position is solved to 1e-11 mm)
    pair = GearPair(*sun_planet, Misalignment(d_gamma=3 * ARCMIN))
    a = run_pair_tca(pair, TCAOptions(steps_per_cycle=10))
    b = run_pair_tca(pair, TCAOptions(steps_per_cycle=40))
    assert np.allclose(a.te_arcsec, b.te_arcsec[::4], atol=1e-7)


@pytest.mark.bench  # a grid study (400 positions, ~45 s): make bench; test_coarse_grid_matches_fine_grid stays
def test_peak_to_peak_is_independent_of_the_grid(sun_planet):
    # the extremes are solved (transitions) or interpolated (vertices): 10 positions per cycle give the
    # peak-to-peak of 400 within 0.01 arcsec, although the grid values alone miss it by ~3 arcsec
    pair = GearPair(*sun_planet, Misalignment(d_gamma=3 * ARCMIN))
    a = run_pair_tca(pair, TCAOptions(cycles=1, steps_per_cycle=10))
    b = run_pair_tca(pair, TCAOptions(cycles=1, steps_per_cycle=400))
    assert abs(a.te_peak_to_peak_arcsec - b.te_peak_to_peak_arcsec) < 0.01
    assert np.allclose(a.transition_te, b.transition_te, atol=1e-9 * 4.8e-6)


def test_profile_crowning_alone_gives_face_edge_contact():
    # A helical pinion crowned in profile only (no plunging): its contact runs along the face with zero
    # TE and reaches the face edges (boundaries 2, 3) - the edge contact that longitudinal crowning
    # (Eq. 1.6) removes; with dgamma = 3 arcmin it is at the edges throughout.
    g1 = Gear("pinion", 21, 2.0, d(20), 20, helix=d(10), hand=1, parabola_pos=0.004)
    g2 = Gear("gear", 35, 2.0, d(20), 20, helix=d(10), hand=-1)
    r = run_pair_tca(GearPair(g1, g2), TCAOptions(steps_per_cycle=12))
    assert r.edge_contact and r.edge_boundaries() <= {2, 3}
    surf = r.kind == ContactKind.SURFACE
    assert np.abs(r.te_arcsec[surf]).max() < 1e-6  # the contact point stays on the pitch line
    r = run_pair_tca(GearPair(g1, g2, Misalignment(d_gamma=3 * ARCMIN)), TCAOptions(steps_per_cycle=12))
    assert np.all(r.kind != ContactKind.SURFACE)
    assert r.max_residual < 1e-10


@pytest.mark.parametrize("beta_deg", [30.0, 40.0])
def test_aligned_helical_pair_converges_at_a_large_helix(beta_deg):
    # issue 24: Newton on the tangency failed on every aligned involute helical pair with beta >= 25 deg
    # (line contact, nearly singular system); tca.pair.sections takes over. Conjugate flanks: TE = 0.
    g1 = Gear("pinion", 20, 3.0, d(20), 30.0, helix=d(beta_deg), hand=1)
    g2 = Gear("wheel", 52, 3.0, d(20), 30.0, helix=d(beta_deg), hand=-1)
    r = run_pair_tca(GearPair(g1, g2), TCAOptions(cycles=1, steps_per_cycle=8))
    assert r.max_residual < 1e-10
    assert np.all(np.isfinite(r.te)) and np.ptp(r.te) < 1e-12  # [rad]: conjugate involute flanks


def test_aligned_crowned_helical_pair_converges():
    # issue 24: z 23/67, m_n 3 mm, beta 15 deg, b 40 mm, lead crowning 10 um, delta gamma = 0 was refused
    from tca.geometry.modifications.crowning import DiskPlunge
    crown = DiskPlunge(100.0, 10e-3 / 20.0**2)  # C_beta = a_pl (b/2)^2
    g1 = Gear("pinion", 23, 3.0, d(20), 40.0, helix=d(15), hand=1, plunge=crown)
    g2 = Gear("wheel", 67, 3.0, d(20), 40.0, helix=d(15), hand=-1, plunge=crown)
    r = run_pair_tca(GearPair(g1, g2), TCAOptions(cycles=1, steps_per_cycle=8))
    assert r.max_residual < 1e-10
    assert np.all(np.isfinite(r.te))
    # crowned flanks touch at a point near the middle of the face: the TE stays below a second of arc
    assert np.ptp(r.te) / ARCSEC < 1.0
