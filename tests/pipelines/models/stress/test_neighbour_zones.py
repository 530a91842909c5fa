"""Refined zones of neighbouring pairs (pipelines.models.stress.scene.neighbour_params): both flanks at one place.

Conjugate flanks (an aligned, unmodified internal pair) make every neighbouring pair "touch" in the TCA
with gap 0 at a tangency of the extended surfaces outside the working areas. Placed independently, the
pinion's zone went below its form circle and the ring's to its tip, and the contact check refused the
model (slave finer than master where they touch, face-size ratio 1.68 > 1.3). The zones are now centred
on the ring's tip edge and the foot of that edge on the pinion's flank, or left out where that foot lies
below the pinion's form circle (such a pair can touch only in the fillet).
"""

import math

import numpy as np
import pytest

from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress

from tests.support.shipped import shipped_table
from tca.contact.systems import PlacedFlank

CASE = "pipelines/cases/stress_internal_pair.toml"


def internal_case(phi1_deg, teeth=3, refine=0.5):
    return read_stress_case(shipped_table(CASE, {"position": None, "phi1_deg": phi1_deg, "mesh.teeth": teeth,
                                                 "mesh.refine": refine}))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The solved internal pair per angle, once: phi1 = 3.0 deg also gives the scene of the zone test below."""
    cache = {}

    def run(phi1_deg):
        if phi1_deg not in cache:
            cache[phi1_deg] = run_stress(internal_case(phi1_deg), tmp_path_factory.mktemp("out"))
        return cache[phi1_deg]
    return run


@pytest.mark.parametrize("phi1_deg", [-3.75, 3.0, 3.375])
def test_internal_pair_with_neighbours_solves_and_balances(runs, phi1_deg):
    s = runs(phi1_deg).summary
    shares = next(iter(s["load_share"].values()))["teeth"]
    assert sum(shares.values()) == pytest.approx(1.0, abs=1e-9)
    assert s["torque_balance_error"] < 1e-3


def test_zones_of_a_neighbour_sit_at_one_point_in_space(runs):
    """Each neighbouring pair's two zone centres are the same point of the pair frame within the zone size.

    The scene is the one meshed and solved at 3.0 deg above (build_scene of the same case; one TCA, not two)."""
    case = internal_case(3.0)
    run = runs(3.0)
    assert run.summary["position"]["remeshed"] is None  # the scene of build_scene(case), not a remesh's
    scene = run.scene
    itf = scene.interfaces[0]
    pair, c = case.pair, itf.contact
    m1, m2 = pair.mounts()
    f1, f2 = PlacedFlank(pair.gear1, pair.side1, m1), PlacedFlank(pair.gear2, pair.side2, m2)
    p1 = 2 * math.pi / pair.gear1.teeth
    assert len(itf.driver.others) == len(itf.driven.others)
    for (j1, a), (j2, b) in zip(itf.driver.others, itf.driven.others):
        k = [o.k for o in c.others if (-o.k) % pair.gear1.teeth == j1][0]
        phr = c.phi1 - k * p1
        x1, _, _ = f1.world(np.array([a.u]), np.array([a.z]), np.array([phr]))
        x2, _, _ = f2.world(np.array([b.u]), np.array([b.z]), np.array([pair.ratio * phr + c.te]))
        assert np.linalg.norm(x1.r[0] - x2.r[0]) < max(a.extent_u, 0.05)
