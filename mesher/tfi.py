r"""Discrete transfinite interpolation (Coons patch) with boundary-parameter blending.

A logical quadrilateral block with node indices :math:`0 \le i \le n_i`, :math:`0 \le j \le n_j`
is bounded by four node rows: :math:`E_{j0}(i)` (j = 0), :math:`E_{j1}(i)` (j = n_j),
:math:`E_{i0}(j)` (i = 0) and :math:`E_{i1}(j)` (i = n_i), with matching corners. Each row has its
own normalized arclength parameters :math:`s_0, s_1` (along i) and :math:`t_0, t_1` (along j), so
opposite sides may be graded differently. The blending parameters of node (i, j) are the
intersection of the lines joining corresponding boundary nodes (Soni's algebraic grid
generation, Thompson et al., *Handbook of Grid Generation*, ch. 3):

.. math::
    \xi = \frac{s_0 + t_0 (s_1 - s_0)}{1 - (s_1 - s_0)(t_1 - t_0)},\qquad \eta = t_0 + \xi\,(t_1 - t_0),

and the node is the Coons patch

.. math::
    P = (1-\eta)E_{j0} + \eta E_{j1} + (1-\xi)E_{i0} + \xi E_{i1}
        - \big[(1-\xi)(1-\eta)P_{00} + \xi(1-\eta)P_{10} + (1-\xi)\eta P_{01} + \xi\eta P_{11}\big],

which reproduces all four boundary rows exactly. Applied in polar coordinates (r, θ) of a gear's
transverse section it keeps circular arcs (top land, rim) and radial lines exact. Every array may
carry leading batch dimensions (one block per axial level z).
"""

from __future__ import annotations

import numpy as np

__all__ = ["tfi", "arc_fractions"]


def arc_fractions(p: np.ndarray) -> np.ndarray:
    """Normalized cumulative chord length (..., n) of node rows p (..., n, d)."""
    seg = np.linalg.norm(np.diff(p, axis=-2), axis=-1)
    c = np.concatenate([np.zeros(seg.shape[:-1] + (1,)), np.cumsum(seg, axis=-1)], axis=-1)
    return c / c[..., -1:]


def tfi(ej0, ej1, ei0, ei1, metric=None) -> np.ndarray:
    """Block nodes (..., ni+1, nj+1, d) from its four boundary rows (see module docstring).

    ``metric`` optionally gives the same four rows in the coordinates in which arclength is
    measured (e.g. Cartesian when interpolating in polar coordinates).
    """
    m = (ej0, ej1, ei0, ei1) if metric is None else metric
    s0, s1 = arc_fractions(m[0])[..., :, None], arc_fractions(m[1])[..., :, None]
    t0, t1 = arc_fractions(m[2])[..., None, :], arc_fractions(m[3])[..., None, :]
    xi = (s0 + t0 * (s1 - s0)) / (1.0 - (s1 - s0) * (t1 - t0))
    eta = t0 + xi * (t1 - t0)
    xi, eta = xi[..., None], eta[..., None]
    P00, P10 = ej0[..., :1, None, :], ej0[..., -1:, None, :]
    P01, P11 = ej1[..., :1, None, :], ej1[..., -1:, None, :]
    return ((1 - eta) * ej0[..., :, None, :] + eta * ej1[..., :, None, :]
            + (1 - xi) * ei0[..., None, :, :] + xi * ei1[..., None, :, :]
            - ((1 - xi) * (1 - eta) * P00 + xi * (1 - eta) * P10 + (1 - xi) * eta * P01 + xi * eta * P11))
