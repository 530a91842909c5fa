"""Grading away from the zones (issue 26, item 2): the split surface under the fillet graded like the base, the axial
spacing outside the zones (``axial_coarse_size``, ``axial_growth``) and the growth across the loaded tooth
(``section_growth`` under the loaded fillet, ``depth_growth`` under the contact and the other flank, from
``back_size``).

The reference is the plan's own distributions (:func:`mesher.body.plan_tooth`) and the definition of the size field
(:mod:`mesher.grading`: every element at most its target size); the fillet stress they buy is measured in
docs/benchmarks.md ("Third round: grading away from the zones").
"""

import numpy as np
import pytest

from mesher import Focus, MeshOptions
from mesher.body import plan_gear, plan_tooth
from mesher.grading import SizeField, count, uniform
from mesher.tooth import ToothGeometry
from tca.errors import InputError

from tests.mesher.gears import gear

COARSE = dict(coarse_size=1.5, contact_size=0.1, fillet_size=0.2, neighbour_size=0.6, axial_contact_size=0.8)
FOCI = {"sun": Focus(1, 0.4, 0.0, 0.5, 3.0), "ring": Focus(-1, -0.3, 0.0, 0.4, 3.0)}  # external and internal


@pytest.mark.parametrize("name", list(FOCI))
def test_split_surface_is_graded_toward_the_space_centre(name):
    g, focus = gear(name), FOCI[name]
    o = MeshOptions(**COARSE)
    sz = o.sizes(g)
    geom = ToothGeometry(g, sz["rim"])
    plan = plan_tooth(geom, sz, 0.0, focus, label="loaded")
    rim = uniform(count(sz["rim"], SizeField(sz["coarse"]), 2))
    blk = geom.blocks(plan, np.array([-1.0, 1.0]), rim)
    for s, key in ((1, "B+"), (-1, "B-")):
        split = blk[key][0, -1, :, :2]  # the row at the space-centre end: mid-surface (j = 0) -> root (j = n)
        seg = np.linalg.norm(np.diff(split, axis=0), axis=1)
        h = plan.half[s]
        # the split surface's layers follow the base's graded fractions (a straight line in polar coordinates:
        # its chord fractions within 2 % of the plan's), the last layer thinner than a uniform one
        np.testing.assert_allclose(np.concatenate([[0.0], np.cumsum(seg)]) / seg.sum(), h, atol=0.02)
        assert seg[-1] < 0.75 * seg.sum() / len(seg)


def test_axial_coarse_size_coarsens_only_outside_the_zone():
    g, focus = gear("sun"), FOCI["sun"]
    base = plan_gear(g, MeshOptions(teeth=3, **COARSE), focus=focus).members[0].z
    wide = plan_gear(g, MeshOptions(teeth=3, axial_coarse_size=3.0, **COARSE), focus=focus).members[0].z
    assert len(wide) < len(base)
    dz_b, dz_w = np.diff(base), np.diff(wide)
    assert dz_w.max() <= 3.0 + 1e-9 and dz_w.max() > 1.5  # the size field's bound, and it is used
    near = lambda z, dz: dz[np.maximum(np.abs(z[1:] - focus.z), np.abs(z[:-1] - focus.z)) <= focus.extent_z]  # noqa: E731
    # the zone keeps its axial levels' spacing (within 5 %: the pinned focus shares the count out a little differently)
    assert near(wide, dz_w).max() <= 1.05 * near(base, dz_b).max()
    assert near(base, dz_b).max() < 1.1 * COARSE["axial_contact_size"]


def test_section_growth_sets_the_layers_across_the_loaded_tooth():
    g, focus = gear("sun"), FOCI["sun"]
    slow = plan_gear(g, MeshOptions(teeth=3, **COARSE), focus=focus)
    fast = plan_gear(g, MeshOptions(teeth=3, section_growth=1.6, **COARSE), focus=focus)
    ls, lf = slow.members[0].plans[slow.centre_index], fast.members[0].plans[fast.centre_index]
    assert lf.n_half(1) < ls.n_half(1) and lf.n_flank == ls.n_flank  # the flank's contact grading is unchanged
    assert fast.cells < slow.cells


def test_fillet_layers_and_depth_layers_are_graded_apart():
    """The loaded side's layers follow the finer of the Hertz field (contact size, ``depth_growth``) and the fillet
    field (fillet size, ``section_growth``); the other side's follow ``back_size`` and ``depth_growth``."""
    g, focus = gear("sun"), FOCI["sun"]
    s, b = focus.side, -focus.side

    def loaded(**kw):
        p = plan_gear(g, MeshOptions(teeth=3, **{**COARSE, **kw}), focus=focus)
        return p, p.members[0].plans[p.centre_index]

    p0, t0 = loaded(section_growth=1.5, depth_growth=1.5)
    _, slow = loaded(section_growth=1.1, depth_growth=1.5)
    assert slow.n_half(s) > t0.n_half(s) and slow.n_half(b) == t0.n_half(b)  # the fillet field: the loaded side only
    _, deep = loaded(section_growth=1.5, depth_growth=2.0)
    assert deep.n_half(b) < t0.n_half(b) and deep.n_half(s) <= t0.n_half(s)
    _, back = loaded(section_growth=1.5, depth_growth=1.5, back_size=0.6)
    assert back.n_half(b) < t0.n_half(b) and back.n_half(s) == t0.n_half(s)
    # every layer on the loaded side at most the finer field's size at its outer end (depth d from the flank)
    sz = p0.sizes
    L = ToothGeometry(g, sz["rim"]).base_length(s, 0.0)
    x = (1.0 - slow.half[s][::-1]) * L  # depths from the flank, 0 -> L
    h = np.diff(x)
    field = np.minimum(sz["contact"] + 0.5 * x[1:], sz["fillet"] + 0.1 * x[1:])
    assert np.all(h <= np.minimum(field, sz["coarse"]) + 1e-9)
    # the axial levels away from the zone grow by axial_growth
    fast = plan_gear(g, MeshOptions(teeth=3, axial_growth=2.0, **COARSE), focus=focus).members[0].z
    assert len(fast) < len(p0.members[0].z)


@pytest.mark.parametrize("kw, key", [(dict(axial_coarse_size=0.5), "mesh.axial_coarse_size_mm"),
                                     (dict(axial_coarse_size=-1.0), "mesh.axial_coarse_size_mm"),
                                     (dict(section_growth=0.9), "mesh.section_growth"),
                                     (dict(depth_growth=3.5), "mesh.depth_growth"),
                                     (dict(axial_growth=0.5), "mesh.axial_growth"),
                                     (dict(back_size=0.0), "mesh.back_size_mm")])
def test_bad_grading_options_name_their_key(kw, key):
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        MeshOptions(**{**COARSE, **kw}).sizes(gear("sun"))
