"""The grading away from the zones of the stress models' sizes (issue 26, item 2; pipelines.models.stress.sizing (G1)-(G3)).

The rules are those of the module docstring; the fillet stress they buy is measured in docs/benchmarks.md ("Third
round: grading away from the zones") and asserted by test_sizing_targets.py (``make bench``).
"""

import pytest

from tca.errors import InputError
from tca.report_data import table_1_1_sun

from pipelines.models.stress.sizing import SizeRules, zone_sizes

ZONES = ((0.25, 4.0, 0.2),)  # one loaded pair: half-width b, half-length a [mm], sine of the line's angle


@pytest.fixture(scope="module")
def sun():
    return table_1_1_sun()


def test_default_grading(sun):
    m = sun.module
    sz = zone_sizes(SizeRules(), sun, False, ZONES, 1.0, 5.0)
    assert sz.fillet == pytest.approx(0.05 * m)  # (G1)
    assert sz.axial_coarse == pytest.approx(2.0 * sz.coarse)  # (G2)
    assert sz.section_growth == 1.5 and sz.growth == 1.3  # (G3): the contact grading keeps mesh.growth
    fine = zone_sizes(SizeRules(refine=2.0), sun, False, ZONES, 1.0, 5.0)
    assert fine.fillet == pytest.approx(0.5 * sz.fillet) and fine.axial_coarse == pytest.approx(0.5 * sz.axial_coarse)
    coarse = zone_sizes(SizeRules(refine=0.3), sun, False, ZONES, 1.0, 5.0)
    assert coarse.axial_coarse == pytest.approx(coarse.coarse)  # (G2): never beyond 1.5 m unless the coarse size is
    mid = zone_sizes(SizeRules(refine=0.6), sun, False, ZONES, 1.0, 5.0)
    assert mid.axial_coarse == pytest.approx(1.5 * m)
    steep = zone_sizes(SizeRules(growth=1.8), sun, False, ZONES, 1.0, 5.0)
    assert steep.section_growth == 1.8  # never slower than the contact grading


def test_grading_overrides(sun):
    sz = zone_sizes(SizeRules(axial_coarse=2.5, section_growth=1.3, refine=0.5), sun, False, ZONES, 1.0, 5.0)
    assert sz.axial_coarse == pytest.approx(5.0) and sz.section_growth == 1.3
    # never below the zone's axial size (the mesher's size field needs h_max >= h_focus)
    tiny = zone_sizes(SizeRules(axial_coarse=1e-3), sun, False, ZONES, 1.0, 5.0)
    assert tiny.axial_coarse == pytest.approx(tiny.axial)


@pytest.mark.parametrize("kw, key", [(dict(axial_coarse=0.0), "mesh.axial_coarse_size_mm"),
                                     (dict(axial_coarse=float("inf")), "mesh.axial_coarse_size_mm"),
                                     (dict(section_growth=1.0), "mesh.section_growth"),
                                     (dict(section_growth=4.0), "mesh.section_growth")])
def test_bad_grading_rules_name_their_key(kw, key):
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        SizeRules(**kw)
