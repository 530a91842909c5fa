"""pipelines.report.designs: the two designs of gearfe compare in two processes, one exchange of colour limits.

Checked with plain callables (no FE): the summaries and the common ranges are those of the serial run, the
second design really runs in another process, and its failure is raised in the parent (no FE error is lost).
"""

import os

import pytest

from tca.errors import InputError

from pipelines.report.designs import DesignSteps, run_designs

LIMITS = {"new": (100.0, 7.0), "conventional": (300.0, 5.0)}


def _steps(fail: str | None = None):
    def solve(label):
        if label == fail:
            raise InputError("mesh.refine", 9.0, "in (0, 4]", "test failure in the design's solve")
        return {"label": label, "pid": os.getpid()}

    def limits(run):
        return LIMITS[run["label"]]

    def finish(label, run, vm, top):
        return {"label": label, "vm": vm, "top": top, "pid": run["pid"], "finish_pid": os.getpid()}

    return DesignSteps(solve, limits, finish)


@pytest.mark.parametrize("jobs", [1, 2])
def test_common_ranges_and_summaries(jobs):
    s = run_designs(("new", "conventional"), _steps(), jobs=jobs)
    assert list(s) == ["new", "conventional"]
    for label in s:
        assert s[label]["label"] == label
        assert (s[label]["vm"], s[label]["top"]) == (300.0, 7.0)  # the maxima of both designs' limits
    assert s["new"]["pid"] == os.getpid()
    assert (s["conventional"]["pid"] != os.getpid()) == (jobs == 2)  # the second design in its own process
    assert s["conventional"]["finish_pid"] == s["conventional"]["pid"]


@pytest.mark.parametrize("fail", ["new", "conventional"])
def test_a_failing_design_raises_in_the_parent(fail):
    with pytest.raises(InputError, match="mesh.refine"):
        run_designs(("new", "conventional"), _steps(fail), jobs=2)
