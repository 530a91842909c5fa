"""Smoke run of the FE benchmark on small meshes (the full run is ``python -m pipelines.bench.fem``)."""

import json

import pytest

from pipelines.bench import fem as bench_fem


@pytest.mark.slow
def test_bench_fem_quick(tmp_path):
    assert bench_fem.main(["--out", str(tmp_path), "--quick"]) == 0
    report = (tmp_path / "report.md").read_text()
    assert "Targets (issue 6)" in report
    data = json.loads((tmp_path / "bench_fem.json").read_text())
    c = data["speed"]["contact"]
    assert c["torque_error"] < 1e-6
    # the quick Hertz line runs meet the 3 % on the peak pressure
    assert all(abs(r["p_err"]) < 0.03 for r in data["hertz"]["line"])
