"""Where the fillet begins: rack junction, or the crossing of a folded (swallowtail) fillet on internal gears."""

import math

import numpy as np
import pytest

from mesher import MeshOptions, mesh_gear
from mesher.region import fillet_start
from tca import Gear
from tca.errors import GeometryError

from tests.mesher.gears import gear


@pytest.mark.parametrize("name", ["sun", "planet", "sun3", "planet3"])
def test_external_fillets_start_at_the_rack_junction(name):
    g = gear(name)
    for side in (1, -1):
        u0, w0, folded = fillet_start(g, side)
        assert not folded
        assert u0 == g.area(side).u_form and w0 == g.surface(side, "fillet").u_range[1]


@pytest.mark.parametrize("name", ["ring", "ring3"])
def test_internal_fillet_swallowtail_is_trimmed_at_its_crossing_with_the_flank(name):
    # the envelope of the rack's tip rounding runs back along the flank, turns at a cusp and crosses
    # the flank: the boundary passes from flank to fillet at that crossing, a little above u_form
    g = gear(name)
    u0, w0, folded = fillet_start(g, 1)
    assert folded
    fl, fi = g.surface(1, "flank"), g.surface(1, "fillet")
    for z in (-10.0, 0.0, 7.0):  # a helicoid's sections are turned copies: the crossing holds at every z
        assert np.linalg.norm(fl.points(u0, z) - fi.points(w0, z)) < 1e-10
    assert 0 < u0 - g.area(1).u_form < 0.05 * g.module
    assert fillet_start(g, -1)[:2] == pytest.approx((u0, w0), abs=1e-12)  # symmetric rack


def test_sharp_tool_on_an_internal_gear_is_refused_with_the_reason():
    g = Gear("ring", 57, 3.0, math.radians(25), 20.0, internal=True, profile_shift=-0.3, tool_tip_radius=0.1)
    with pytest.raises(GeometryError, match="tool tip radius"):
        mesh_gear(g, MeshOptions(teeth=1))
