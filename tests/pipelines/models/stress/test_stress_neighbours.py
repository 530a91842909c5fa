"""Load sharing by neighbouring tooth pairs near a change of the pair in contact (issues 6 and 7).

Near a transition the next pair's unloaded gap (TCA) is smaller than the elastic approach, so it
takes part of the load. A coarse faceted flank lies inside the curved one by h^2/(8 rho) — about
0.1 mm at 3 mm elements, more than the approach — and would never touch: the other teeth's loaded
flanks are meshed at ``SizeRules.neighbour`` (default 0.1 m = 0.2 mm here; divided by refine when refine > 1).

Measured on stress_pair_small (refine 0.5, T = 156 N m on the planet) at phi1 = -5.71 deg (next pair
5.2 arcsec behind in the TCA), share of the next pair vs its effective profile size:
3 mm (coarse) 0.0, 1.2 mm 0.06, 0.8 mm 0.18, 0.5 mm 0.40, 0.3 mm 0.499, 0.2 mm (default) 0.532,
0.1 mm 0.545, and 0.545 again with every size halved (refine 1, 183k DOF).
"""

from pathlib import Path

import pytest

from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import build_scene, run_stress

from tests.support.shipped import shipped_table

CASE = Path(__file__).resolve().parents[4] / "pipelines" / "cases" / "stress_pair_small.toml"


def case_at(phi1_deg, **mesh):
    return read_stress_case(shipped_table(CASE, {"position": None, "phi1_deg": phi1_deg,
                                                 **{f"mesh.{k}": v for k, v in mesh.items()}}))


def next_pair_share(summary):
    teeth = summary["load_share"]["sun-planet"]["teeth"]
    return teeth["a/sun1-planet1"], teeth["a/sun0-planet0"], sum(teeth.values())


def test_neighbouring_pair_shares_the_load_near_a_transition(tmp_path):
    s = run_stress(case_at(-5.71), tmp_path / "default").summary
    nxt, cur, tot = next_pair_share(s)
    assert tot == pytest.approx(1.0, abs=1e-9)
    # converged value 0.545 (finest meshes above); the default keeps it within 0.05
    assert nxt == pytest.approx(0.545, abs=0.05)
    assert s["torque_balance_error"] < 1e-3


def test_coarse_neighbours_miss_the_sharing(tmp_path):
    """The reason for the neighbour size: with coarse neighbouring flanks the next pair stays open
    (zones from the unloaded TCA, ``sizing = "tca"``, with neighbour foci turned off: ``neighbour_reach_um = 0``)."""
    # refine 0.3 (the others here: the shipped 0.5): a behaviour, not a value; the neighbour size is 3 mm either way.
    # Measured at refine 0.3: next pair 0.0, current 1.0 (15.6k DOF), as at 0.5.
    s = run_stress(case_at(-5.71, neighbour_size_mm=3.0, neighbour_reach_um=0.0, sizing="tca", refine=0.3),
                   tmp_path / "coarse").summary
    nxt, cur, _ = next_pair_share(s)
    assert nxt < 0.01 and cur > 0.99
    assert s["position"]["refined_neighbours"] == []


def test_a_pair_within_reach_gets_its_own_zone():
    """The next pair (5.2 arcsec behind) gets its own refined zone — the loaded estimate loads it (the default
    ``sizing = "loaded"``; with ``"tca"`` it is within the default reach of the unloaded TCA) — even with coarse
    neighbouring flanks elsewhere (3 mm). The scene alone (TCA and loaded estimate: no mesh, no solve); that the FE
    then shares the load as the finest meshes do is the study below, in make bench."""
    scene, _ = build_scene(case_at(-5.71, neighbour_size_mm=3.0))
    assert [n["pair"] for n in scene.info["refined_neighbours"]][:1] == [[1, 1]]


@pytest.mark.bench
def test_a_pair_within_reach_is_meshed_like_the_loaded_one(tmp_path):
    """A comparison of mesh options (3 mm neighbouring flanks with the next pair's own zone against the converged
    0.545 of the module docstring), moved to make bench: with its zone the next pair shares the load as the finest
    meshes do. Its zone is checked in make test by :func:`test_a_pair_within_reach_gets_its_own_zone`."""
    s = run_stress(case_at(-5.71, neighbour_size_mm=3.0), tmp_path / "focus").summary
    nxt, cur, _ = next_pair_share(s)
    assert [n["pair"] for n in s["position"]["refined_neighbours"]][:1] == [[1, 1]]
    assert nxt == pytest.approx(0.545, abs=0.05)


def test_one_pair_carries_the_load_mid_cycle(tmp_path):
    """At the maximum of the TE (mid-cycle) the neighbouring pairs' gaps exceed the approach.

    Refine 0.3 (27k DOF; 50k at the shipped 0.5): the neighbouring flanks keep their 0.2 mm size (divided by refine
    only when refine > 1), so they could close if their gaps allowed; measured share of the current pair 1.0 at both."""
    s = run_stress(case_at(-1.3171, refine=0.3), tmp_path / "mid").summary
    nxt, cur, _ = next_pair_share(s)
    assert cur > 0.999
