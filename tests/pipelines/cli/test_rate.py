"""``gearfe rate``: the ISO 6336 rating of a case's gears from its [rating] table (pipelines/cases/rating.py,
pipelines/cli/rate.py); the summary's ``rating`` key; bad input refused in one line with exit 2 and no files;
cases outside ISO's assumptions rated with a warning."""

import json
import time

import pytest

from pipelines.cli import main
from pipelines.cases.kinds import read_case
from tca.rating import iso_material, rate
from tca.rating.from_gears import GearSpec, Load, Service, rating_case

from tests.support.shipped import shipped_data, write_case

GEAR = {"material": "Eh", "quality": "MQ", "hardness": 700.0}
RATING = {"driver_speed_rpm": 1500.0, "life_hours": 20000.0, "viscosity_40_mm2s": 220.0, "application_factor": 1.25,
          "accuracy_grade": 6, "gears": {"pinion": dict(GEAR), "wheel": dict(GEAR)}}
PER_GEAR = ("sigma_h0_mpa", "sigma_h_mpa", "sigma_f0_mpa", "sigma_f_mpa", "safety_contact", "safety_bending", "factors")


def spur_case(tmp_path, **over):
    d = shipped_data("stress_spur_pair", {"rating": RATING, **over})
    return write_case(tmp_path, "spur", d)


def test_rate_writes_the_rating_in_seconds(tmp_path, capsys):
    path = spur_case(tmp_path)
    t0 = time.perf_counter()
    assert main(["rate", str(path), "--out", str(tmp_path / "out")]) == 0
    dt = time.perf_counter() - t0
    assert dt < 10.0  # measured 0.1-0.2 s after the imports
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    r = s["rating"]
    assert set(r["gears"]) == {"pinion", "wheel"}
    for g in r["gears"].values():
        assert set(PER_GEAR) <= set(g)
        for f in g["factors"].values():
            assert set(f) == {"value", "source", "note"} and f["source"] in ("iso", "input", "gearfe")
    p = r["gears"]["pinion"]
    assert p["factors"]["Y_F"]["source"] == "gearfe" and p["factors"]["K_v"]["source"] == "iso"
    assert p["factors"]["K_A"] == {"value": 1.25, "source": "input", "note": p["factors"]["K_A"]["note"]}
    assert any("Z_X" in x for x in r["simplified"]) and any("K_gamma" in x for x in r["simplified"])
    # the same numbers as the library on the same gears (the case's torque is on the wheel)
    _, job = read_case(path, "rate")
    pair = job.meshes[0].pair
    lib = rate(rating_case(pair, {n: GearSpec(iso_material("Eh", "MQ", 700.0, youngs_modulus=2.068e5, poisson=0.29), 6)
                                  for n in ("pinion", "wheel")},
                           Service(1500.0, application_factor=1.25, viscosity_40=220.0, life_hours=20000.0),
                           Load(120e3)).case)
    assert p["safety_contact"] == pytest.approx(lib.pinion.s_h, rel=1e-12)
    assert r["gears"]["wheel"]["safety_bending"] == pytest.approx(lib.wheel.s_f, rel=1e-12)
    assert (tmp_path / "out" / "rating.md").read_text().startswith("# ISO 6336 rating")
    assert "S_H" in capsys.readouterr().out


@pytest.mark.parametrize("key, value, named", [
    ("rating.gears.pinion.material", "Unobtainium", "rating.gears.pinion.material"),
    ("rating.gears.wheel.quality", "MX", "rating.gears.wheel.quality"),
    ("rating.gears.wheel.hardness", 400.0, "hardness"),
    ("rating.driver_speed_rpm", 0.0, "rating.driver_speed_rpm"),
    ("rating.driver_speed_rpm", -100.0, "rating.driver_speed_rpm"),
    ("rating.life_hours", 0.0, "rating.life_hours"),
    ("rating.application_factor", 0.9, "rating.application_factor"),
    ("rating.k_gamma", 0.95, "rating.k_gamma"),
    ("rating.k_h_beta", 12.0, "rating.k_h_beta"),
    ("rating.accuracy_grade", 13, "rating.accuracy_grade"),
    ("rating.gears.pinion.flank_rz_um", 80.0, "rating.gears.pinion.flank_rz_um"),
    ("rating.gears.pinion.colour", "red", "rating.gears.pinion.colour"),
    ("rating.gears.gear3", dict(GEAR), "rating.gears.gear3"),
    ("rating.driven_torque_nm", 100.0, "rating.driven_torque_nm"),  # the stress case has its own torque
])
def test_bad_rating_input_exits_2_in_one_line_without_files(tmp_path, capsys, key, value, named):
    d = shipped_data("stress_spur_pair", {"rating": RATING})
    d = shipped_data(str(write_case(tmp_path, "base", d)), {key: value})
    path = write_case(tmp_path, "bad", d)
    out = tmp_path / "out"
    for cmd in ("rate", "stress"):
        assert main([cmd, str(path), "--out", str(out)]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and named in err, err
        assert not out.exists()


def test_missing_gear_table_and_missing_rating(tmp_path, capsys):
    d = shipped_data("stress_spur_pair", {"rating": {**RATING, "gears": {"pinion": dict(GEAR)}}})
    assert main(["rate", str(write_case(tmp_path, "a", d)), "--out", str(tmp_path / "o")]) == 2
    assert "rating.gears.wheel" in capsys.readouterr().err
    d = shipped_data("stress_spur_pair")
    assert main(["rate", str(write_case(tmp_path, "b", d)), "--out", str(tmp_path / "o")]) == 2
    assert "rating" in capsys.readouterr().err and not (tmp_path / "o").exists()


def test_outside_iso_assumptions_rated_with_a_warning(tmp_path):
    short = {"addendum": 0.55, "tool_addendum": 0.85}  # ε_α = 0.94 < 1
    d = shipped_data("stress_spur_pair", {"rating": RATING, **{f"gears.{g}.{k}": v for g in ("pinion", "wheel")
                                                               for k, v in short.items()}})
    assert main(["rate", str(write_case(tmp_path, "short", d)), "--out", str(tmp_path / "o")]) == 0
    w = json.loads((tmp_path / "o" / "summary.json").read_text())["rating"]["warnings"]
    assert any(x.startswith("eps_alpha_below_1") for x in w) and any(x.startswith("root_load_point") for x in w)


def test_a_pair_case_gives_its_torque_in_rating_and_tca_still_reads_it(tmp_path):
    rating = {**RATING, "driven_torque_nm": 156.0, "gears": {"sun": dict(GEAR), "planet": dict(GEAR)}}
    d = shipped_data("part1_sun_planet", {"rating": rating})
    path = write_case(tmp_path, "pair", d)
    assert main(["rate", str(path), "--out", str(tmp_path / "o")]) == 0
    r = json.loads((tmp_path / "o" / "summary.json").read_text())["rating"]
    assert r["gears"]["planet"]["role"] == "pinion"  # 34 teeth against the sun's 41
    assert any(w.startswith("profile_crowned") for w in r["warnings"])
    assert r["meshes"]["pair"]["pair"]["pinion_torque_nm"] == pytest.approx(156.0, rel=1e-12)
    from pipelines.cases.kinds import validate_case
    from pipelines.cases.reader import load_case

    assert validate_case(load_case(path), "tca").name == "pair"
    d = shipped_data("part1_sun_planet", {"rating": RATING | {"gears": rating["gears"]}})
    assert main(["rate", str(write_case(tmp_path, "notorque", d)), "--out", str(tmp_path / "o2")]) == 2


def test_a_planetary_train_rates_both_meshes(tmp_path):
    gears = {"sun": dict(GEAR), "planet": {**GEAR, "mean_stress_factor": 0.7},
             "ring": {"material": "V (alloy)", "quality": "MQ", "hardness": 300.0, "yield_strength_mpa": 700.0,
                      "brinell_hardness": 290.0}}
    rating = {**RATING, "driven_torque_nm": 2000.0, "k_gamma": 1.1, "gears": gears}
    d = shipped_data("part1_planetary_regulation", {"rating": rating})
    assert main(["rate", str(write_case(tmp_path, "train", d)), "--out", str(tmp_path / "o")]) == 0
    r = json.loads((tmp_path / "o" / "summary.json").read_text())["rating"]
    assert set(r["meshes"]) == {"sun-planet", "planet-ring"}
    assert set(r["gears"]) == {"sun", "planet", "ring"}
    assert r["gears"]["ring"]["role"] == "wheel" and r["gears"]["ring"]["mesh"] == "planet-ring"
    for m in r["meshes"].values():
        for g in m["gears"].values():
            assert g["factors"]["K_gamma"] == {"value": 1.1, "source": "input", "note": g["factors"]["K_gamma"]["note"]}
    # per member and planet: the ring's torque / (2 n) on the ring
    assert r["meshes"]["planet-ring"]["pair"]["pinion_torque_nm"] == pytest.approx(2000.0 / 10 * 34 / 109, rel=1e-9)


def test_a_twin_stress_case_rates_member_meshes(tmp_path):
    """Part 1's twin drive (stress_part1_new.toml): the ring's torque of the case, per member and planet."""
    gears = {"sun": dict(GEAR), "planet": {**GEAR, "mean_stress_factor": 0.7},
             "ring": {"material": "V (alloy)", "quality": "MQ", "hardness": 300.0, "yield_strength_mpa": 700.0,
                      "brinell_hardness": 290.0}}
    d = shipped_data("stress_part1_new", {"rating": {**RATING, "gears": gears}})
    assert main(["rate", str(write_case(tmp_path, "twin", d)), "--out", str(tmp_path / "o")]) == 0
    r = json.loads((tmp_path / "o" / "summary.json").read_text())["rating"]
    torque = d["torque_nm"]
    n = d["planets"]
    assert r["meshes"]["planet-ring"]["pair"]["pinion_torque_nm"] == pytest.approx(torque / (2 * n) * 34 / 109, rel=1e-9)
    assert r["gears"]["planet"]["factors"]["Y_M"]["value"] == 0.7
