"""Transfinite interpolation of a block from its boundary rows (mesher.tfi)."""

import numpy as np

from mesher.grading import uniform
from mesher.tfi import arc_fractions, tfi


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
