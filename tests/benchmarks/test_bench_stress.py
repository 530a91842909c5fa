"""The stress speed-vs-error benchmark: error bookkeeping on analytic sequences (the run itself: `make bench`)."""

from __future__ import annotations

import math

import pytest

from benchmarks import AREAS
from benchmarks.stress import choose_refine, errors_of

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
    assert AREAS["stress"][0] == "benchmarks.stress"
    for area in ("tca", "fem", "mesher", "part1", "part2", "part3"):
        assert area in AREAS


# The --quick smoke run of the whole benchmark (60-120 s) moved to `make bench` (issue 13: `make test` under
# 5 minutes); the error bookkeeping above is what the benchmark's numbers rest on.
