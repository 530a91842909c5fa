r"""One-dimensional node distributions driven by a target element size and a growth ratio.

A focus point :math:`x_c` with target size :math:`h_c`, growth ratio :math:`q` and largest size
:math:`h_{max}` define the size function

.. math:: h(x) = \min\left(h_{max},\ h_c + (q - 1)\,\max(|x - x_c| - w, 0)\right),

which is the continuous form of a geometric progression (element :math:`k` away from the focus
has size :math:`\approx h_c q^k`); :math:`w` (``plateau``, default 0) keeps the size :math:`h_c`
over a zone of half-width :math:`w` around the focus (e.g. a contact ellipse). Nodes are equidistributed in :math:`F(x) = \int_0^x dx'/h(x')`:
with :math:`n = \lceil F(L) \rceil` elements, :math:`x_k = F^{-1}(k F(L)/n)`, so every element is at
most its target size. A *pinned* focus is made a node exactly (each side gets its own count),
which places a node on the TCA contact point; a focus closer than :math:`h_c/2` to an end of the
edge is served by the end node instead (no sliver element).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.errors import InputError

__all__ = ["SizeField", "MinField", "distribute", "count", "uniform"]

_SAMPLES = 2049


@dataclass(frozen=True)
class SizeField:
    """Target element size [mm]: h_focus at `focus` growing by ratio `growth` up to h_max."""

    h_max: float
    h_focus: float | None = None
    focus: float | None = None  # position along the edge [mm]
    growth: float = 1.25
    plateau: float = 0.0  # half-width [mm] of the zone of size h_focus around the focus

    def __post_init__(self):
        if not (self.h_max > 0):
            raise InputError("mesh.coarse_size_mm", self.h_max, "> 0")
        if self.h_focus is not None and not (0 < self.h_focus <= self.h_max):
            raise InputError("mesh.contact_size_mm", self.h_focus, f"in (0, coarse size {self.h_max:g}] mm")
        if not (1.0 <= self.growth <= 3.0):
            raise InputError("mesh.growth", self.growth, "in [1, 3]")
        if not (self.plateau >= 0.0 and math.isfinite(self.plateau)):
            raise InputError("mesh.plateau_mm", self.plateau, ">= 0 mm")

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, float)
        if self.h_focus is None or self.focus is None:
            return np.full_like(x, self.h_max)
        d = np.maximum(np.abs(x - self.focus) - self.plateau, 0.0)
        return np.minimum(self.h_max, self.h_focus + (self.growth - 1.0) * d)


@dataclass(frozen=True)
class MinField:
    """The smallest of several size fields (several refined zones on one edge); ``focus`` and
    ``h_focus`` are the first field's (the node :func:`distribute` pins)."""

    fields: tuple

    def __call__(self, x) -> np.ndarray:
        return np.min([f(x) for f in self.fields], axis=0)

    @property
    def focus(self):
        return self.fields[0].focus

    @property
    def h_focus(self):
        return self.fields[0].h_focus


def _cumulative(length: float, h: SizeField):
    x = np.linspace(0.0, length, _SAMPLES)
    w = 1.0 / h(x)
    F = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(x))])
    return x, F


def count(length: float, h: SizeField | MinField, nmin: int = 1) -> int:
    """Number of elements needed on an edge of `length` [mm] for sizes at most h(x)."""
    if not (length > 0):
        raise InputError("edge length", length, "> 0 mm")
    _, F = _cumulative(length, h)
    return max(nmin, int(math.ceil(F[-1] - 1e-9)))


def uniform(n: int) -> np.ndarray:
    """Fractions 0..1 of n equal elements."""
    return np.linspace(0.0, 1.0, n + 1)


def distribute(length: float, h: SizeField | MinField, n: int | None = None, nmin: int = 1, pin: bool = False) -> np.ndarray:
    """Node fractions (n+1,) in [0, 1] of an edge of `length` [mm] graded by h; focus a node if `pin`."""
    if n is None:
        n = count(length, h, nmin)
    if n < 1:
        raise InputError("element count", n, ">= 1")
    x, F = _cumulative(length, h)
    c = h.focus if (pin and h.focus is not None) else None
    snap = 0.5 * (h.h_focus or 0.0)  # a focus closer than half its size to an end is served by the end node
    if c is None or c <= snap or c >= length - snap or n < 2:
        pos = np.interp(np.linspace(0.0, F[-1], n + 1), F, x)
    else:
        Fc = float(np.interp(c, x, F))
        n1 = min(max(int(round(n * Fc / F[-1])), 1), n - 1)
        left = np.interp(np.linspace(0.0, Fc, n1 + 1), F, x)
        right = np.interp(np.linspace(Fc, F[-1], n - n1 + 1), F, x)
        left[-1] = right[0] = c
        pos = np.concatenate([left, right[1:]])
    pos[0], pos[-1] = 0.0, length
    return pos / length
