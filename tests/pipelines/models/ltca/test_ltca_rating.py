"""``gearfe ltca`` with a [rating]: the pair rated with ISO's factors and with K_Hβ, K_Hα of its loaded TCA
(pipelines/analyses/rating.py, tca/rating/analysis.py), each printed beside ISO's.

The aligned, unmodified spur pair 19/24 of stress_spur_pair.toml on a coarse flank grid (8 positions, 1 x 2 mm): its load per
unit face width is nearly uniform, K_Hβ(gearfe) = 1.028 measured (12 positions, grid 0.6 x 1 mm) (ISO's method C gives 1.18: it adds the helix
deviations of grade 6 that the ideal gears do not have); its single-contact load governs the transverse sharing,
K_Hα(gearfe) = 1 (ISO: 1). The given K_γ stays the user's in both ratings."""

import json

import pytest

from pipelines.cli import main

from tests.support.shipped import shipped_data, write_case

GEAR = {"material": "Eh", "quality": "MQ", "hardness": 700.0}


def test_ltca_rates_the_pair_both_ways(tmp_path, capsys):
    d = shipped_data("stress_spur_pair", {
        "position": None, "tca": {"cycles": 1, "steps_per_cycle": 20},
        "ltca": {"positions": 8, "profile_size_mm": 1.0, "axial_size_mm": 2.0},
        "rating": {"driver_speed_rpm": 1500.0, "life_hours": 20000.0, "viscosity_40_mm2s": 220.0, "accuracy_grade": 6,
                   "k_gamma": 1.1, "gears": {"pinion": dict(GEAR), "wheel": dict(GEAR)}}})
    out = tmp_path / "out"
    assert main(["ltca", str(write_case(tmp_path, "spur", d)), "--out", str(out)]) == 0
    r = json.loads((out / "summary.json").read_text())["rating"]
    assert set(r["compared"]) == {"K_Hbeta", "K_Halpha"}
    kb = r["compared"]["K_Hbeta"]
    assert 1.0 <= kb["gearfe"] < 1.06 and kb["iso"] > kb["gearfe"]
    assert r["compared"]["K_Halpha"]["gearfe"] == pytest.approx(1.0, abs=1e-6)
    g = r["gearfe"]["gears"]["pinion"]["factors"]
    assert g["K_Hbeta"]["source"] == "gearfe" and g["K_Halpha"]["source"] == "gearfe"
    assert g["K_gamma"] == {"value": 1.1, "source": "input", "note": g["K_gamma"]["note"]}
    assert r["gears"]["pinion"]["factors"]["K_Hbeta"]["source"] == "iso"
    # lower K_Hβ: higher safeties with gearfe's factors
    assert r["gearfe"]["gears"]["pinion"]["safety_contact"] > r["gears"]["pinion"]["safety_contact"]
    text = capsys.readouterr().out
    assert "K_Hbeta: ISO" in text and "gearfe" in text
