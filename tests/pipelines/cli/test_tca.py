"""`gearfe tca` on pair cases: files and summary keys, shipped cases, bad input -> status 2 and no files."""

import csv
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from pipelines.cases.reader import CASES_DIR
from pipelines.cli import main

FAST_PAIR = """
kind = "pair"
title = "test pair"
driver = "pinion"
driven = "gear"
[gears.pinion]
teeth = 21
module_mm = 2.0
pressure_angle_deg = 20.0
face_width_mm = 20.0
helix_deg = 10.0
hand = "right"
parabola_drive_per_mm = 0.004
[gears.gear]
teeth = 35
module_mm = 2.0
pressure_angle_deg = 20.0
face_width_mm = 20.0
helix_deg = 10.0
hand = "left"
[misalignment]
d_gamma_arcmin = 3.0
[tca]
cycles = 2
steps_per_cycle = 12
"""


def write(tmp_path, text, name="case.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_pair_case_writes_summary_csv_and_plots(tmp_path):
    case = write(tmp_path, FAST_PAIR)
    out = tmp_path / "out"
    assert main(["tca", str(case), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    for key in ("te_peak_to_peak_arcsec", "edge_contact", "positions", "max_residual_mm", "elapsed_s"):
        assert key in s
    assert s["positions"] == 25 and s["max_residual_mm"] < 1e-10
    rows = list(csv.DictReader(open(out / "tca.csv")))
    assert len(rows) == 25
    for col in ("phi1_deg", "phi2_deg", "te_arcsec", "x_mm", "ellipse_a_mm", "ellipse_b_mm", "residual_mm"):
        assert col in rows[0]
    for png in ("te.png", "contact_paths.png"):
        assert (out / png).stat().st_size > 10_000
    assert not list(tmp_path.glob(".out.tmp-*"))  # staging folder removed


@pytest.mark.parametrize("name", sorted(p.name for p in CASES_DIR.glob("*.toml") if 'kind = "pair"' in p.read_text()))
def test_shipped_pair_cases_run(tmp_path, name):
    assert main(["tca", str(CASES_DIR / name), "--out", str(tmp_path / "out")]) == 0
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["max_residual_mm"] < 1e-10


@pytest.mark.parametrize(
    "edit,message",
    [
        (("hand = \"left\"", "hand = \"left\"\ncolour = \"red\""), "gears.gear.colour"),
        (("teeth = 21", "teeth = 2"), "gears.pinion.teeth"),
        (("teeth = 21", "teeth = 12"), "undercut"),
        (('driven = "gear"', 'driven = "pinion"'), "driven"),
        (("cycles = 2", "cycles = 0"), "tca.cycles"),
        (('d_gamma_arcmin = 3.0', 'd_gamma_arcmin = "three"'), "misalignment.d_gamma_arcmin"),
        (('kind = "pair"', 'kind = "pear"'), "kind"),
    ],
)
def test_bad_input_exits_2_with_one_line_and_no_files(tmp_path, capsys, edit, message):
    case = write(tmp_path, FAST_PAIR.replace(*edit, 1))
    out = tmp_path / "out"
    assert main(["tca", str(case), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1
    assert not out.exists() or not any(out.iterdir())
    assert not list(tmp_path.glob(".out.tmp-*"))


def test_missing_case_file_exits_2(tmp_path, capsys):
    assert main(["tca", str(tmp_path / "nope.toml"), "--out", str(tmp_path / "o")]) == 2
    assert "CASE" in capsys.readouterr().err


@pytest.mark.skipif(shutil.which("gearfe", path=str(Path(sys.executable).parent)) is None,
                    reason="console script not installed (run through `make test`)")
def test_console_script(tmp_path):
    case = write(tmp_path, FAST_PAIR.replace("teeth = 21", "teeth = 2", 1))
    exe = shutil.which("gearfe", path=str(Path(sys.executable).parent))
    p = subprocess.run([exe, "tca", str(case), "--out", str(tmp_path / "o")], capture_output=True, text=True)
    assert p.returncode == 2 and "gears.pinion.teeth" in p.stderr
