r"""Gear accuracy grade to tolerances: ISO 1328-1:1995 (the edition ISO/TR 6336-30 applies).

For accuracy grade :math:`Q` (0..12) the tolerances [µm] are those of grade 5 times :math:`2^{(Q-5)/2}`, with
grade 5 given by (ISO 1328-1:1995, clause 6; :math:`m = m_n`, :math:`d` reference diameter, :math:`b` face width
in mm):

.. math::
    f_{pt} = 0.3(m + 0.4\sqrt d) + 4 \quad (A1),\qquad
    F_\alpha = 3.2\sqrt m + 0.22\sqrt d + 0.7 \quad (A2),\qquad
    f_{f\alpha} = 2.5\sqrt m + 0.17\sqrt d + 0.5 \quad (A3),

    f_{H\alpha} = 2\sqrt m + 0.14\sqrt d + 0.5 \quad (A4),\qquad
    F_\beta = 0.1\sqrt d + 0.63\sqrt b + 4.2 \quad (A5),\qquad
    f_{H\beta} = f_{f\beta} = 0.07\sqrt d + 0.45\sqrt b + 3 \quad (A6).

The 1995 edition evaluates (A1)-(A6) with the geometric mean of the limits of the size range that holds
:math:`m`, :math:`d`, :math:`b` (ranges below) and rounds the result: to 0.1 µm below 10 µm, to 1 µm from
10 µm on. The base pitch deviation used by ISO 6336-1 is :math:`f_{pb} = f_{pt}\cos\alpha_t` (A7).
(A7) and the range/rounding rule reproduce the running-in allowances printed by a KISSsoft 03/2017 report
to 0.2 % (tests/test_kisssoft_nrel.py). ISO 1328-1:2013 uses other formulas and is not implemented.
"""

from __future__ import annotations

import math
from bisect import bisect_left
from dataclasses import dataclass

from tca.rating.errors import RatingInputError, check_range

__all__ = ["Tolerances", "tolerances", "EDITION"]

EDITION = "ISO 1328-1:1995"

_D_LIMITS = (5.0, 20.0, 50.0, 125.0, 280.0, 560.0, 1000.0, 1600.0, 2500.0, 4000.0, 6000.0, 8000.0, 10000.0)
_M_LIMITS = (0.5, 2.0, 3.5, 6.0, 10.0, 16.0, 25.0, 40.0, 70.0)
_B_LIMITS = (4.0, 10.0, 20.0, 40.0, 80.0, 160.0, 250.0, 400.0, 650.0, 1000.0)


@dataclass(frozen=True)
class Tolerances:
    """ISO 1328-1:1995 tolerances [µm] of one gear of accuracy grade ``grade``."""

    grade: int
    f_pt: float  # single pitch deviation
    f_pb: float  # base pitch deviation f_pt cos α_t (A7)
    F_alpha: float  # total profile deviation
    f_f_alpha: float  # profile form deviation
    f_H_alpha: float  # profile slope deviation
    F_beta: float  # total helix deviation
    f_H_beta: float  # helix slope deviation (= helix form f_fβ)


def _mean_of_range(key: str, value: float, limits: tuple[float, ...]) -> float:
    """Geometric mean of the ISO 1328-1:1995 size range holding ``value`` (a range includes its upper limit)."""
    if not limits[0] <= value <= limits[-1]:
        raise RatingInputError(key, value, f"in [{limits[0]:g}, {limits[-1]:g}] (the size ranges of {EDITION})")
    i = max(1, bisect_left(limits, value))
    return math.sqrt(limits[i - 1] * limits[i])


def _round(v: float) -> float:
    """ISO 1328-1:1995 rounding: 0.1 µm below 10 µm, 1 µm from 10 µm on."""
    return float(round(v)) if v >= 10.0 else round(v, 1)


def tolerances(grade: int, reference_diameter: float, normal_module: float, face_width: float,
               transverse_pressure_angle: float, *, range_means: bool = True) -> Tolerances:
    """Tolerances (A1)-(A7) of a gear [µm] from grade, d, m_n, b [mm] and α_t [rad].

    ``range_means=False`` evaluates the formulas at the actual sizes and does not round (the 1995 edition's tables use
    the range means, which is the default).
    """
    if isinstance(grade, bool) or int(grade) != grade or not 0 <= int(grade) <= 12:
        raise RatingInputError("accuracy_grade", grade, f"an integer in [0, 12] ({EDITION})")
    q = int(grade)
    check_range("reference_diameter", reference_diameter, 0.0, lo_open=True)
    if range_means:
        d = _mean_of_range("reference_diameter", reference_diameter, _D_LIMITS)
        m = _mean_of_range("normal_module", normal_module, _M_LIMITS)
        b = _mean_of_range("face_width", face_width, _B_LIMITS)
        rnd = _round
    else:
        d, m, b = reference_diameter, normal_module, face_width
        rnd = float
    s = 2.0 ** (0.5 * (q - 5))
    f_pt = rnd(s * (0.3 * (m + 0.4 * math.sqrt(d)) + 4.0))
    return Tolerances(
        grade=q,
        f_pt=f_pt,
        f_pb=f_pt * math.cos(transverse_pressure_angle),
        F_alpha=rnd(s * (3.2 * math.sqrt(m) + 0.22 * math.sqrt(d) + 0.7)),
        f_f_alpha=rnd(s * (2.5 * math.sqrt(m) + 0.17 * math.sqrt(d) + 0.5)),
        f_H_alpha=rnd(s * (2.0 * math.sqrt(m) + 0.14 * math.sqrt(d) + 0.5)),
        F_beta=rnd(s * (0.1 * math.sqrt(d) + 0.63 * math.sqrt(b) + 4.2)),
        f_H_beta=rnd(s * (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 3.0)),
    )
