"""Issue 26 targets of the models sized by the loaded TCA (``make bench``: about 1.5 min on a quiet 2-core machine).

References outside the code path: the peak pressure of the crowned pair's model before issue 26 at refine 1.41
(2190 MPa, 638,784 DOF, issue 26) and the Richardson value of the fillet stress from the loaded levels at refine
0.71/1/1.41 (626.9 MPa, order 0.84, docs/benchmarks.md: pinned from those runs, with the split surface under the
fillet meshed uniformly); the Richardson value of the fillet stress with the graded split surface, from the fillet
size halved twice at refine 1 (0.2/0.1/0.05 mm: 603.2/609.3/610.9 MPa, 611.5 MPa, order 1.91; refine 0.71/1/1.41 with
the fillet 0.1 mm / refine gives 609.6 MPa; ``python -m benchmarks.sizing --grading``, pinned from those runs); Hertz's line contact of the whole
load for the FZG-type pair (Johnson eq. 4.45 via the summary's estimate); the twin drive's member shares of the
model before issue 26 (0.511/0.489 at the sun, 0.388/0.612 at the ring, docs/models.md; measured again at
0.506/0.388 on the same code). Timings are not asserted (machine load): docs/benchmarks.md has them.
"""

import pytest

from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress

from tests.support.shipped import shipped_table

pytestmark = pytest.mark.bench

FZG = {"gears.pinion.teeth": 16, "gears.pinion.profile_shift": 0.18, "gears.wheel.profile_shift": 0.17,
       "center_distance_mm": 91.5}


@pytest.fixture(scope="module")
def crowned(tmp_path_factory):
    case = read_stress_case(shipped_table("stress_pair_small", {"mesh.refine": 1.0}))
    return run_stress(case, tmp_path_factory.mktemp("crowned")).summary


def test_crowned_pair_at_the_default(crowned):
    s = crowned
    assert s["dofs"] <= 160_000  # measured 149,025 (147,906 before the fourth round, 159,840 before item 2)
    assert s["max_contact_pressure_mpa"] == pytest.approx(2190.0, rel=0.05)  # measured 2225.5
    assert s["load_share"]["sun-planet"]["teeth"]["a/sun0-planet0"] == pytest.approx(1.0, abs=0.02)


def test_crowned_pair_fillet_within_3_percent_of_richardson(crowned):
    # measured 608.3 MPa, -2.97 % (606.9 before the fourth round, 589.2 before the grading of item 2: strict xfails);
    # 626.9 is the Richardson value of a sequence at order 0.84 with the split surface meshed uniformly
    assert crowned["max_fillet_stress_mpa"] == pytest.approx(626.9, rel=0.03)


def test_crowned_pair_fillet_within_3_percent_of_the_graded_richardson_value(crowned):
    # 611.5 MPa: Richardson from the fillet size 0.2/0.1/0.05 mm at refine 1 (order 1.91), pinned from those runs;
    # measured 608.3 (-0.5 %; 606.9 before the fourth round); before the grading of item 2: 589.2 (-3.6 %, fails)
    assert crowned["max_fillet_stress_mpa"] == pytest.approx(611.5, rel=0.03)


def test_fzg_pair_at_the_pitch_point(tmp_path):
    s = run_stress(read_stress_case(shipped_table("stress_spur_pair", FZG)), tmp_path / "fzg").summary
    hz = s["interfaces"]["pinion-wheel"]["members"]["a"]["hertz_estimate"]
    assert hz["line"]
    assert s["max_contact_pressure_mpa"] == pytest.approx(hz["p0_mpa"], rel=0.05)  # measured +3.1 % (877.6 / 851.0)
    assert s["dofs"] <= 90_000  # measured 54,648 with (G7) (78,936 before the fifth round, 80,340 before the fourth)


def test_twin_new_design(tmp_path):
    s = run_stress(read_stress_case(shipped_table("stress_part1_new")), tmp_path / "twin").summary
    assert s["dofs"] <= 350_000  # measured 297,078 (342,492 before the fourth round, 341,424 before item 2)
    sun, ring = s["load_share"]["sun-planet"]["members"], s["load_share"]["planet-ring"]["members"]
    assert sun["a"] == pytest.approx(0.511, abs=0.02)  # measured 0.506
    assert ring["a"] == pytest.approx(0.388, abs=0.02)  # measured 0.391 (0.389 before the fourth round)
