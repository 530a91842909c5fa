"""`gearfe stress`: the pair model, Part 1's twin models (Numerical Example 1.3), bad input, a transition.

Cases are the shipped TOML files with a few keys overridden (coarse meshes, so the file runs in
well under a minute and a half on the 2-core machine). The measured numbers quoted next to the
assertions were taken with these settings (``uptime`` load 2-4, other engineers running).
"""

import dataclasses
import json
import math
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
import pytest

from pipelines.cases.reader import CASES_DIR
from pipelines.cli import main
from pipelines.cases.stress import read_stress_case

from tests.support.shipped import shipped_data, shipped_table, write_case
from pipelines.models.stress.run import run_stress
from tca.errors import InputError
from tca.pair.analysis import run_pair_tca

ISSUE_KEYS = ("max_von_mises_mpa", "max_contact_pressure_mpa", "contact_force_n", "torque_balance_error", "dofs",
              "solve_s", "load_share")
EXTRA_KEYS = ("contact_area_mm2", "max_fillet_stress_mpa", "max_fillet_von_mises_mpa", "reaction_torque_nm",
              "expected_reaction_torque_nm", "ratio", "kinematic_ratio", "torque_balance_error_kinematic",
              "edge_contact", "fe_edge_contact", "interfaces", "focus", "rigid_motion", "position", "tca", "warnings",
              "tca_s", "mesh_s", "results_s", "total_s", "stress_recovery", "files")


def case(name: str, **over):
    return read_stress_case(shipped_table(name, over))


def shares_sum_to_one(summary):
    for name, share in summary["load_share"].items():
        assert sum(share["members"].values()) == pytest.approx(1.0, abs=1e-12), name
        assert sum(share["teeth"].values()) == pytest.approx(1.0, abs=1e-12), name


# ------------------------------------------------------------------------------------------------ pair model
@pytest.fixture(scope="module")
def pair_run(tmp_path_factory):
    """stress_pair_small as shipped (refine 0.5, 34k DOF), through the CLI."""
    out = tmp_path_factory.mktemp("pair") / "out"
    assert main(["stress", str(CASES_DIR / "stress_pair_small.toml"), "--out", str(out)]) == 0
    return out, json.loads((out / "summary.json").read_text())


def test_pair_summary_has_the_issue_keys_and_shares_sum_to_one(pair_run):
    out, s = pair_run
    for key in ISSUE_KEYS + EXTRA_KEYS:
        assert key in s, key
    assert sorted(p.name for p in out.iterdir()) == ["result.vtu", "summary.json"]
    assert s["dofs"] > 10000 and s["solve_s"] > 0
    assert set(s["load_share"]) == {"sun-planet"}
    shares_sum_to_one(s)
    # at the maximum TE the loaded pair is far from the transitions: one pair carries the load
    assert s["load_share"]["sun-planet"]["teeth"]["a/sun0-planet0"] == pytest.approx(1.0)
    assert s["position"]["next_pair_gap_um"] > 20.0  # measured 25.8 um (TCA)
    assert s["warnings"] == []
    assert not s["edge_contact"] and not s["fe_edge_contact"]


def test_pair_reaction_torque_equals_t_times_n1_over_n2(pair_run):
    _, s = pair_run
    assert s["ratio"] == pytest.approx(41 / 34, rel=1e-15)
    assert s["reaction_torque_nm"] > 0 and s["reaction_body"] == "sun"
    # issue 6: within 0.1 %; measured 2.6e-4 (nominal) and 7.2e-5 (kinematic)
    assert s["torque_balance_error"] < 1e-3
    assert s["torque_balance_error_kinematic"] < 1e-3
    # the contact transmits in the ratio of its moment arms = the instantaneous ratio N1/N2 + dTE/dphi1 of
    # the TCA (slope from a parabola through three grid values, O(h^2)); measured 5.7e-7 relative
    pos = s["position"]
    assert pos["instantaneous_ratio"] == pytest.approx(41 / 34 + pos["te_slope"], rel=1e-5)
    assert s["kinematic_ratio"] == pytest.approx(pos["instantaneous_ratio"], rel=1e-12)


def test_pair_contact_force_is_torque_over_tca_arm(pair_run):
    _, s = pair_run
    m = s["interfaces"]["sun-planet"]["members"]["a"]
    load = m["hertz_estimate"]["load_n"]  # T / |((x - o2) x n) . a2| at the TCA contact point
    # an involute helicoid's normal has the arm r_b cos(beta_b) about its axis; the double-crowned planet
    # (and the 3' misalignment) moves it by 1.9e-4 (measured): 1e-3
    planet = case("stress_pair_small").pair.gear2
    beta_b = math.atan(math.tan(math.radians(10.0)) * math.cos(planet.transverse_pressure_angle))
    assert load == pytest.approx(156e3 / (planet.r_b * math.cos(beta_b)), rel=1e-3)
    # the planet's equilibrium fixes sum(f arm) = T; the FE force spreads over the contact ellipse where
    # the arm of the crowned flank differs slightly from the TCA point's: 0.1 %. Measured 2.1e-4.
    assert s["contact_force_n"] == pytest.approx(load, rel=1e-3)
    assert m["force_n"] == s["contact_force_n"]  # bookkeeping identity, beside the closed-form arm check above


def test_pair_vtu_has_the_fields(pair_run):
    out, s = pair_run
    m = meshio.read(out / "result.vtu")
    assert 3 * len(m.points) == s["dofs"] and len(m.cells[0].data) == s["elements"]
    for name in ("displacement", "von_mises", "contact_pressure", "principal_stress", "stress", "reaction"):
        assert name in m.point_data, name
    assert m.point_data["displacement"].shape == (len(m.points), 3)
    assert float(m.point_data["von_mises"].max()) == pytest.approx(s["max_von_mises_mpa"], rel=1e-12)
    assert float(m.point_data["contact_pressure"].max()) == pytest.approx(s["max_contact_pressure_mpa"], rel=1e-12)
    assert np.count_nonzero(m.point_data["contact_pressure"] > 0) == s["fe"]["active_nodes"]


def test_pair_peak_pressure_near_hertz_at_fine_contact_mesh(tmp_path):
    """Peak contact pressure against the summary's Hertz estimate (TCA curvatures, whole load on one contact).

    Not checkable at the shipped coarse mesh: the nodal peak (force / tributary area) is +47 % at refine 0.5
    (contact size 2b/3, ~3 nodes across the ellipse's minor axis). Measured on this case (max TE):
    refine 0.5 -> 3394 MPa, 1.0 -> 2560, 1.5 -> 2199, 2.0 (515k DOF) -> 2179, against Hertz p0 = 2312 MPa:
    the converged FE peak is ~6 % below Hertz (finite tooth, not a half-space). Here the contact zone
    alone is refined to 0.06 mm x 0.7 mm (b/4 x a/6; sizes are divided by refine 0.5), one tooth per gear
    (the pair in contact carries the whole load at this position: with three teeth each the neighbours'
    shares are 0.0), 87.8k DOF: measured 2235.4 MPa = 0.967 p0 (three teeth, 129.6k DOF: 2210.1 MPa = 0.956
    p0, at the grading of issue 26's third round). Band +-10 %: the remaining mesh error and the half-space
    error (-6 %); a wrong E*, load or curvature (p0 ~ (P E*^2 / R^2)^(1/3)) leaves it.
    """
    c = case("stress_pair_small", **{"mesh.contact_size_mm": 0.03, "mesh.axial_contact_size_mm": 0.35,
                                     "mesh.teeth": 1})
    s = run_stress(c, tmp_path / "fine").summary
    hz = s["interfaces"]["sun-planet"]["members"]["a"]["hertz_estimate"]
    assert not hz["line"] and hz["p0_mpa"] == pytest.approx(2312, rel=0.01)
    assert 0.90 < s["max_contact_pressure_mpa"] / hz["p0_mpa"] < 1.10
    # the FE contact patch against the Hertz ellipse pi a b (3.17 mm^2): measured 2.88 mm^2 (2.90 with three teeth;
    # tributary areas of the active nodes: a ragged outline at 0.06 x 0.7 mm, 15 %)
    assert s["contact_area_mm2"] == pytest.approx(math.pi * hz["a_mm"] * hz["b_mm"], rel=0.15)


# ------------------------------------------------------------------------------------------------ twin models
# Full size (refine 1, three teeth) is 450k DOF and ~45 s. One tooth per part and refine 0.4 (58k DOF) keeps
# the findings; at refine 0.3 the kinematic torque balance degrades to 1.2e-3 at some positions (11 active
# nodes in all: the FE forces no longer act where the TCA contact is).
TWIN_MESH = {"mesh.refine": 0.4, "mesh.teeth": 1}


@pytest.fixture(scope="module")
def new_design(tmp_path_factory):
    return run_stress(case("stress_part1_new", **TWIN_MESH), tmp_path_factory.mktemp("new")).summary


@pytest.fixture(scope="module")
def conventional(tmp_path_factory):
    # the grading before issue 26's fourth round (growth 1.3, the layers across the tooth growing by 1.5): this coarse
    # model's kinematic torque balance is 9.73e-4 with it and 1.04e-3 with the defaults of the fourth round at refine
    # 0.3 (growth 1.5 away from the zones: 1.042e-3 alone; docs/benchmarks.md "Fourth round: the fillet target")
    c = case("stress_part1_conventional", **{"mesh.refine": 0.3, "mesh.teeth": 1, "mesh.growth": 1.3})
    c = dataclasses.replace(c, mesh=dataclasses.replace(c.mesh, section_growth=1.5, depth_growth=1.5))
    return run_stress(c, tmp_path_factory.mktemp("conv")).summary


def test_new_design_shares_the_load_between_members_without_edge_contact(new_design):
    """Report Fig. 1.9(a): both planet members carry load at the sun and at the ring; no edge contact."""
    s = new_design
    shares_sum_to_one(s)
    sun, ring = s["load_share"]["sun-planet"]["members"], s["load_share"]["planet-ring"]["members"]
    # Report Fig. 1.9(a): both members carry load at the sun and at the ring (neither share near 0 or 1).
    for shares in (sun, ring):
        assert 0.2 < shares["a"] < 0.8
    # Regression pins of this coarse model (refine 0.4, one tooth), refreshed when the contact constraints moved
    # to the Gauss points (issue 14): measured a/b 0.512/0.488 at the sun and 0.307/0.693 at the ring (0.509 and
    # 0.315 with nodal constraints). The full-size model (docs/workflows.md, 581.9k DOF, nodal constraints) gave
    # 0.511/0.489 and 0.388/0.612: the coarse ring share is 0.08 low, so it is pinned, not compared with it.
    # Sized by the loaded estimate (issue 26: member a's ring mesh gets a second zone, on the pair that takes 0.21
    # of it) the coarse ring share moved to 0.322 (measured), nearer the full size's; 0.307 with sizing = "tca".
    assert sun["a"] == pytest.approx(0.512, abs=0.005)
    assert ring["a"] == pytest.approx(0.322, abs=0.005)
    assert not s["edge_contact"] and not s["fe_edge_contact"]
    for itf in s["interfaces"].values():
        for m in itf["members"].values():
            assert m["tca_kind"] == "surface" and not m["edge_contact"]
    # the ring turns with the leading member; the other member closes its ring backlash elastically
    pos = s["position"]
    lag = "a" if pos["leading_member"] == "b" else "b"
    assert pos["members"][pos["leading_member"]]["ring_backlash_um"] == 0.0
    assert 0.0 < pos["members"][lag]["ring_backlash_um"] < 20.0  # measured 8.2 um


def test_new_design_reaction_torque_follows_the_kinematic_ratio(new_design):
    """Sun reaction against T N1/N3 (41/109): the nominal mismatch at max TE is real and explained.

    Every contact transmits torque in the ratio of its moment arms, which is its mesh's instantaneous
    ratio N_i/N_j + dTE/dphi (checked against the TCA slope below). With a rigid twin planet the sun
    reaction is T (sum_k sigma_k rho12_k) / (sum_k tau_k / rho23_k) (stress_results module docstring),
    sigma/tau the members' shares of the planet torque at the sun/ring. At the max-TE position the
    leading member is at the maximum of its TE (its rho12 rho23 = N1/N3), the other is on the flank of
    its TE (rho12 rho23 off by ~7e-3), and the sun and ring shares differ: the kinematic ratio is 2.9e-3
    above nominal. Measured here: nominal error 2.78e-3, kinematic 1.9e-4 (full size: 2.75e-3, 3.3e-4).
    """
    s = new_design
    assert s["ratio"] == pytest.approx(41 / 109, rel=1e-15)
    assert s["torque_balance_error_kinematic"] < 1e-3  # issue 6: 0.1 %
    predicted = s["kinematic_ratio"] / s["ratio"] - 1.0
    assert abs(predicted) > 2e-3  # a property of the TCA and the load shares, not FE error
    actual = s["reaction_torque_nm"] / s["expected_reaction_torque_nm"] - 1.0
    assert actual == pytest.approx(predicted, abs=1e-3)
    assert s["torque_balance_error"] == pytest.approx(abs(actual), rel=1e-12)
    pos = s["position"]
    prod = {}
    for k, m in pos["members"].items():
        # arms ratio = nominal + TCA slope (parabola through three grid values, O(h^2)): measured < 3e-6
        assert m["sun_mesh"]["instantaneous_ratio"] == pytest.approx(41 / 34 + m["sun_mesh"]["te_slope"], rel=1e-5)
        assert m["ring_mesh"]["instantaneous_ratio"] == pytest.approx(34 / 109 + m["ring_mesh"]["te_slope"], rel=1e-5)
        prod[k] = m["sun_mesh"]["instantaneous_ratio"] * m["ring_mesh"]["instantaneous_ratio"] / (41 / 109) - 1.0
    lead = pos["leading_member"]
    lag = "a" if lead == "b" else "b"
    # the leading member is at the grid maximum of its TE: within half a TCA step (0.11 deg) of the true
    # maximum, where its relative slope changes by ~1.3e-3 per degree -> |slope| <= 1.5e-4; measured 1.2e-4
    assert abs(prod[lead]) < 3e-4
    assert prod[lag] > 3e-3  # measured 7.2e-3: on the rising flank of its TE
    # sigma_k, tau_k ~ force shares (the planet's arms of the members differ by < 1e-3): sun and ring differ
    share = s["load_share"]
    assert abs(share["sun-planet"]["members"][lead] - share["planet-ring"]["members"][lead]) > 0.1


def test_conventional_design_loads_one_member_with_edge_contact(conventional):
    """Report Fig. 1.9(b): only one planet member is under load, and edge contact occurs."""
    s = conventional
    shares_sum_to_one(s)
    for name in ("sun-planet", "planet-ring"):
        m = s["load_share"][name]["members"]
        assert m["a"] == pytest.approx(1.0, abs=1e-6), name  # measured exactly 1 (b keeps a 35 um backlash)
    assert s["position"]["members"]["b"]["sun_backlash_um"] > 20.0  # measured 35.6 um
    assert s["edge_contact"] and s["fe_edge_contact"]
    assert s["interfaces"]["sun-planet"]["members"]["a"]["tca_kind"] in ("edge", "corner")
    assert s["interfaces"]["sun-planet"]["members"]["a"]["edge_contact"]
    # max TE is at a transition here (corner contact): member a's next pairs are 0.8 um off by the TCA, which
    # the summary warns about; unloaded member b (35 um backlash) gets no warning
    assert s["warnings"] and all(w.split(":")[0] in ("sun-planet a", "planet-ring a") for w in s["warnings"])
    # only member a loaded and involute meshes (TE slopes ~1e-4): the nominal ratio holds. Measured 1.9e-4.
    assert s["torque_balance_error"] < 1e-3
    assert s["torque_balance_error_kinematic"] < 1e-3


# ------------------------------------------------------------------------------------------------ bad input
BAD = [
    ({"colour": "red"}, "colour"),
    ({"torque_nm": -156.0}, "torque_nm"),
    ({"torque_nm": 0.0}, "torque_nm"),
    ({"phi1_deg": 1.0}, "phi1_deg"),  # together with position = "max_te"
    ({"position": 1.5}, "position"),
    ({"planets": 5}, "planets"),  # a planetary key in a pair case
    ({"fe.element": "C3D20"}, "fe.element"),
    ({"mesh.refine": 0.0}, "mesh.refine"),
]


@pytest.mark.parametrize("over, field", BAD)
def test_bad_input_names_the_field(over, field, tmp_path):
    with pytest.raises(InputError) as e:
        read_stress_case(shipped_table("stress_pair_small", over))
    assert e.value.field == field
    path = write_case(tmp_path, "stress_pair_small", shipped_data("stress_pair_small", over))
    out = tmp_path / "out"
    assert main(["stress", str(path), "--out", str(out)]) == 2
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == [path.name]  # no staging folder left behind


def test_position_out_of_range_fails_after_the_tca_and_writes_nothing(tmp_path):
    """21 positions (one cycle of 20 steps): indices -21..20. One run, through the command line (the library call
    run_stress(case, out) raising InputError("position", ...) was a second TCA of the same case; the one-line message
    below is that error's text, printed by the CLI's InputError handler)."""
    path = write_case(tmp_path, "stress_pair_small", shipped_data("stress_pair_small", position=21))
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-m", "pipelines.cli", "stress", str(path), "--out", str(out)],
                       capture_output=True, text=True, cwd=Path(__file__).resolve().parents[4], timeout=300)
    assert r.returncode == 2, r.stderr
    assert "position = 21 is invalid" in r.stderr and "[-21, 20]" in r.stderr
    assert not out.exists() and not any(p.name.startswith(".out.tmp") for p in tmp_path.iterdir())


def test_twin_case_rejects_pair_keys():
    with pytest.raises(InputError) as e:
        read_stress_case(shipped_table("stress_part1_new", driver="sun"))
    assert e.value.field == "driver"


# ------------------------------------------------------------------------------------------------ hard case
def test_pair_at_a_transition_shares_the_load_between_two_pairs(tmp_path):
    """At the transition both pairs touch (TCA); the FE shares the load between them.

    The other teeth's loaded flanks are meshed at ``SizeRules.neighbour`` so that the neighbouring
    pair can close (with coarse neighbours the FE gap there stayed 13 um where the TCA gap is
    0.002 um, the second pair got nothing, and the summary warned). Measured shares 0.499/0.501 at the shipped
    refine 0.5; here refine 0.3 (43k DOF; a behaviour: both pairs carry load, equilibrium; the neighbouring
    flanks keep their 0.2 mm size below refine 1): measured 0.480/0.520, torque balance errors 2.9e-4 (nominal)
    and 2.2e-4 (kinematic).
    """
    c0 = case("stress_pair_small")
    trans = run_pair_tca(c0.pair, c0.tca).transitions
    assert len(trans) == 1  # one cycle
    c = case("stress_pair_small", position=None, phi1_deg=math.degrees(float(trans[0])), **{"mesh.refine": 0.3})
    s = run_stress(c, tmp_path / "t").summary
    pos = s["position"]
    assert pos["next_pair_gap_um"] < 0.1  # two pairs in contact by the TCA (measured 0.002 um)
    shares_sum_to_one(s)
    teeth = sorted(s["load_share"]["sun-planet"]["teeth"].values())
    assert teeth[-1] == pytest.approx(0.5, abs=0.1) and teeth[-2] == pytest.approx(0.5, abs=0.1)
    assert s["warnings"] == []  # the next pair carries load: nothing to warn about
    assert all(math.isfinite(s[k]) for k in ("max_von_mises_mpa", "max_contact_pressure_mpa", "contact_force_n"))
    # the two pairs are at the two ends of their TE parabolas, slopes -5.1e-3 and about +5e-3 rad/rad: with
    # equal shares the nominal ratio holds again (measured 1.0e-5 at refine 0.5, 2.9e-4 at 0.3), and so does the
    # kinematic ratio that weights each pair's instantaneous ratio by its FE force (measured 1.1e-4 at refine 0.5,
    # 2.2e-4 at 0.3; 4.3e-3 with the TCA pair alone)
    assert abs(pos["te_slope"]) > 3e-3
    assert s["torque_balance_error"] < 1e-3
    assert s["torque_balance_error_kinematic"] < 1e-3
