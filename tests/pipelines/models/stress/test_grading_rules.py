"""The grading away from the zones of the stress models' sizes (issue 26, item 2;
pipelines.models.stress.sizing (G1)-(G6)).

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
    assert sz.fillet == pytest.approx(0.045 * m)  # (G1)
    assert sz.axial_coarse == pytest.approx(2.0 * sz.coarse)  # (G2)
    assert sz.section_growth == pytest.approx(1.3) and sz.depth_growth == pytest.approx(1.5)  # (G3), (G5)
    assert sz.growth == 1.5 and sz.axial_growth is None  # (G4): the profile and axial levels grow by mesh.growth
    assert sz.back == sz.fillet
    fine = zone_sizes(SizeRules(refine=2.0), sun, False, ZONES, 1.0, 5.0)
    assert fine.fillet == pytest.approx(0.5 * sz.fillet) and fine.axial_coarse == pytest.approx(0.5 * sz.axial_coarse)
    # (G3), (G5): the slope q - 1 of the size field is divided by refine like the sizes
    assert fine.section_growth == pytest.approx(1.15) and fine.depth_growth == pytest.approx(1.25)
    coarse = zone_sizes(SizeRules(refine=0.3), sun, False, ZONES, 1.0, 5.0)
    assert coarse.axial_coarse == pytest.approx(coarse.coarse)  # (G2): never beyond 1.5 m unless the coarse size is
    assert coarse.section_growth == pytest.approx(2.0) and coarse.depth_growth == pytest.approx(8 / 3)
    mid = zone_sizes(SizeRules(refine=0.6), sun, False, ZONES, 1.0, 5.0)
    assert mid.axial_coarse == pytest.approx(1.5 * m)
    assert mid.section_growth == pytest.approx(1.5) and mid.depth_growth == pytest.approx(1 + 0.5 / 0.6)
    rough = zone_sizes(SizeRules(refine=0.1), sun, False, ZONES, 1.0, 5.0)
    assert rough.section_growth == 3.0 and rough.depth_growth == 3.0  # the mesher's largest growth


def test_grading_overrides(sun):
    sz = zone_sizes(SizeRules(axial_coarse=2.5, section_growth=1.3, depth_growth=1.4, axial_growth=1.2, back=0.3,
                              refine=0.5), sun, False, ZONES, 1.0, 5.0)
    assert sz.axial_coarse == pytest.approx(5.0) and sz.section_growth == 1.3
    assert sz.depth_growth == 1.4 and sz.axial_growth == 1.2 and sz.back == pytest.approx(0.6)
    # never below the zone's axial size (the mesher's size field needs h_max >= h_focus)
    tiny = zone_sizes(SizeRules(axial_coarse=1e-3), sun, False, ZONES, 1.0, 5.0)
    assert tiny.axial_coarse == pytest.approx(tiny.axial)


@pytest.mark.parametrize("kw, key", [(dict(axial_coarse=0.0), "mesh.axial_coarse_size_mm"),
                                     (dict(axial_coarse=float("inf")), "mesh.axial_coarse_size_mm"),
                                     (dict(section_growth=1.0), "mesh.section_growth"),
                                     (dict(section_growth=4.0), "mesh.section_growth"),
                                     (dict(depth_growth=1.0), "mesh.depth_growth"),
                                     (dict(axial_growth=3.5), "mesh.axial_growth"),
                                     (dict(back=0.0), "mesh.back_size_mm")])
def test_bad_grading_rules_name_their_key(kw, key):
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        SizeRules(**kw)


def test_axial_size_of_a_uniform_line_contact(sun):
    """(G7): a line contact whose line load is uniform (w_min / w_max >= 0.9) gets a/4 along the line, one whose load
    varies (misalignment, end relief) and an ellipse a/6; an inclined line keeps b / (3 s) when finer."""
    a = 4.0  # [mm]: a/4 and a/6 below the coarse size 0.75 m of the sun (m = 2 mm)
    spur = ((0.13, a, 0.0, 0.95),)
    assert zone_sizes(SizeRules(), sun, True, spur, 0.2, 8.0).axial == pytest.approx(a / 4)
    assert zone_sizes(SizeRules(), sun, True, ((0.13, a, 0.0, 0.78),), 0.2, 8.0).axial == pytest.approx(a / 6)
    assert zone_sizes(SizeRules(), sun, False, spur, 0.2, 8.0).axial == pytest.approx(a / 6)  # an ellipse
    assert zone_sizes(SizeRules(), sun, True, ((0.13, a, 0.0),), 0.2, 8.0).axial == pytest.approx(a / 4)  # u unknown
    helical = zone_sizes(SizeRules(), sun, True, ((0.13, a, 0.3, 1.0),), 0.2, 8.0)
    assert helical.axial == pytest.approx(max(0.13 / 0.9, helical.contact))
    assert zone_sizes(SizeRules(refine=2.0), sun, True, spur, 0.2, 8.0).axial == pytest.approx(a / 8)
