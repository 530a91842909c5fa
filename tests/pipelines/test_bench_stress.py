"""The stress speed-vs-error benchmark: error bookkeeping on analytic sequences, and a real --quick run."""

from __future__ import annotations

import json
import math

import pytest

from pipelines.bench import AREAS
from pipelines.bench.stress import QUANTITIES, choose_refine, errors_of, main

Q = math.sqrt(2.0)


def test_errors_of_recovers_an_asymptotic_sequence():
    # f = 100 + 40 h^2 exactly (h = 1/refine): orders 2, Richardson limit 100 to rounding
    refines = [0.5 * Q**k for k in range(4)]
    f = [100 + 40 / r**2 for r in refines]
    e = errors_of(refines, f)
    assert e["asymptotic"]
    assert e["orders"] == pytest.approx([2.0, 2.0], abs=1e-9)
    assert e["reference"] == pytest.approx(100.0, rel=1e-12)
    assert e["errors"][0] == pytest.approx(160 / 100, rel=1e-9)


def test_errors_of_falls_back_to_the_finest_level_when_erratic():
    # differences change sign (as a nodally sampled peak does): no Richardson limit, errors against the finest
    refines = [0.5 * Q**k for k in range(4)]
    f = [130.0, 110.0, 112.0, 100.0]
    e = errors_of(refines, f)
    assert not e["asymptotic"]
    assert e["orders"] == [None, None]
    assert e["reference"] == 100.0
    assert e["errors"][:3] == pytest.approx([0.30, 0.10, 0.12]) and e["errors"][-1] is None


def test_choose_refine_takes_the_cheapest_level_within_tolerance():
    rows = [{"refine": r, "dofs": d} for r, d in ((0.5, 1), (1.0, 2), (2.0, 3))]
    errs = {"max_von_mises_mpa": {"errors": [0.2, 0.03, 0.01]},
            "max_contact_pressure_mpa": {"errors": [0.3, 0.06, 0.02]}}
    c = choose_refine(rows, errs)
    assert c["refine"] == 2.0 and c["both_index"] == 2
    errs["max_contact_pressure_mpa"]["errors"] = [0.3, 0.1, None]  # pressure not bounded at any level
    c = choose_refine(rows, errs)
    assert c["refine"] == 1.0 and c["both_index"] is None and c["von_mises_index"] == 1


def test_stress_area_is_registered():
    assert AREAS["stress"][0] == "pipelines.bench.stress"
    for area in ("tca", "fem", "mesher", "part1", "part2", "part3"):
        assert area in AREAS


def test_quick_run_writes_report_and_plots(tmp_path):
    # three coarse levels of the real sun-planet contact model, a coarse speed check and two Hertz solves
    assert main(["--out", str(tmp_path), "--quick"]) == 0
    md = (tmp_path / "stress.md").read_text()
    data = json.loads((tmp_path / "stress.json").read_text())
    for name in ("stress_error_dof.png", "stress_error_time.png", "stress_values.png"):
        png = tmp_path / name
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    rows = data["levels"]
    assert len(rows) == 3
    assert [r["dofs"] for r in rows] == sorted(r["dofs"] for r in rows)
    for r in rows:
        assert f"| {r['refine']:.3f} | {r['dofs']} |" in md
        for k in QUANTITIES:
            assert f"{r[k]:.1f}" in md
        assert r["contact_force_n"] == pytest.approx(r["hertz"]["load_n"], rel=0.01)  # all the load on the loaded pair
    for k, e in data["errors"].items():  # errors are |f - reference| / reference
        for r, x in zip(rows, e["errors"]):
            if x is not None:
                assert x == pytest.approx(abs(r[k] - e["reference"]) / e["reference"], rel=1e-9)
    s = data["speed"]
    assert s["ratio"] == pytest.approx(s["best"]["contact_solve_s"] / s["linear"]["pardiso_s"])
    assert f"= {s['ratio']:.2f} |" in md
    # issue 14 tolerance on the peak Hertz pressure at 3 elements per half-width with the default constraints: 3 %
    for key in ("line", "point"):
        for r in data["hertz"][key]:
            assert f"{r['p_err']:+.2%}" in md
            if r["points"] == "gauss":
                assert abs(r["p_err"]) < 0.03 and abs(r["moment_a_err"]) < 0.10
    # issue 14: today's method beside the default at every level, same meshes
    st = data["pressure"]
    assert [r["dofs"] for r in st["nodes_levels"]] == [r["dofs"] for r in rows]
    assert "Targets (issue 14)" in md
