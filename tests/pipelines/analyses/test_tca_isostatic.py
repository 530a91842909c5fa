"""`gearfe tca` on isostatic-train cases (kind = "isostatic"): the shipped Part 3 cases and bad input."""

import csv
import json
import math

import pytest

from pipelines.cases.reader import CASES_DIR
from pipelines.cli import main

CASES = {p.stem: p for p in sorted(CASES_DIR.glob("part3_*.toml"))}


def run_case(path, out):
    code = main(["tca", str(path), "--out", str(out)])
    return code, (json.loads((out / "summary.json").read_text()) if (out / "summary.json").exists() else None)


def edited(tmp_path, name, *subs):
    text = CASES[name].read_text()
    for a, b in subs:
        assert a in text, a
        text = text.replace(a, b)
    p = tmp_path / f"{name}.toml"
    p.write_text(text)
    return p


def test_all_part3_cases_are_shipped():
    assert set(CASES) >= {"part3_ideal", "part3_double_crowned", "part3_indexing", "part3_carrier_center",
                          "part3_sun_runout", "part3_planet_runout"}


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    out = {}
    for name, path in CASES.items():
        d = tmp_path_factory.mktemp(name)
        code, s = run_case(path, d)
        assert code == 0
        out[name] = (s, d)
    return out


def test_shipped_cases_give_the_report_numbers(results):
    # the acceptance numbers of issue 4 at the cases' own resolution (720 positions); tolerances as in
    # tests/tca/isostatic/test_analysis.py
    s = {k: v[0] for k, v in results.items()}
    for k in s:
        assert s[k]["dof"]["state"] == "isostatic" and s[k]["dof"]["isostatic_planets"] == 3
        assert s[k]["all_planets_in_contact"] is True
        assert s[k]["positions"] == 720
    assert s["part3_ideal"]["carrier_te_peak_to_peak_arcsec"] < 0.01
    assert s["part3_ideal"]["sun_center_max_um"] < 0.01
    assert 1.5 < s["part3_double_crowned"]["carrier_lag_mean_arcsec"] < 2.5
    assert s["part3_indexing"]["sun_center_radius_um"] == pytest.approx(25.0, abs=1.0)
    assert s["part3_indexing"]["carrier_lag_mean_arcsec"] == pytest.approx(6.38, abs=0.2)
    assert s["part3_indexing"]["closed_form_section_3_4_2"]["carrier_lag_increase_arcsec"] == pytest.approx(
        s["part3_indexing"]["carrier_lag_mean_arcsec"], abs=0.01)
    assert s["part3_carrier_center"]["carrier_te_peak_to_peak_arcsec"] < 0.05
    assert s["part3_sun_runout"]["sun_center_radius_um"] == pytest.approx(20.0, abs=0.01)
    assert s["part3_sun_runout"]["carrier_te_peak_to_peak_arcsec"] < 0.05
    assert s["part3_planet_runout"]["te_period_sun_rev"] == pytest.approx(0.9463, abs=1e-3)
    # the first-order closed form travels with every summary (involute: equal to second order)
    for k in ("part3_indexing", "part3_carrier_center", "part3_sun_runout", "part3_planet_runout"):
        assert s[k]["closed_form_first_order"]["carrier_te_peak_to_peak_arcsec"] == pytest.approx(
            s[k]["carrier_te_peak_to_peak_arcsec"], abs=0.03)


def test_result_files(results):
    s, d = results["part3_indexing"]
    assert sorted(p.name for p in d.iterdir()) == sorted(s["files"])
    rows = list(csv.DictReader(open(d / "tca.csv")))
    assert len(rows) == 720
    assert math.hypot(float(rows[0]["sun_x_um"]), float(rows[0]["sun_y_um"])) == pytest.approx(25.06, abs=0.05)
    assert {f"p{i}_sun_tooth" for i in (1, 2, 3)} <= set(rows[0])
    for png in ("sun_center.png", "carrier_te.png"):
        assert (d / png).stat().st_size > 10000


def test_short_run_with_double_crowned_planets_and_direct_solver(tmp_path):
    p = edited(tmp_path, "part3_indexing", ('planets = "involute"', 'planets = "double_crowned"'),
               ("positions = 720", "positions = 12"), ("carrier_revolutions = 1.0", "carrier_revolutions = 0.01"))
    p.write_text(p.read_text() + '\n[solver]\nmethod = "direct"\n')
    code, s = run_case(p, tmp_path / "out")
    assert code == 0
    assert s["positions"] == 12 and s["method"] == "direct" and s["planets_variant"] == "double_crowned"
    assert 7.0 < s["carrier_lag_mean_arcsec"] < 9.5  # about 8.2 arcsec (report 3.4.2), sampled over 1/100 turn


@pytest.mark.parametrize("subs,match", [
    ((("planets = 3", "planets = 2"),), "under-constrained"),
    ((("planets = 3", "planets = 4"),), "hyperstatic"),
    ((("planets = 3", "planets = 5"),), "assembly"),
    ((('planets = "involute"', 'planets = "crowned"'),), "planets"),
    ((("positions = 720", "positions = 720\nstep_deg = 1.0"),), "run.step_deg"),
    ((("tangential_um = 20.0", "tangential_um = 2000.0"),), "tangential_um"),
    ((("planet = 1", "planet = 4"),), "planet_errors"),
    ((("teeth = 43", "teeth = 43\nparabola_drive_per_mm = 1e-3"),), "gears.planet"),
])
def test_bad_cases_exit_2_without_files(tmp_path, capsys, subs, match):
    p = edited(tmp_path, "part3_indexing", *subs)
    out = tmp_path / "out"
    code = main(["tca", str(p), "--out", str(out)])
    assert code == 2
    assert match in capsys.readouterr().err
    assert not out.exists() or not any(out.iterdir())


def test_double_crowned_needs_a_crowning_table(tmp_path, capsys):
    text = CASES["part3_double_crowned"].read_text()
    text = text[: text.index("\n[crowning]")]
    p = tmp_path / "c.toml"
    p.write_text(text)
    assert main(["tca", str(p), "--out", str(tmp_path / "o")]) == 2
    assert "crowning" in capsys.readouterr().err


def test_fixed_sun_with_three_planets_runs_as_a_rigid_hyperstatic_train(tmp_path):
    # case 1 constraints with three planets (N_f - N_c = -2): the carrier follows the first planet to touch and
    # planet 1, advanced by its 20 um indexing error, keeps the loop backlash 2 dE_t cos(a) = 37.6 um
    p = edited(tmp_path, "part3_indexing", ('sun_axis = "floating"', 'sun_axis = "fixed"'),
               ("positions = 720", "positions = 24"))
    code, s = run_case(p, tmp_path / "out")
    assert code == 0
    assert s["dof"]["state"] == "hyperstatic" and s["rigid_hyperstatic"] is True
    assert s["all_planets_in_contact"] is False
    assert s["planet_backlash_max_um"][0] == pytest.approx(2 * 20 * math.cos(math.radians(20)), abs=0.05)
    assert s["sun_center_max_um"] == 0.0
