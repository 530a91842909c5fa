"""plan_gear: the element and node counts of mesh_gear before a node is placed (issue 26).

The resource estimate of a stress model (pipelines.models.stress.model.estimate_resources) is the sum of
its parts' plans, so it is exact only if every plan counts what the mesher then builds: checked here on the
shapes of zone the stress scenes make (a point zone, a helical line zone across the whole face, further
foci on neighbouring teeth, a double-helical gear, an internal gear, an end relief's pinned levels are in
the shipped-case sweep of ``make bench``, benchmarks.reliability). Exact equality: both count the same
distributions, so any difference is a bug, not a tolerance.
"""

import pytest

from mesher import Focus, MeshOptions, mesh_gear
from mesher.body import plan_gear

from tests.mesher.gears import gear

COARSE = dict(coarse_size=1.5, contact_size=0.3, fillet_size=0.4, neighbour_size=0.6, axial_contact_size=0.8)

CASES = {
    "point zone": ("sun", dict(teeth=3), Focus(1, 0.4, 2.0, 0.5, 3.0), ()),
    "helical line across the face": ("planet", dict(teeth=3), Focus(-1, 0.2, 0.0, 1.3, 18.0), ()),
    "two further foci": ("sun", dict(teeth=3), Focus(1, 0.4, 0.0, 0.6, 9.0),
                         ((1, Focus(1, 1.2, -6.0, 0.5, 9.0)), (40, Focus(1, -0.8, 7.0, 0.5, 9.0)))),
    "internal gear": ("ring", dict(teeth=3), Focus(-1, -0.3, -6.0, 0.4, 4.0), ()),
    "double-helical": ("planet", dict(teeth=1, gap=10.0), Focus(-1, 0.2, 4.0, 0.4, 3.0), ()),
    "no focus": ("planet3", dict(teeth=1), None, ()),
}


@pytest.mark.parametrize("name", list(CASES))
def test_plan_counts_are_the_mesh_counts(name):
    g, opts, focus, others = CASES[name]
    o = MeshOptions(**opts, **COARSE)
    plan = plan_gear(gear(g), o, focus=focus, others=others)
    mesh = mesh_gear(gear(g), o, focus=focus, others=others, check=False)
    assert (plan.cells, plan.nodes) == (mesh.n_cells, mesh.n_points)
