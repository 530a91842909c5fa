"""The ISO 6336 rating of a Part 1 train with the K_gamma of its loaded TCA (issue 25 item 2, issue 22): gearfe ltca
of a planetary case with [rating] rates every member both ways: K_gamma taken as 1 (ISO alone) beside the train's."""

import json
import math

import pytest

from pipelines.cli import main
from tests.support.shipped import shipped_table, write_case

GEAR = {"material": "Eh", "quality": "MQ", "hardness": 700.0}
GEARS = {"sun": dict(GEAR), "planet": {**GEAR, "mean_stress_factor": 0.7},
         "ring": {"material": "V (alloy)", "quality": "MQ", "hardness": 300.0, "yield_strength_mpa": 700.0,
                  "brinell_hardness": 290.0}}
RATING = {"driver_speed_rpm": 1500.0, "life_hours": 20000.0, "viscosity_40_mm2s": 220.0, "accuracy_grade": 6,
          "gears": GEARS}
LTCA = {"profile_size_mm": 2.0, "axial_size_mm": 8.0, "slice_mm": 4.0, "positions_per_cycle": 1,
        "carrier_revolutions": 3.0 / 109, "torques_nm": [400.0], "regulation": "none"}


def test_ltca_of_a_part1_train_rates_it_with_its_k_gamma(tmp_path):
    case = write_case(tmp_path, "train", shipped_table("part1_twin_dgamma", {"ltca": LTCA, "rating": RATING}).data)
    out = tmp_path / "out"
    assert main(["ltca", str(case), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    r = s["rating"]
    kg = s["k_gamma_members"]
    assert kg > 1.0
    assert set(r["meshes"]) == {"sun-planet", "planet-ring"}
    for m in r["meshes"].values():
        for name, g in m["gears"].items():
            assert g["factors"]["K_gamma"]["value"] == 1.0 and "taken as 1" in g["factors"]["K_gamma"]["note"]
            h = m["gearfe"]["gears"][name]
            assert h["factors"]["K_gamma"] == {"value": pytest.approx(kg, rel=1e-12), "source": "gearfe",
                                               "note": h["factors"]["K_gamma"]["note"]}
            # the nominal stresses do not change; the load factors do: K_gamma enters the line load, so K_v and
            # K_Hbeta of ISO change with it and sigma_H grows by less than sqrt(K_gamma), sigma_F by less than K_gamma
            assert h["sigma_h0_mpa"] == pytest.approx(g["sigma_h0_mpa"], rel=1e-12)
            assert g["sigma_h_mpa"] < h["sigma_h_mpa"] <= g["sigma_h_mpa"] * math.sqrt(kg) * (1 + 1e-9)
            assert g["sigma_f_mpa"] < h["sigma_f_mpa"] <= g["sigma_f_mpa"] * kg * (1 + 1e-9)
            assert h["safety_contact"] < g["safety_contact"] and h["safety_bending"] < g["safety_bending"]
    # the ring torque of the run: T3 = T1 N3/N1 with the carrier at rest; per member and planet T3 / (2 n)
    n = s["planets"]
    sun, planet, ring = s["teeth"]
    assert r["meshes"]["planet-ring"]["pair"]["pinion_torque_nm"] == pytest.approx(
        400.0 * ring / sun / (2 * n) * planet / ring, rel=1e-9)
    assert "K_gamma" in " ".join(r["compared"])
