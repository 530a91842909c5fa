"""Mesh convergence of a gear-level stress (issue 13): the fillet's maximum principal stress of the loaded
teeth converges under refinement of the whole model, with an observed order above 0.5.

Case: the shipped crowned pair (pipelines/cases/stress_pair_small.toml, Table 1.1 sun driving the
double-crowned planet, 3 arcmin) at refine 0.5, 0.707 and 1 (element sizes in the ratio sqrt(2); 51k, 86k
and 147k DOF, about 20 s on the quiet 2-core machine). Measured: 554.0, 575.6, 587.8 MPa, observed order 1.6,
Richardson value 604 MPa (the default refine 1 is 2.7 % below it). With the earlier node-averaged contact
gaps the same study gave no asymptotic order at affordable sizes (differences growing). With the neighbouring
pairs in refined zones of their own the models are larger (76k, 154k and 306k DOF) and the values 554.9,
575.1, 587.0 MPa (observed order 1.56). A convergence study, so it runs with ``make bench`` (marker
``bench``), not ``make test``.

Since issue 26's fourth round the default's layer growth depends on refine ((G3) 1 + 0.3/refine, (G5) 1 + 0.5/refine,
pipelines.models.stress.sizing): at refine 0.5 and 0.71 the layers grow faster than at 1, so the default models of
the three levels are not one family in which only the sizes change, and their fillet stresses (594.06, 601.04,
608.28 MPa) are not in the asymptotic range (a strict expected failure below). With the grading held at refine 1's
the levels converge (order 1.22, second test).
"""

import math
from dataclasses import replace

import pytest

from benchmarks.convergence import richardson
from pipelines.cases import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress

REFINE = (0.5, math.sqrt(0.5), 1.0)

pytestmark = pytest.mark.bench


# the layer growths of the default at refine 1 ((G3) 1.3 under the loaded fillet, (G5) 1.5 under the contact and the
# other flank), held at every level: sizes divided by refine, the grading the same (a self-similar family)
HELD = {"section_growth": 1.3, "depth_growth": 1.5}


def _fillet(tmp_path_factory, **grading):
    case = read_stress_case(load_case(CASES_DIR / "stress_pair_small.toml"))
    out = []
    for r in REFINE:
        mesh = replace(case.mesh, refine=r, **grading)
        s = run_stress(replace(case, mesh=mesh), tmp_path_factory.mktemp(f"r{r:.3f}")).summary
        out.append(s["max_fillet_stress_mpa"])
    return out


@pytest.fixture(scope="module")
def fillet(tmp_path_factory):
    """The default models (their layer growth refine-dependent, (G3) and (G5))."""
    return _fillet(tmp_path_factory)


@pytest.fixture(scope="module")
def fillet_held(tmp_path_factory):
    """The grading held at refine 1's (:data:`HELD`)."""
    return _fillet(tmp_path_factory, **HELD)


def _check_convergence(fillet):
    h = [1.0 / r for r in REFINE]  # element sizes are divided by refine
    rich = richardson(h, fillet)
    # issue 13: observed order > 0.5 over three levels (a consistent discretisation of a smooth stress field;
    # trilinear elements would give 2 in the asymptotic range)
    assert rich.order > 0.5
    # monotone, with shrinking differences
    d1, d2 = fillet[1] - fillet[0], fillet[2] - fillet[1]
    assert d1 > 0 and 0 < d2 < d1
    # the default (refine 1) within 5 % of the extrapolated value, as the docs claim for fillet stresses
    assert abs(fillet[-1] / rich.value - 1) < 0.05


@pytest.mark.xfail(strict=True, raises=AssertionError, reason=(
    "measured 594.06, 601.04, 608.28 MPa at refine 0.5/0.71/1 (47,328 / 78,840 / 149,025 DOF): differences 6.98 and "
    "7.24 MPa, not shrinking (observed order -0.1): with issue 26's refine-dependent layer growth (G3, G5, fourth "
    "round) the three default models are not one family in which only the sizes change (their layers grow faster "
    "at the coarser levels), and they are not in the asymptotic range (with the grading held: order 1.22, next test); refine 1.41 gives 609.02 MPa (348,126 DOF). Failing since the fourth round (0eac15d too), "
    "docs/benchmarks.md 'Fifth round'"))
def test_fillet_stress_converges_with_an_observed_order_above_one_half(fillet):
    _check_convergence(fillet)


def test_fillet_stress_converges_with_the_grading_held(fillet_held):
    """The same levels with the grading held (a self-similar family: only the sizes change): measured 595.37,
    603.18, 608.28 MPa (53,184 / 88,440 / 149,025 DOF), differences 7.81 and 5.10 MPa, observed order 1.22,
    Richardson value 617.9 MPa, refine 1 (the default's model) 1.6 % below it."""
    _check_convergence(fillet_held)
