r"""Richardson extrapolation of a quantity computed on a sequence of refined meshes.

For three meshes with element sizes :math:`h_1 > h_2 > h_3` in a constant ratio
:math:`r = h_1/h_2 = h_2/h_3` and values :math:`f_i = f + C h_i^p + \dots`, the observed order and
the extrapolated value are

.. math::
    p = \frac{\ln\left((f_1 - f_2)/(f_2 - f_3)\right)}{\ln r},\qquad
    f_\infty = f_3 + \frac{f_3 - f_2}{r^p - 1}.

The errors of the meshes are then :math:`|f_i - f_\infty|/|f_\infty|`. A sequence that does not
converge monotonically (the differences change sign) has no Richardson limit: we say so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.errors import InputError

__all__ = ["Richardson", "richardson"]


@dataclass(frozen=True)
class Richardson:
    """Observed order, extrapolated value and relative errors of each level."""

    order: float
    value: float
    errors: tuple[float, ...]


def richardson(h: list[float], f: list[float]) -> Richardson:
    """Extrapolate the last three of values f at element sizes h (decreasing, constant ratio)."""
    if len(h) != len(f) or len(h) < 3:
        raise InputError("refinements", len(h), "at least three sizes with one value each")
    h1, h2, h3 = h[-3:]
    f1, f2, f3 = f[-3:]
    if not (h1 > h2 > h3 > 0):
        raise InputError("refinements", (h1, h2, h3), "decreasing positive element sizes")
    r1, r2 = h1 / h2, h2 / h3
    if abs(r1 - r2) > 1e-6 * r1:
        raise InputError("refinements", (r1, r2), "a constant refinement ratio")
    d1, d2 = f1 - f2, f2 - f3
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        raise InputError("refinements", (f1, f2, f3), "monotonically converging values (no Richardson limit)")
    p = math.log(d1 / d2) / math.log(r1)
    value = f3 + (f3 - f2) / (r1**p - 1)
    errs = tuple(abs(fi - value) / abs(value) for fi in f)
    return Richardson(p, value, errs)
