r"""Face load factors of ISO 6336-1: K_Hβ by method C and K_Fβ from K_Hβ.

Method C takes a linear load distribution over the face width :math:`b` for the effective equivalent
misalignment :math:`F_{\beta y}` and the mesh stiffness :math:`c_{\gamma\beta}`; with the mean line load
:math:`F_m/b`, :math:`F_m = F_t K_A K_\gamma K_v`:

.. math::
    K_{H\beta} = 1 + \frac{F_{\beta y} c_{\gamma\beta}}{2 F_m/b}\quad\Big(\frac{F_{\beta y} c_{\gamma\beta}}{F_m/b} \le 2\Big),
    \qquad K_{H\beta} = \sqrt{\frac{2 F_{\beta y} c_{\gamma\beta}}{F_m/b}}\quad (\text{otherwise}) \quad (F1)

(the first: contact over the whole face; the second: over the loaded length
:math:`b_{cal} = \sqrt{2 F_m/(F_{\beta y} c_{\gamma\beta}/b)}`; both give 2 at the switch).

.. math::
    F_{\beta y} = F_{\beta x} - y_\beta,\qquad
    F_{\beta x} = \max\big(1.33 B_1 f_{sh} + B_2 f_{ma},\ F_{\beta x,\min}\big),\qquad
    F_{\beta x,\min} = \max(0.005 F_m/b,\ 0.5 F_\beta) \quad (F2)

    f_{sh} = 0.023\,\frac{F_m}{b}\,\gamma,\qquad
    \gamma = \Big[\Big|1 + K'\frac{l\,s}{d_1^2}\Big(\frac{d_1}{d_{sh}}\Big)^4 - 0.3\Big| + 0.3\Big]\Big(\frac{b}{d_1}\Big)^2
    \quad (F3)

:math:`f_{sh}` [µm] is the pinion's bending and torsion deflection (spur and single helical; :math:`F_m/b` in N/mm),
:math:`f_{ma}` [µm] the mesh misalignment from manufacture and assembly (input), :math:`K'` the pinion arrangement
constant, :math:`l` the bearing span, :math:`s` the pinion offset from mid-span, :math:`d_{sh}` the shaft diameter
(ISO 6336-1 method C); :math:`B_1 = B_2 = 1` without helix modification (other values from ISO 6336-1's table for
the modification are inputs here). :math:`y_\beta` is the running-in allowance (:mod:`.running_in`).

.. math::
    K_{F\beta} = K_{H\beta}^{N_F},\qquad N_F = \frac{(b/h)^2}{1 + b/h + (b/h)^2},\qquad b/h \ge 3 \quad (F4)

with :math:`b/h` the smaller of :math:`b_1/h_1` and :math:`b_2/h_2` (tooth depths :math:`h`). (F4) reproduces
K_Fβ = 1.12803 of ISO/TR 6336-30 Example 1 and K_Fβ = 1.136 of a KISSsoft report (tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.rating.errors import check_range

__all__ = ["ShaftData", "FaceLoad", "face_load_factor", "face_load_exponent", "root_face_load_factor"]


@dataclass(frozen=True)
class ShaftData:
    """Input of method C [mm, µm]: mesh misalignment f_ma, helix-modification constants B_1, B_2, pinion shaft.

    Defaults: f_ma = 0 (assembly adjusted), no helix modification (B_1 = B_2 = 1), pinion centred between its
    bearings (s = 0, so K' does not enter and γ = (b/d_1)²).
    """

    mesh_misalignment: float = 0.0  # f_ma [µm]
    b1: float = 1.0
    b2: float = 1.0
    k_prime: float = 0.0  # K'
    bearing_span: float = 1.0  # l [mm]
    pinion_offset: float = 0.0  # s [mm]
    shaft_diameter: float = 1.0  # d_sh [mm]

    def __post_init__(self):
        check_range("shaft.mesh_misalignment", self.mesh_misalignment, 0.0)
        check_range("shaft.b1", self.b1, 0.0, 1.0)
        check_range("shaft.b2", self.b2, 0.0, 1.0)
        check_range("shaft.k_prime", self.k_prime, -2.0, 2.0)
        check_range("shaft.bearing_span", self.bearing_span, 0.0, lo_open=True)
        check_range("shaft.pinion_offset", self.pinion_offset, 0.0)
        check_range("shaft.shaft_diameter", self.shaft_diameter, 0.0, lo_open=True)


@dataclass(frozen=True)
class FaceLoad:
    """K_Hβ of method C with its intermediate values [µm, N/mm]."""

    k_h_beta: float
    f_sh: float
    f_beta_x: float
    y_beta: float
    f_beta_y: float
    mean_line_load: float  # F_m / b
    full_contact: bool  # first branch of (F1)


def face_load_factor(*, mean_line_load: float, pinion_diameter: float, face_width: float, c_gamma_beta: float,
                     total_helix_deviation: float, shaft: ShaftData, running_in) -> FaceLoad:
    """K_Hβ (F1)-(F3). ``running_in``: callable F_βx -> y_β [µm]; ``total_helix_deviation`` F_β [µm]."""
    wm = check_range("mean_line_load", mean_line_load, 0.0, lo_open=True)
    d1, b = pinion_diameter, face_width
    gamma = (abs(1.0 + shaft.k_prime * shaft.bearing_span * shaft.pinion_offset / d1 ** 2
                 * (d1 / shaft.shaft_diameter) ** 4 - 0.3) + 0.3) * (b / d1) ** 2
    f_sh = 0.023 * wm * gamma
    f_bx = max(1.33 * shaft.b1 * f_sh + shaft.b2 * shaft.mesh_misalignment, 0.005 * wm, 0.5 * total_helix_deviation)
    y_b = running_in(f_bx)
    f_by = max(f_bx - y_b, 0.0)
    x = f_by * c_gamma_beta / wm
    full = x <= 2.0
    k = 1.0 + 0.5 * x if full else math.sqrt(2.0 * x)
    return FaceLoad(k, f_sh, f_bx, y_b, f_by, wm, full)


def face_load_exponent(face_width: float, tooth_depth: float) -> float:
    """N_F of (F4) for b/h (b/h below 3 taken as 3)."""
    r = max(face_width / tooth_depth, 3.0)
    return r * r / (1.0 + r + r * r)


def root_face_load_factor(k_h_beta: float, face_widths: tuple[float, float],
                          tooth_depths: tuple[float, float]) -> float:
    """K_Fβ (F4) from K_Hβ, the face widths (b_1, b_2) and tooth depths (h_1, h_2) [mm]: the smaller b/h counts."""
    check_range("k_h_beta", k_h_beta, 1.0)
    i = min((0, 1), key=lambda j: face_widths[j] / tooth_depths[j])
    return k_h_beta ** face_load_exponent(face_widths[i], tooth_depths[i])
