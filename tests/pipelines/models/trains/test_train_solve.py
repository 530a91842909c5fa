"""The coupled train solve against closed forms (docs/trains.md): equal shares, a pin error, a floating sun, the pair.

A small spur train in phase (N1 = 24, N2 = 21, N3 = 66, three planets: N1/3 and N3/3 integers, so every planet
meshes at the same phase), m = 2 mm, b = 10 mm, coarse flank grids (the closed forms hold for any grid)."""

import math

import numpy as np
import pytest

from fem.material import STEEL
from tca.geometry.gear import Gear
from tca.isostatic.linear import linear_response
from tca.isostatic.train import IsostaticTrain, PlanetPlacement

from pipelines.models.ltca.contact import SliceLaw, solve_contact
from pipelines.models.trains.geometry import TrainErrors, single_layout
from pipelines.models.trains.model import build_train_model
from pipelines.models.trains.options import TrainOptions
from pipelines.models.trains.run import solve_run
from pipelines.models.trains.solver import MeshBlock, RigidSystem, solve_train

T = 100e3  # N mm on the sun
ALPHA = math.radians(20.0)


def gears():
    d = math.radians
    return (Gear("sun", 24, 2.0, d(20), 10), Gear("planet", 21, 2.0, d(20), 10),
            Gear("ring", 66, 2.0, d(20), 10, internal=True))


@pytest.fixture(scope="module")
def fixed():
    lay = single_layout(*gears(), 3)
    return build_train_model(lay, TrainOptions(torques=(T,), profile_size=1.0, axial_size=2.5))


@pytest.fixture(scope="module")
def floating(fixed):
    from dataclasses import replace

    return fixed.with_options(replace(fixed.opts, sun_axis="floating"))


PSI = 2 * math.pi * np.arange(3) / (3 * 24)  # three positions over a mesh cycle


def pin(e_t, e_r=0.0, planet=0):
    p = [(0.0, 0.0)] * 3
    p[planet] = (e_r, e_t)
    return TrainErrors(pins=tuple(p))


def test_ideal_train_equal_shares(fixed):
    r = solve_run(fixed, TrainErrors(), T, PSI)
    assert np.abs(r.sun_share * 3 - 1).max() < 0.005
    assert np.abs(r.ring_share * 3 - 1).max() < 0.005
    assert r.k_gamma == pytest.approx(1.0, abs=0.005)
    assert r.unloaded == []


def path_stiffness(model, psi, h=0.02):
    """Tangent stiffness [N/mm] of one planet's path (sun mesh and ring mesh in series) along the line of action,
    from the ideal train at T and T (1 + h): dP / du with P = s T / r_b1 and u = r_b1 omega_1."""
    rb = model.layout.sun.r_b
    a, b = (solve_run(model, TrainErrors(), t, [psi]) for t in (T, T * (1 + h)))
    dP = (b.sun_share[0, 0] * b.torque - a.sun_share[0, 0] * a.torque) / rb
    du = -(b.te[0] - a.te[0]) / model.layout.carrier_ratio * rb
    return dP / du


@pytest.mark.parametrize("e", [0.5e-3, -0.5e-3])
def test_single_pin_error_linear_and_closed_form(fixed, e):
    """Sun held: K_gamma - 1 proportional to e, and = n k (e-bar - e_i) 2 cos(alpha) r_b1 / T at the most loaded planet
    (docs/trains.md, Eq. T6)."""
    psi = PSI[:1]
    k1 = solve_run(fixed, pin(e), T, psi).k_gamma - 1
    k2 = solve_run(fixed, pin(2 * e), T, psi).k_gamma - 1
    assert k2 / k1 == pytest.approx(2.0, rel=0.02)
    k = path_stiffness(fixed, psi[0])
    a = np.array([2 * e * math.cos(ALPHA), 0.0, 0.0])  # the path openings
    closed = 3 * k * float((a.mean() - a).max()) * fixed.layout.sun.r_b / T
    assert k1 == pytest.approx(closed, rel=0.05)


def test_floating_sun_shares_and_centre(floating):
    """Floating sun, one pin error (tangential and radial): K_gamma = 1 and the sun centre where the unloaded
    isostatic TCA puts it (first order, tca.isostatic.linear)."""
    e_t, e_r = 5e-3, 3e-3
    r = solve_run(floating, pin(e_t, e_r, planet=1), T, PSI)
    assert r.k_gamma == pytest.approx(1.0, abs=0.01)
    sun, pl, ring = gears()
    iso = IsostaticTrain(sun, (pl,) * 3, ring, placements=(PlanetPlacement(), PlanetPlacement(e_t, e_r),
                                                          PlanetPlacement()))
    mc = floating.layout.carrier_ratio
    lin = linear_response(iso, PSI / (1 - mc))  # the sun's absolute angle
    err = np.linalg.norm(r.sun_center - lin.sun_center, axis=1) / np.linalg.norm(lin.sun_center, axis=1)
    assert err.max() < 0.05


def test_pair_regression(fixed):
    """One mesh, the driven rotation its only DOF: the train solve is the pair LTCA's solve."""
    key = next(iter(fixed.layout.pairs))
    L = fixed.slices(key, 0.3).lines
    torque = 300e3 * L.arm0 / 100.0
    ref = solve_contact(L, torque, STEEL, fixed.local)
    L0 = max(float(np.ptp(L.xi[L.pair == 0])), L.ds)
    block = MeshBlock(L.W, L.gap, L.arm[:, None], SliceLaw(L.length, L.radius, L.depth), L.kappa,
                      torque / L.arm0 / L0)
    sol = solve_train([block], RigidSystem(np.zeros((1, 1)), np.array([torque]), np.array([torque])), STEEL,
                      fixed.local)
    assert sol.q[0] == pytest.approx(ref.delta, rel=1e-6)
    np.testing.assert_allclose(sol.F[0], ref.F, atol=1e-6 * ref.F.sum())
    np.testing.assert_allclose(sol.pressure[0], ref.pressure, rtol=1e-5, atol=1e-6 * ref.pressure.max())


def test_unloaded_planet_is_a_result(fixed):
    """A large positive pin error lifts planet 1 off both meshes: its share is 0 and it is reported."""
    r = solve_run(fixed, pin(0.05), T, PSI[:1])
    assert r.sun_share[0, 0] == 0.0
    assert r.unloaded == [(1, 1)]
    assert r.sun_share[0].sum() == pytest.approx(1.0, rel=1e-9)


def test_elastic_pins_closed_form(fixed):
    """Pins of stiffness k_p: the planet force 2 P cos(alpha) (tangential) moves the pin by 2 P cos(alpha) / k_p, which
    opens the path by 2 cos(alpha) times that: the path stiffness becomes 1 / (1/k + 4 cos^2(alpha) / k_p) in
    Eq. (T6) (docs/trains.md)."""
    from dataclasses import replace

    kp = 300e3  # N/mm = 300 N/um
    model = fixed.with_options(replace(fixed.opts, pin_stiffness=kp))
    e, psi = 0.5e-3, PSI[:1]
    ideal = solve_run(model, TrainErrors(), T, psi)
    assert ideal.k_gamma == pytest.approx(1.0, abs=0.005)
    k1 = solve_run(model, pin(e), T, psi).k_gamma - 1
    k = path_stiffness(fixed, psi[0])
    keff = 1.0 / (1.0 / k + 4 * math.cos(ALPHA) ** 2 / kp)
    closed = 2 * keff * e * math.cos(ALPHA) * fixed.layout.sun.r_b / T
    assert k1 == pytest.approx(closed, rel=0.05)
    assert k1 < solve_run(fixed, pin(e), T, psi).k_gamma - 1


def test_sun_support_between_held_and_floating(fixed):
    """A sun on a support: stiff, it behaves as held; soft, as floating (K_gamma between, monotone)."""
    from dataclasses import replace

    psi, err = PSI[:1], pin(2e-3)
    held = solve_run(fixed, err, T, psi).k_gamma
    floating = solve_run(fixed.with_options(replace(fixed.opts, sun_axis="floating")), err, T, psi).k_gamma
    k = [solve_run(fixed.with_options(replace(fixed.opts, sun_support=s)), err, T, psi).k_gamma
         for s in (1e9, 1e5, 1e3)]
    assert k[0] == pytest.approx(held, abs=1e-3) and k[2] == pytest.approx(floating, abs=2e-3)
    assert held > k[1] > floating


def test_twin_train_in_phase_members_share_equally():
    """A double-helical train (Part 1's kind) in phase, no errors: every member of every twin carries 1/(2n)."""
    from tca.planetary.train import DoubleHelicalTrain, ShaftErrors
    from pipelines.models.trains.geometry import double_helical_layout

    d = math.radians
    sun = Gear("sun", 27, 2.0, d(20), 8, helix=d(10), hand=1)
    planet = Gear("planet", 24, 2.0, d(20), 8, helix=d(10), hand=-1, parabola_pos=0.005, parabola_neg=0.005)
    ring = Gear("ring", 75, 2.0, d(20), 8, helix=d(10), hand=-1, internal=True)
    train = DoubleHelicalTrain(sun, planet, ring, 3, 4.0)
    lay = double_helical_layout(train, [ShaftErrors()] * 3, [(0.0, 0.0)] * 3)
    assert sum(s.mirror for s in lay.sites) == 6 and len(lay.pairs) == 2  # member b: member a's slices mirrored
    from tca.pair.analysis import TCAOptions

    model = build_train_model(lay, TrainOptions(torques=(T,), profile_size=1.5, axial_size=4.0, slice=2.0,
                                                positions_per_cycle=1, tca=TCAOptions(steps_per_cycle=12)))
    r = solve_run(model, TrainErrors(), T, [0.0])
    assert np.abs(r.member_share * 6 - 1).max() < 0.005
    assert r.k_gamma_members == pytest.approx(1.0, abs=0.005)
