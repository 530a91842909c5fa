"""Bad set-ups and failed solves of the isostatic train TCA fail loudly, naming the field or the position."""

import dataclasses
import math

import numpy as np
import pytest

from tca.isostatic.dof import TrainConstraints
from tca.errors import ConvergenceError, GeometryError, InputError
from tca.isostatic.analysis import IsostaticOptions, phi1_grid, run_isostatic_tca
from tca.isostatic.train import IsostaticTrain, PlanetPlacement
from tca.report_data import indexing_error_placements, table_3_1_gears

d = math.radians
SUN, PLANET, RING = table_3_1_gears()


def test_floating_sun_with_two_planets_is_under_constrained():
    tr = IsostaticTrain(SUN, (PLANET,) * 2, RING)  # 216 / 2: assembles, but N_f - N_c = 1
    with pytest.raises(InputError, match=r"planets.count.*under-constrained"):
        run_isostatic_tca(tr, np.array([0.0]))


def test_floating_sun_with_four_planets_is_hyperstatic():
    tr = IsostaticTrain(SUN, (PLANET,) * 4, RING)  # 216 / 4: assembles, N_f - N_c = -1
    with pytest.raises(InputError, match=r"planets.count.*hyperstatic"):
        run_isostatic_tca(tr, np.array([0.0]))


@pytest.mark.parametrize("make,err,match", [
    (lambda: IsostaticTrain(SUN, (PLANET,) * 5, RING), InputError, r"planets.count.*assembly"),
    (lambda: IsostaticTrain(SUN, (PLANET,) * 3, dataclasses.replace(RING, teeth=150)), InputError, "ring.teeth"),
    (lambda: IsostaticTrain(SUN, (dataclasses.replace(PLANET, helix=d(10)),) * 3, RING), InputError, "helix_deg"),
    (lambda: IsostaticTrain(SUN, (PLANET,) * 3, RING, sun_center=(0.01, 0.0)), InputError, "sun_center_error_um"),
    (lambda: IsostaticTrain(SUN, (PLANET,) * 3, RING, TrainConstraints(1)), InputError, "planets.count"),
    (lambda: IsostaticTrain(SUN, (PLANET,) * 3, RING, placements=(PlanetPlacement(),)), InputError, "planets.errors"),
    (lambda: IsostaticTrain(SUN, (PLANET,) * 8, RING), GeometryError, "overlap"),
    (lambda: IsostaticTrain(SUN, (PLANET, dataclasses.replace(PLANET, teeth=44), PLANET), RING), InputError,
     "planet2.teeth"),
    (lambda: PlanetPlacement(tangential=float("nan")), InputError, "tangential_error_um"),
])
def test_bad_trains_are_rejected(make, err, match):
    with pytest.raises(err, match=match):
        make()


def test_bad_runs_are_rejected():
    tr = IsostaticTrain(SUN, (PLANET,) * 3, RING)
    with pytest.raises(InputError, match="solver.method"):
        IsostaticOptions(method="newton")
    with pytest.raises(InputError, match="exactly one"):
        phi1_grid(tr, 10, sun_revolutions=1.0, carrier_revolutions=1.0)
    with pytest.raises(InputError, match="run.positions"):
        phi1_grid(tr, 0, sun_revolutions=1.0)
    with pytest.raises(InputError, match="phi1"):
        run_isostatic_tca(tr, np.array([]))


def test_outer_newton_that_does_not_converge_names_the_position():
    # the fictitious-unknowns iteration needs 2-3 steps for a 20 um indexing error; allowing one must fail
    tr = IsostaticTrain(SUN, (PLANET,) * 3, RING, placements=indexing_error_placements())
    with pytest.raises(ConvergenceError, match=r"Eqs. 3.21-3.22.*phi1 = 1[23].000000 deg \(position [12] of 2\)"):
        run_isostatic_tca(tr, np.radians([12.0, 13.0]), IsostaticOptions(max_outer=1))


def test_inner_newton_that_cannot_reach_its_tolerance_names_position_and_planet():
    # 1e-14 mm is below the round-off of points ~300 mm from the origin: the subtrain solve stalls
    tr = IsostaticTrain(SUN, (PLANET,) * 3, RING, placements=indexing_error_placements())
    with pytest.raises(ConvergenceError, match=r"Eq. 3.18.*phi1 = .* deg \(position \d of 3\), planet \d"):
        run_isostatic_tca(tr, np.radians([1.0, 2.0, 3.0]), IsostaticOptions(tol=1e-14))


def test_contact_ratio_below_one_is_reported_as_edge_contact():
    # addendum 0.5 m: transverse contact ratio ~0.9, so at some positions no pair touches inside both working
    # areas (the tips' edges carry the load, which the planar TCA does not model)
    short = {g: dataclasses.replace(g, addendum=0.5) for g in (SUN, PLANET, RING)}
    tr = IsostaticTrain(short[SUN], (short[PLANET],) * 3, short[RING])
    with pytest.raises(GeometryError, match=r"(edge contact|outside the working areas).*phi1 = .* deg \(position"):
        run_isostatic_tca(tr, phi1_grid(tr, 60, carrier_revolutions=0.02))


def test_corner_gap_measures_penetration_of_a_point_into_the_mate():
    # The edge-contact check measures end points of working areas against the mate flank. At a solved contact the
    # sun's contact point has gap 0 to the planet flank; turning the planet by +-delta about its axis changes the
    # gap by -+ r_b2 delta along the line of action (1e-9 mm tolerance: Newton foot and round-off; the
    # linearisation error (r_b2 delta)^2 / rho ~ 1e-10 mm for delta = 1e-5 rad).
    from tca.isostatic.flanks import PlacedTeeth
    from tca.isostatic.subtrain import Members, corner_gap, poses

    tr = IsostaticTrain(SUN, (PLANET,) * 3, RING)
    r = run_isostatic_tca(tr, np.array([0.2]))
    fl = tr.flanks()
    m = Members(np.full(3, 0.2), tr.theta, tr.pins, np.zeros((3, 2)), r.teeth.reshape(3, 4), np.zeros((3, 3, 2)))
    gaps = []
    for delta in (-1e-5, 0.0, 1e-5):
        P = poses(tr, fl, m, r.phi2[0] + delta, r.phi_c_planets[0])
        g, _ = corner_gap(PlacedTeeth(fl.sun, P.As, P.cs, m.teeth[:, 0]), r.params[0, :, 0],
                          PlacedTeeth(fl.planet_s, P.Ap, P.cp, m.teeth[:, 1]))
        gaps.append(g)
    gaps = np.array(gaps)
    assert np.abs(gaps[1]).max() < 1e-9
    slope = PLANET.r_b * 1e-5
    assert np.abs(np.abs(gaps[0]) - slope).max() < 1e-9 and np.abs(np.abs(gaps[2]) - slope).max() < 1e-9
    assert np.all(np.sign(gaps[0]) == -np.sign(gaps[2]))
