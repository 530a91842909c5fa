"""Headline numbers that mean what they say (pipelines/models/stress/headline.py), FE against ISO 6336.

Aligned spur pair of pipelines/cases/stress_spur_pair.toml (19/24, m 4.5 mm, b 14 mm, T2 = 120 N m), one tooth per
gear where ISO's assumption (one pair carries the whole load) is the model's:

* root: the FE's largest principal stress at ISO 6336-3's critical section (the 30° tangent of the loaded tooth's
  tension fillet) against σ_F0 at each gear's HPSTC (the pinion's at "hpstc", the wheel's at "lpstc"); target 10 %,
  measured -0.1 % (pinion, contact size 0.2 mm) and +0.4 % (wheel, refine 1) on this machine;
* contact: the smooth peak of the loaded pair at the pinion's inner point of single contact ("lpstc") against ISO
  6336-2's σ_H0·Z_B/Z_ε (σ_H0 with the FE's E, ν; Z_ε, ISO's allowance for sharing, reported beside); target 5 %,
  measured +2.6 % (921.1 against 897.8 MPa, refine 1, 78k DOF, 14 s);
* three teeth at the HPSTC (refine 0.3): the entering pair touches with the wheel's tip edge; its peak is flagged
  with its location and pair, apart from the loaded pair's smooth peak (the headline ``contact_peak_mpa``).

The internal ring's critical section is checked on the model of test_internal_root.py (one solve for both).

The crowned helical pair of issue 25 (pipelines/cases/stress_helical_crowned.toml) runs in ``make bench``
(``test_helical_loaded_tooth_is_stable_and_the_tip_bearing_peak_apart``): refine 0.5 and 1 need 5 and 8 GB.
"""

import math
from dataclasses import replace
from pathlib import Path

import pytest

from tca.errors import InputError

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress
from tca.pair.te import path_of_contact
from tca.rating.root_stress import root_factors


def spur(position: str, teeth: int = 1, **mesh):
    c = read_stress_case(load_case(CASES_DIR / "stress_spur_pair.toml"))
    return replace(c, position=position, mesh=replace(c.mesh, teeth=teeth, **mesh))


def sigma_f0(c, gear, torque):
    rf = root_factors(gear, path_of_contact(c.pair).contact_ratio)
    return torque / gear.r_p / (gear.face_width * gear.module) * rf.y_f * rf.y_s


def test_loaded_tooth_at_the_30_degree_section_against_sigma_f0_at_the_hpstc(tmp_path):
    """Also the pinion's fillet maximum principal stress of the result (``fillet_stress``) against σ_F0 (10 %;
    measured 121.4 against 117.7 MPa, +3.2 %): this is the model of test_standard_gears' former
    ``test_pinion_root_stress_at_the_hpstc_against_iso_6336_3``, solved once for both."""
    c = spur("hpstc", contact=0.2)  # the root stress does not need the Hertz band resolved (b = 0.125 mm)
    run = run_stress(c, tmp_path)
    s = run.summary
    g1 = c.pair.gear1
    sig = sigma_f0(c, g1, c.torque * g1.teeth / c.pair.gear2.teeth)
    rs = s["root_stress"]["pinion"]
    assert s["iso6336_sigma_f0_mpa"]["pinion"] == pytest.approx(sig, rel=1e-9)
    fe = run.result.fillet_stress()["pinion/tooth0/fillet_pos"]["max_principal_mpa"]
    assert fe == pytest.approx(sig, rel=0.10)
    assert rs["tooth"] == 0 and rs["load_share"] == pytest.approx(1.0)
    assert rs["critical_section_mpa"] == pytest.approx(sig, rel=0.10)
    # the critical section lies on the fillet, below its maximum, between the root and the base circle
    assert rs["critical_section_mpa"] <= rs["fillet_max_mpa"] <= 1.05 * rs["critical_section_mpa"]
    assert g1.r_root < math.hypot(*rs["critical_section_point_mm"][:2]) < g1.r_b


def test_peak_pressure_at_the_pinions_inner_point_of_single_contact(tmp_path):
    c = spur("lpstc")
    s = run_stress(c, tmp_path).summary
    iso = s["iso6336"]["contact"]
    assert iso["z_eps"] < 1.0  # ISO's allowance for sharing, reported beside
    loaded = next(p for p in s["contact_peaks"] if p["force_n"] > 0)
    assert not loaded["edge_flagged"]
    assert loaded["smooth_peak_mpa"] == pytest.approx(iso["at_inner_point_pinion"], rel=0.05)
    assert s["contact_peak_mpa"] == loaded["smooth_peak_mpa"]
    # the wheel's HPSTC is the driver's LPSTC: its loaded tooth against its σ_F0
    g2 = c.pair.gear2
    assert s["root_stress"]["wheel"]["critical_section_mpa"] == pytest.approx(sigma_f0(c, g2, c.torque), rel=0.10)


def test_entering_pair_tip_edge_is_flagged_apart_from_the_loaded_pair(tmp_path):
    """A behaviour (the flag, its location and pair, the headline apart from it), not a value: refine 0.3 (23k DOF;
    was 0.5). Measured at 0.3: one edge peak ("corner", the wheel's, pair pinion18-wheel23) of 1850 MPa, the loaded
    pair's smooth peak 717 MPa, the pinion's loaded tooth share 0.59."""
    c = spur("hpstc", teeth=3, refine=0.3)
    s = run_stress(c, tmp_path).summary
    edges = s["edge_peaks"]
    assert len(edges) == 1
    e = edges[0]
    assert e["edge_kind"] in ("tip edge", "corner") and e["edge_of"] == "wheel"
    assert e["pair"].endswith("pinion18-wheel23") and len(e["edge_point_mm"]) == 3
    assert s["max_contact_pressure_mpa"] == pytest.approx(e["edge_peak_mpa"])  # the raw maximum is that edge
    loaded = next(p for p in s["contact_peaks"] if p["pair"].endswith("pinion0-wheel0"))
    assert s["contact_peak_mpa"] == pytest.approx(loaded["smooth_peak_mpa"])
    assert 0 < s["contact_peak_mpa"] < e["edge_peak_mpa"]
    # both loaded teeth of the pinion's loaded pair and the wheel's entering tooth are in root_stress with their shares
    assert 0.5 < s["root_stress"]["pinion"]["load_share"] < 0.7
    shares = {t["tooth"]: t["load_share"] for t in s["root_stress"]["wheel"]["teeth"]}
    assert sum(shares.values()) == pytest.approx(1.0, abs=1e-9)
    assert s["max_fillet_stress_mpa"] <= s["max_fillet_stress_raw_mpa"]


@pytest.mark.bench
@pytest.mark.xfail(strict=True, raises=InputError, reason=(
    "refused before meshing at refine 1: estimated 1,779,525 DOF, 37.9 GB, above the 16 GB this test allows (the "
    "refine-0.5 model: 296,058 DOF, 4.3 GB). The estimate was 33.6 GB already at 6ccfe27; the docstring's 15 GB is "
    "from an earlier commit, not bisected; docs/benchmarks.md 'Fifth round'"))
def test_helical_loaded_tooth_is_stable_and_the_tip_bearing_peak_apart(tmp_path, monkeypatch):
    """Issue 25's crowned helical pair at the pitch point, refine 0.5 and 1 (5.1 and 7.8 GB peak; the estimates,
    9.6 and 15 GB, exceed a 10 GB limit: this test allows 16 GB). Measured on this machine: the pinion's loaded
    tooth at the 30° section 278.9 and 287.6 MPa (+3.1 %), its fillet maximum 301.8 and 314.2 MPa (+4.1 %); the
    wheel's tip edge bearing on the entering pinion tooth 6038 and 7797 MPa, flagged apart."""
    monkeypatch.setenv("GEARFE_MAX_MEMORY_GB", "16")
    base = read_stress_case(load_case(CASES_DIR / "stress_helical_crowned.toml"))
    out = {}
    for refine in (0.5, 1.0):
        out[refine] = run_stress(replace(base, mesh=replace(base.mesh, refine=refine)), Path(tmp_path) / f"r{refine}").summary
    a, b = (out[r]["root_stress"]["pinion"] for r in (0.5, 1.0))
    assert a["critical_section_mpa"] == pytest.approx(b["critical_section_mpa"], rel=0.05)
    assert a["fillet_max_mpa"] == pytest.approx(b["fillet_max_mpa"], rel=0.05)
    for s in out.values():
        e = s["edge_peaks"]
        assert e and e[0]["edge_kind"] in ("tip edge", "corner") and e[0]["edge_of"] == "wheel"
        assert s["max_fillet_stress_mpa"] < e[0]["edge_peak_mpa"]
        assert s["contact_peak_mpa"] < e[0]["edge_peak_mpa"]
