"""`gearfe tca` on planetary cases (kind = "planetary"): end to end on a fast variant, and bad input."""

import json
import re
from pathlib import Path

import pytest

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cli import main
from pipelines.cases.planetary import read_installment, read_train

REG = CASES_DIR / "part1_planetary_regulation.toml"
DGAMMA = CASES_DIR / "part1_twin_dgamma.toml"


def variant(tmp_path: Path, src: Path, section: str = "", **subs) -> Path:
    """A copy of a shipped case with `key = value` lines replaced (first occurrence after `[section]`)."""
    text = src.read_text()
    start = text.index(f"[{section}]") if section else 0
    head, text = text[:start], text[start:]
    for key, value in subs.items():
        text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, count=1, flags=re.M)
        assert n == 1, key
    text = head + text
    p = tmp_path / f"{src.stem}_variant.toml"
    p.write_text(text)
    return p


def test_shipped_cases_hold_the_report_data():
    # Table 1.1 train and the Table 1.2 installment errors / Example 1.2's 3 arcmin, read without running TCA
    for path, dex, dg in ((REG, [0, 20, -20, 5, -5], [0] * 5), (DGAMMA, [0] * 5, [3, 0, 0, 0, 0])):
        case = load_case(path)
        assert case.get("kind", str) == "planetary"
        train = read_train(case)
        assert (train.sun.teeth, train.planet.teeth, train.ring.teeth, train.planets) == (41, 34, 109, 5)
        assert [round(x, 6) for x in (train.sun.helix, train.planet.helix, train.ring.helix)] == [
            round(x * 3.141592653589793 / 180, 6) for x in (10.25, 10.0, 9.75)]
        errs = read_installment(case.table("installment"), 5)
        assert [round(e.d_ex * 1e3, 9) for e in errs] == dex
        assert [round(e.d_gamma * 180 / 3.141592653589793 * 60, 9) for e in errs] == dg


def test_cli_regulation_end_to_end(tmp_path, capsys):
    # the Table 1.2 case on a coarse grid (10 steps per cycle, one cycle) to keep the suite fast
    case = variant(tmp_path, REG, steps_per_cycle=10, cycles=1)
    out = tmp_path / "out"
    assert main(["tca", str(case), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["kind"] == "planetary"
    assert [r["dEx_um"] for r in s["regulation"]] == [0, 20, -20, 5, -5]
    for r, dz1 in zip(s["regulation"], [0, -4.44, 4.44, -1.11, 1.11]):
        assert set(r) >= {"dEx_um", "dz1_mm", "dz2_mm"}
        assert r["dz1_mm"] == pytest.approx(dz1, abs=0.01)
        assert r["dz2_mm"] == pytest.approx(r["dz1_mm"], abs=0.02)  # coarse grid: peaks to ~0.2 arcsec
    assert s["te_spread_before_arcsec"] > 140
    assert s["te_spread_after_arcsec"] < s["te_spread_before_arcsec"] / 10
    assert s["single_planet_in_mesh_before"] is True
    assert s["before"]["planets_in_mesh"] == [2]
    for f in ("summary.json", "te.csv", "fig14_te.png", "fig14c_contact_paths.png"):
        assert (out / f).stat().st_size > 0
    assert not (out / "fig15_members.png").exists()
    rows = (out / "te.csv").read_text().splitlines()
    assert len(rows) == 1 + 11 and rows[0].startswith("phi1_deg,te_before_1_arcsec")
    assert "te_spread_after_arcsec" in capsys.readouterr().out


@pytest.mark.parametrize("section,subs,message", [
    ("", {"planets": 4}, r"gears\.ring\.teeth = 109 is invalid.*\(Eq\. 1\.3\): \(41 \+ 109\) / 4 = 37\.5"),
    ("gears.planet", {"teeth": 33}, r"gears\.planet\.teeth = 33 is invalid.*\(109 - 41\) / 2 = 34 \(Eq\. 1\.4\)"),
    ("tca", {"steps_per_cycle": 12}, r"tca\.steps_per_cycle = 12 is invalid.*multiple of the number of planets"),
    ("", {"d_ex_um": "[0.0, 20.0]"}, r"installment\.d_ex_um.*a list of 5 numbers"),
    ("", {"d_gamma_arcmin": "[0, 0, 90, 0, 0]"}, r"installment\.d_gamma_arcmin.*numbers in \[-60, 60\]"),
    ("gears.ring", {"helix_deg": 10.25}, r"gears\.ring\.helix_deg = 10\.25 is invalid.*beta1 != beta3"),
])
def test_bad_input_exit_status_2_and_no_files(tmp_path, capsys, section, subs, message):
    case = variant(tmp_path, REG, section, **subs)
    out = tmp_path / "out"
    assert main(["tca", str(case), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert re.search(message, err), err
    assert not out.exists() or not any(out.iterdir())
