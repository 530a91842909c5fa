r"""Tooth stiffness of ISO 6336-1 (clause 9, method B): single stiffness c' and mesh stiffness c_γα, c_γβ.

Theoretical single stiffness of a solid steel spur pair from the virtual numbers of teeth :math:`z_{n1}, z_{n2}`
(for an internal wheel :math:`1/z_{n2} = 0`) and the profile shifts:

.. math::
    q' = C_1 + \frac{C_2}{z_{n1}} + \frac{C_3}{z_{n2}} + C_4 x_1 + C_5\frac{x_1}{z_{n1}} + C_6 x_2
         + C_7\frac{x_2}{z_{n2}} + C_8 x_1^2 + C_9 x_2^2,\qquad c'_{th} = \frac1{q'} \quad (S1)

with :math:`C_1..C_9` = 0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182
[mm µm/N]. The single stiffness and the mesh stiffness [N/(mm µm)]:

.. math::
    c' = c'_{th} C_M C_R C_B \cos\beta\,\frac{E}{E_{st}}\,
         \min\Big(1, \big(\tfrac{F_t K_A/b}{100}\big)^{0.25}\Big) \quad (S2)

    C_M = 0.8,\qquad C_R = 1 + \frac{\ln(b_s/b)}{5 e^{s_R/(5 m_n)}} \ (\text{solid: } 1),\qquad
    C_B = \big[1 + 0.5(1.2 - h_{fP}/m_n)\big]\big[1 - 0.02(20° - \alpha_n)\big] \quad (S3)

    c_{\gamma\alpha} = c'(0.75\varepsilon_\alpha + 0.25),\qquad c_{\gamma\beta} = 0.85\,c_{\gamma\alpha} \quad (S4)

:math:`E = 2E_1E_2/(E_1 + E_2)`, :math:`E_{st} = 206000` MPa; :math:`b_s/b` is clamped to [0.2, 1.2] and
:math:`s_R/m_n \ge 1`. (S1)-(S4) reproduce the c'_th, c', c_γα, c_γβ of ISO/TR 6336-30 Example 1 to 1e-5 and the c'
of two KISSsoft-rated spur planetary stages (sun-planet and planet-ring) to 0.1 % (tests). The load correction
of (S2) for F_t K_A/b < 100 N/mm is not covered by those sources.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.rating.errors import RatingWarning, check_range
from tca.rating.geometry import DEG, PairGeometry
from tca.rating.materials import STEEL_YOUNGS_MODULUS

__all__ = ["GearBody", "MeshStiffness", "mesh_stiffness", "theoretical_single_stiffness"]

_C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


@dataclass(frozen=True)
class GearBody:
    """Web/rim proportions of the wheel body for C_R (S3): ``web_ratio`` b_s/b, ``rim_ratio`` s_R/m_n.

    Both ``None`` (default): solid disc, C_R = 1.
    """

    web_ratio: float | None = None
    rim_ratio: float | None = None

    def __post_init__(self):
        if (self.web_ratio is None) != (self.rim_ratio is None):
            from tca.rating.errors import RatingInputError

            raise RatingInputError("gear_body", (self.web_ratio, self.rim_ratio), "both b_s/b and s_R/m_n, or neither")
        if self.web_ratio is not None:
            check_range("gear_body.web_ratio", self.web_ratio, 0.0, lo_open=True)
            check_range("gear_body.rim_ratio", self.rim_ratio, 0.0, lo_open=True)


@dataclass(frozen=True)
class MeshStiffness:
    """Single and mesh stiffness [N/(mm µm)] with the factors of (S2), (S3)."""

    c_th: float
    c_prime: float
    c_gamma_alpha: float
    c_gamma_beta: float
    c_m: float
    c_r: float
    c_b: float
    load_correction: float
    warnings: tuple[RatingWarning, ...] = ()


def theoretical_single_stiffness(zn1: float, zn2: float | None, x1: float, x2: float) -> float:
    """c'_th (S1) [N/(mm µm)]; ``zn2=None`` for an internal wheel (1/z_n2 = 0)."""
    r2 = 0.0 if zn2 is None else 1.0 / zn2
    q = (_C[0] + _C[1] / zn1 + _C[2] * r2 + _C[3] * x1 + _C[4] * x1 / zn1 + _C[5] * x2 + _C[6] * x2 * r2
         + _C[7] * x1 * x1 + _C[8] * x2 * x2)
    return 1.0 / q


def mesh_stiffness(geom: PairGeometry, line_load: float, *, e1: float = STEEL_YOUNGS_MODULUS,
                   e2: float = STEEL_YOUNGS_MODULUS, body: GearBody = GearBody()) -> MeshStiffness:
    """c', c_γα, c_γβ (S1)-(S4) of ``geom``; ``line_load`` = F_t K_A / b [N/mm]."""
    check_range("line_load", line_load, 0.0, lo_open=True)
    x1, x2 = geom.profile_shift
    warnings = []
    if not -0.5 <= x1 + x2 <= 2.0:
        warnings.append(RatingWarning("stiffness_shift_range", f"x1 + x2 = {x1 + x2:.3f} outside [-0.5, 2]: the "
                                      "regression (S1) of ISO 6336-1 for c'_th is extrapolated"))
    zn1, zn2 = geom.virtual_teeth
    c_th = theoretical_single_stiffness(zn1, None if geom.internal else zn2, x1, x2)
    if body.web_ratio is None:
        c_r = 1.0
    else:
        bs = min(max(body.web_ratio, 0.2), 1.2)
        sr = max(body.rim_ratio, 1.0)
        c_r = 1.0 + math.log(bs) / (5.0 * math.exp(sr / 5.0))
    c_b = (1.0 + 0.5 * (1.2 - geom.dedendum)) * (1.0 - 0.02 * (20.0 - geom.pressure_angle / DEG))
    e = 2.0 * e1 * e2 / (e1 + e2)
    load = min(1.0, (line_load / 100.0) ** 0.25)
    c = c_th * 0.8 * c_r * c_b * math.cos(geom.helix_angle) * e / STEEL_YOUNGS_MODULUS * load
    cga = c * (0.75 * geom.eps_alpha + 0.25)
    return MeshStiffness(c_th, c, cga, 0.85 * cga, 0.8, c_r, c_b, load, tuple(warnings))
