"""1D graded distributions and the transfinite interpolation of a block."""

import numpy as np
import pytest

from mesher.grading import SizeField, count, distribute, uniform
from mesher.tfi import arc_fractions, tfi
from tca.errors import InputError


def test_uniform_size_gives_equal_elements():
    # 10 mm at 0.7 mm: ceil(10 / 0.7) = 15 equal elements
    assert count(10.0, SizeField(0.7)) == 15
    f = distribute(10.0, SizeField(0.7))
    np.testing.assert_allclose(np.diff(f), 1 / 15, rtol=1e-12)


@pytest.mark.parametrize("focus", [0.0, 3.3, 7.0, 10.0])
def test_graded_elements_respect_target_size_and_growth(focus):
    h = SizeField(1.0, 0.1, focus, 1.25)
    x = 10.0 * distribute(10.0, h, pin=True)
    le = np.diff(x)
    # equidistribution of 1/h: each element is at most the largest target size on it
    # (0.2 % allowance: the integral of 1/h is a 2049-point trapezoid rule)
    hmax = np.maximum(h(x[:-1]), h(x[1:]))
    assert np.all(le <= hmax * 1.002)
    # neighbours differ by at most the growth ratio (5 % allowance for the rounding of counts at a pin)
    r = le[1:] / le[:-1]
    assert np.all(np.maximum(r, 1 / r) <= 1.25 * 1.05)
    # the focus is a node, and the elements touching it are within one growth step of the target
    k = int(np.argmin(np.abs(x - focus)))
    assert abs(x[k] - focus) < 1e-12
    touching = le[max(k - 1, 0):k + 1]
    assert np.all(touching <= 0.1 * 1.25 * 1.002)


def test_focus_near_an_end_is_served_by_the_end_node():
    # a focus 0.01 mm from the end (less than half the 0.1 mm target) must not create a sliver
    h = SizeField(1.0, 0.1, 9.99, 1.25)
    x = 10.0 * distribute(10.0, h, pin=True)
    assert np.diff(x).min() > 0.05
    assert not np.any(np.abs(x - 9.99) < 1e-12)


def test_size_field_rejects_bad_input():
    with pytest.raises(InputError, match="contact_size"):
        SizeField(1.0, 2.0, 0.0)
    with pytest.raises(InputError, match="growth"):
        SizeField(1.0, 0.5, 0.0, growth=5.0)


def _polar_rows(r0, r1, t0, t1, fi, fj):
    """Boundary rows of the annular sector r0..r1, t0..t1 in polar coordinates (r, theta)."""
    ej0 = np.stack([r0 + fi * (r1 - r0), np.full_like(fi, t0)], -1)
    ej1 = np.stack([r0 + fi * (r1 - r0), np.full_like(fi, t1)], -1)
    ei0 = np.stack([np.full_like(fj, r0), t0 + fj * (t1 - t0)], -1)
    ei1 = np.stack([np.full_like(fj, r1), t0 + fj * (t1 - t0)], -1)
    return ej0, ej1, ei0, ei1


def test_tfi_of_a_polar_rectangle_is_the_exact_polar_grid():
    fi = uniform(7) ** 1.5
    fj = uniform(5)
    rows = _polar_rows(30.0, 36.0, -0.1, 0.1, fi, fj)
    P = tfi(*rows)
    R, T = np.meshgrid(30.0 + 6.0 * fi, -0.1 + 0.2 * fj, indexing="ij")
    np.testing.assert_allclose(P[..., 0], R, atol=1e-12)
    np.testing.assert_allclose(P[..., 1], T, atol=1e-14)


def test_tfi_reproduces_differently_graded_boundaries_exactly():
    # a curved quad: bottom graded toward its end, top uniform, curved sides
    s = uniform(12)
    bottom = np.stack([10 * s**2, 0.5 * np.sin(np.pi * s)], -1)
    top = np.stack([10 * s, 5 + 0.3 * np.sin(2 * np.pi * s)], -1)
    t = uniform(6)
    left = np.stack([-0.4 * np.sin(np.pi * t), 5 * t], -1)
    right = np.stack([10 + 0.2 * np.sin(np.pi * t), 5 * t**1.3], -1)
    P = tfi(bottom, top, left, right)
    np.testing.assert_allclose(P[:, 0], bottom, atol=1e-13)
    np.testing.assert_allclose(P[:, -1], top, atol=1e-13)
    np.testing.assert_allclose(P[0, :], left, atol=1e-13)
    np.testing.assert_allclose(P[-1, :], right, atol=1e-13)
    # no folded cell: every quad keeps the orientation of the block
    a = P[:-1, :-1]
    b, c, d = P[1:, :-1], P[1:, 1:], P[:-1, 1:]
    cross = lambda u, v: u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]  # noqa: E731
    area = 0.5 * (cross(a, b) + cross(b, c) + cross(c, d) + cross(d, a))
    assert np.all(area > 0)
    np.testing.assert_allclose(arc_fractions(P[:, 0])[-1], 1.0)
