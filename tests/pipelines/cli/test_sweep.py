"""`gearfe sweep`: grid, Dask run, gathered CSV, resume without recomputation, bad input."""

import csv
import json

from pipelines.cli import main
from tests.pipelines.cli.test_tca import FAST_PAIR

SWEEP = """
task = "tca"
base = "base.toml"
[[axes]]
key = "misalignment.d_gamma_arcmin"
values = [0.0, 3.0]
[[axes]]
key = "gears.pinion.parabola_drive_per_mm"
values = [0.004]
"""


def setup(tmp_path, sweep=SWEEP):
    (tmp_path / "base.toml").write_text(FAST_PAIR)
    (tmp_path / "sweep.toml").write_text(sweep)
    return tmp_path / "sweep.toml"


def test_sweep_runs_gathers_and_resumes(tmp_path):
    sw = setup(tmp_path)
    out = tmp_path / "out"
    assert main(["sweep", str(sw), "--out", str(out), "--workers", "1"]) == 0
    rows = list(csv.DictReader(open(out / "results.csv")))
    assert [r["misalignment.d_gamma_arcmin"] for r in rows] == ["0.0", "3.0"]
    assert all(r["status"] == "ok" for r in rows)
    # the misaligned point has a larger TE than the aligned one (crowned pinion absorbs it partly)
    assert float(rows[1]["te_peak_to_peak_arcsec"]) != float(rows[0]["te_peak_to_peak_arcsec"])
    stamps = {p.name: (p / "summary.json").stat().st_mtime_ns for p in (out / "cases").iterdir()}
    assert len(stamps) == 2
    # an interrupted run leaves a hidden temporary folder: it is not a result and is cleaned up
    (out / "cases" / ".abc.tmp-123").mkdir()
    assert main(["sweep", str(sw), "--out", str(out), "--workers", "1"]) == 0  # nothing left: no cluster started
    assert not (out / "cases" / ".abc.tmp-123").exists()
    again = {p.name: (p / "summary.json").stat().st_mtime_ns for p in (out / "cases").iterdir()}
    assert again == stamps  # finished points were not recomputed
    grid = json.loads((out / "sweep.json").read_text())
    assert grid["axes"] == ["misalignment.d_gamma_arcmin", "gears.pinion.parabola_drive_per_mm"]


def test_bad_sweep_key_exits_2_before_any_work(tmp_path, capsys):
    sw = setup(tmp_path, SWEEP.replace("gears.pinion.parabola_drive_per_mm", "gears.pinion.colour"))
    out = tmp_path / "out"
    assert main(["sweep", str(sw), "--out", str(out)]) == 2
    assert "colour" in capsys.readouterr().err
    assert not out.exists()


def test_bad_sweep_value_exits_2(tmp_path, capsys):
    sw = setup(tmp_path, SWEEP.replace("values = [0.004]", "values = [-1.0]"))
    assert main(["sweep", str(sw), "--out", str(tmp_path / "o")]) == 2
    assert "parabola_drive_per_mm" in capsys.readouterr().err


def test_sweep_with_a_failing_point_keeps_the_others(tmp_path, capsys):
    # a centre distance 5 mm too large takes the teeth out of mesh (contact ratio < 1: no contact), which
    # only the TCA finds: the point fails at run time, the other point is computed, the sweep exits 1
    sw = setup(tmp_path, SWEEP.replace('key = "misalignment.d_gamma_arcmin"\nvalues = [0.0, 3.0]',
                                       'key = "misalignment.d_center_um"\nvalues = [0.0, 5000.0]'))
    assert "d_center_um" in sw.read_text()
    out = tmp_path / "out"
    assert main(["sweep", str(sw), "--out", str(out), "--workers", "0"]) == 1  # the same run_point as on Dask
    rows = list(csv.DictReader(open(out / "results.csv")))
    assert [r["misalignment.d_center_um"] for r in rows] == ["0.0", "5000.0"]
    assert rows[0]["status"] == "ok" and float(rows[0]["te_peak_to_peak_arcsec"]) > 0
    assert rows[1]["status"].startswith("error:") and "no contact" in rows[1]["status"]
    # only the finished point has a case folder (the failed one leaves no half-written files)
    assert [p.name for p in (out / "cases").iterdir()] == [rows[0]["id"]]
    assert rows[1]["id"] in capsys.readouterr().err
