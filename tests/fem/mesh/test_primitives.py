"""Structured test meshes: exact counts and volumes, graded spacings, face sets, bad cells."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fem.elements.hex8 import hex_geometry
from fem.mesh import primitives as prim
from fem.errors import FEInputError


def _volume(mesh):
    return hex_geometry(mesh.points, mesh.cells, False).dx.sum()


def test_box_counts_volume_and_sides():
    m = prim.box("b", np.linspace(0, 2, 5), prim.graded(0, 3, 0.1, growth=1.3), np.linspace(0, 1, 3))
    ny = len(prim.graded(0, 3, 0.1, growth=1.3)) - 1
    assert m.n_cells == 4 * ny * 2 and m.n_points == 5 * (ny + 1) * 3
    assert _volume(m) == pytest.approx(6.0, rel=1e-12)
    # the six sides cover the boundary exactly once
    sides = np.concatenate([m.face_sets[f"b/{s}"] for s in ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")])
    bf = prim.boundary_faces(m)
    assert len(sides) == len(bf) and len({tuple(f) for f in sides}) == len(bf)


def test_cylinder_segment_volume_converges_to_the_annulus():
    r = np.linspace(1.0, 2.0, 3)
    th = np.linspace(0.0, np.pi / 2, 65)
    m = prim.cylinder_segment("c", r, th, np.linspace(0, 1, 2))
    exact = np.pi / 4 * (4.0 - 1.0)
    # chords of 1.4 deg: the polygonal annulus is short of the circle by dtheta^2 / 6 = 1.0e-4
    assert _volume(m) == pytest.approx(exact, rel=2e-4)
    assert _volume(m) < exact


@settings(max_examples=50, deadline=None)
@given(st.floats(0.5, 20.0), st.floats(0.001, 0.2), st.floats(0.0, 1.0), st.floats(1.0, 1.6), st.floats(0.0, 1.0))
def test_graded_spacing(length, h_frac, at_frac, growth, width_frac):
    h = h_frac * length
    x = prim.graded(0.0, length, h, at=at_frac * length, width=width_frac * length, growth=growth)
    d = np.diff(x)
    assert x[0] == 0.0 and x[-1] == length
    assert np.all(d > 0)
    # each side is scaled by a factor within [1/(1 + growth), 1 + growth] to end exactly, so no
    # element is finer than h / 2.6, and neighbours differ by the growth factor, or at the join of
    # the two sides by the ratio of their scale factors
    assert d.min() > min(h, length) / 2.6
    ratio = np.maximum(d[1:] / d[:-1], d[:-1] / d[1:])
    assert np.all(ratio < (1.0 + growth) ** 2 + 1e-9)


def test_inverted_cell_is_rejected():
    m = prim.box("b", [0, 1], [0, 1], [0, 1])
    with pytest.raises(FEInputError, match="det J"):
        hex_geometry(m.points, m.cells[:, [4, 5, 6, 7, 0, 1, 2, 3]], True)


def test_spline_coupling_sets():
    m = prim.spline_coupling(sizes=prim.SplineMesh(h=0.5, fine_width=1.0, hz=1.25, z_fine_width=5.0, growth=1.8, h_max=5.0))
    assert m.bodies == ("hub", "sleeve")
    for body in m.bodies:
        for k in range(3):
            for s in ("flank", "fillet"):
                assert len(m.face_sets[f"{body}/tooth{k}/{s}"]) > 0
    assert "hub" in m.reference_points
    assert hex_geometry(m.points, m.cells, True).dx.min() > 0
