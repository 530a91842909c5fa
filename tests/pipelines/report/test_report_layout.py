"""report.html reads well at 1400 px (issue 25, item 4): no table cut off or overlapping its neighbour, images inside
the page, the rating table, ISO's σ_F0 and σ_H0 beside the FE values, the tooth-pair shares, a picture of each
flagged peak; ``compare`` states Part 1's finding only for twin drives. Laid out by headless Chromium
(tests/pipelines/report/html_check.py); the screenshots are kept in the test's folder for a person to look at."""

import json

import pytest

from pipelines.cli import main

from tests.pipelines.report.html_check import layout, overlaps, screenshot
from tests.support.shipped import shipped_data, write_case

GEAR = {"material": "Eh", "quality": "MQ", "hardness": 700.0}
RATING = {"driver_speed_rpm": 1500.0, "life_hours": 20000.0, "viscosity_40_mm2s": 220.0, "application_factor": 1.25,
          "accuracy_grade": 6, "gears": {"pinion": dict(GEAR), "wheel": dict(GEAR)}}


def check_layout(page, tmp_path):
    box = layout(page, tmp_path)
    w = box["width"]
    assert box["tables"], "no table on the page"
    cut = [t for t in box["tables"] if t[2] > w + 1 or t[0] < -1]
    assert not cut, f"tables beyond the {w} px page: {cut}"
    assert not overlaps(box["tables"]), "tables overlap"
    assert not overlaps(box["headings"]), "headings overlap"
    assert all(i[2] <= w + 1 for i in box["images"]), "an image beyond the page"
    return box


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("layout")
    case = write_case(tmp, "spur", shipped_data("stress_spur_pair", {"rating": RATING, "mesh.teeth": 3}))
    out = {"hpstc": tmp / "hpstc"}  # the entering pair's tip edge is flagged there (a peak picture)
    assert main(["run", str(case), "--out", str(out["hpstc"]), "--refine", "0.4", "--position", "hpstc"]) == 0
    cmp = tmp / "cmp"
    assert main(["compare", str(case), str(case), "--out", str(cmp), "--refine", "0.3", "--position", "pitch"]) == 0
    return out, cmp


def test_run_report_reads_well_at_1400_px(runs, tmp_path):
    out, _ = runs
    page = out["hpstc"] / "report.html"
    check_layout(page, tmp_path)
    screenshot(page, out["hpstc"] / "screenshot_1400.png", tmp_path, size=(1400, 6000))
    text = page.read_text()
    s = json.loads((out["hpstc"] / "summary.json").read_text())
    for head in ("ISO 6336 rating", "FE beside ISO 6336", "Load per pair of teeth", "Flagged peaks"):
        assert head in text
    assert f"{s['iso6336_sigma_f0_mpa']['pinion']:.4g}" in text and "σ_H0·Z_B/Z_ε" in text
    share = s["load_share"]["pinion-wheel"]["teeth"]["a/pinion0-wheel0"]
    assert 0.5 < share < 0.7 and f"<td>{share:.4g}</td>" in text  # the loaded pair's share, not the member's 1.000
    assert s["pictures"]["peaks"] and all((out["hpstc"] / p["file"]).is_file() for p in s["pictures"]["peaks"])
    assert s["rating"]["gears"]["pinion"]["safety_bending"] > 1


def test_compare_of_two_pair_cases_states_no_part1_finding(runs, tmp_path):
    _, cmp = runs
    md = (cmp / "compare.md").read_text()
    assert "What the two cases share" in md and "reproduced" not in md and "Fig. 1.9" not in md
    f = json.loads((cmp / "compare.json").read_text())["finding"]
    assert "reproduced" not in f and "contact_peak_mpa" in f
    text = (cmp / "report.html").read_text()
    assert "What the two cases share" in text and "Finding (Part 1" not in text
    check_layout(cmp / "report.html", tmp_path)
    screenshot(cmp / "report.html", cmp / "screenshot_1400.png", tmp_path, size=(1400, 6000))
