r"""Tooth root strength of ISO 6336-3, method B: root stress and the factors of its limit.

The form factor :math:`Y_F` and the stress correction factor :math:`Y_S` (load at the outer point of single pair
contact) and the notch parameter :math:`q_s = s_{Fn}/(2\rho_F)` are inputs: gearfe computes them from the generated
tooth (``tca.iso6336`` / ``root_stress``). With :math:`F_t` at the reference circle and :math:`b` the gear's
face width (a wider gear counts at most one module beyond the mate on each side):

.. math::
    \sigma_{F0} = \frac{F_t}{b\,m_n} Y_F Y_S Y_\beta Y_B Y_{DT},\qquad
    \sigma_F = \sigma_{F0} K_A K_\gamma K_v K_{F\beta} K_{F\alpha} \quad (B1)

    Y_\beta = 1 - \varepsilon_\beta\,\frac{\beta}{120°}\quad (\varepsilon_\beta \to 1 \text{ above } 1,\ \beta \to 30° \text{ above } 30°)
    \quad (B2)

    Y_B = 1\ (s_R/h_t \ge 1.2),\quad 1.6\ln\frac{2.242\,h_t}{s_R}\ (0.5 < s_R/h_t < 1.2);\qquad
    \text{internal: } 1\ (s_R/m_n \ge 3.5),\ 1.15\ln\frac{8.324\,m_n}{s_R}\ (1.75 < s_R/m_n < 3.5) \quad (B3)

    Y_{DT} = 1\ (\varepsilon_{\alpha n} \le 2.05 \text{ or grade } > 4),\quad -0.666\,\varepsilon_{\alpha n} + 2.366\
    (2.05 < \varepsilon_{\alpha n} \le 2.5),\quad 0.7\ (\varepsilon_{\alpha n} > 2.5) \quad (B4)

Tooth root stress limit and safety:

.. math::
    \sigma_{FG} = \sigma_{F\lim} Y_{ST} Y_{NT} Y_{\delta relT} Y_{RrelT} Y_X Y_M,\quad Y_{ST} = 2,\quad
    \sigma_{FP} = \sigma_{FG}/S_{F\min},\quad S_F = \sigma_{FG}/\sigma_F \quad (B5)

    Y_{\delta relT} = \frac{1 + \sqrt{\rho'\chi^*}}{1 + \sqrt{\rho'\chi^*_T}},\quad
    \chi^* = \tfrac15(1 + 2q_s),\quad \chi^*_T = \tfrac15(1 + 2\cdot 2.5) \quad (B6)

with the slip-layer thickness :math:`\rho'` [mm] by material: GG 0.3124 (σ_B = 150) .. 0.3095 (σ_B = 300),
GGG (ferr.) 0.3095, NT/NV 0.1005, St 0.0833 (σ_S = 300) .. 0.0445 (σ_S = 400), V/GTS/GGG (perl., bai.)
0.0281, 0.0194, 0.0064, 0.0014 at σ_0.2 = 500, 600, 800, 1000 (linear between), Eh/IF 0.0030 (B7).

.. math::
    Y_{RrelT}\ (1 \le R_z \le 40):\ 1.674 - 0.529(R_z + 1)^{0.1}\ \text{(V, GGG perl./bai., Eh, IF)},\
    5.306 - 4.203(R_z + 1)^{0.01}\ \text{(St)},\ 4.299 - 3.259(R_z + 1)^{0.0058}\ \text{(GG, GGG ferr., NT, NV)};

    R_z < 1:\ 1.120,\ 1.070,\ 1.025 \quad (B8)

    Y_X = 1\ (m_n \le 5);\ 1.03 - 0.006m_n \,(\ge 0.85)\ \text{St, V, GGG, GTS};\
    1.05 - 0.01m_n \,(\ge 0.8)\ \text{Eh, IF, NT, NV};\ 1.075 - 0.015m_n \,(\ge 0.7)\ \text{GG, GGG ferr.} \quad (B9)

Static values for limited life (:mod:`.life`, L3): Y_RrelT = Y_X = 1, and

.. math::
    Y_{\delta relT,st} = \frac{1 + 0.93(Y_S - 1)(200/\sigma_S)^{1/4}}{1 + 0.93(200/\sigma_S)^{1/4}}\ \text{(St)},\quad
    \frac{1 + 0.82(Y_S - 1)(300/\sigma_{0.2})^{1/4}}{1 + 0.82(300/\sigma_{0.2})^{1/4}}\ \text{(V, GTS, GGG perl.)},

    0.44Y_S + 0.12\ \text{(Eh, IF)},\quad 0.20Y_S + 0.60\ \text{(NT, NV)},\quad 1\ \text{(GG, GGG ferr.)} \quad (B10)

:math:`Y_M` (mean stress factor) is an input: 1 for one-way bending, 0.7 for idlers and planets (reversed bending
of ISO 6336-5).
"""

from __future__ import annotations

import math

from tca.rating.errors import RatingInputError, check_range
from tca.rating.geometry import DEG
from tca.rating.materials import Material, MaterialKind

__all__ = ["helix_factor", "rim_factor", "deep_tooth_factor", "notch_sensitivity", "notch_sensitivity_static",
           "surface_factor", "size_factor", "slip_layer"]

_K = MaterialKind
_V_LIKE = frozenset({_K.V_CARBON, _K.V_ALLOY, _K.GTS, _K.GGG})
_HARD_ROOT = frozenset({_K.EH, _K.IF})
_NITRIDED = frozenset({_K.NT, _K.NV_NITRIDED, _K.NV_NITROCARBURIZED})
_IRON = frozenset({_K.GG, _K.GGG_FERRITIC})
_ST = frozenset({_K.ST, _K.ST_CAST})


def helix_factor(eps_beta: float, beta: float) -> float:
    """Y_β (B2)."""
    return 1.0 - min(eps_beta, 1.0) * min(beta / DEG, 30.0) / 120.0


def rim_factor(rim_thickness: float | None, tooth_depth: float, normal_module: float, internal: bool) -> float:
    """Y_B (B3); ``rim_thickness`` s_R [mm] or ``None`` (solid: 1)."""
    if rim_thickness is None:
        return 1.0
    s = check_range("rim_thickness", rim_thickness, 0.0, lo_open=True)
    if internal:
        r = s / normal_module
        if r >= 3.5:
            return 1.0
        check_range("rim_thickness/m_n", r, 1.75, lo_open=True, why="ISO 6336-3 Y_B for internal gears")
        return 1.15 * math.log(8.324 * normal_module / s)
    r = s / tooth_depth
    if r >= 1.2:
        return 1.0
    check_range("rim_thickness/h_t", r, 0.5, lo_open=True, why="ISO 6336-3 Y_B for external gears")
    return 1.6 * math.log(2.242 * tooth_depth / s)


def deep_tooth_factor(eps_alpha_n: float, accuracy_grade: int) -> float:
    """Y_DT (B4)."""
    if accuracy_grade > 4 or eps_alpha_n <= 2.05:
        return 1.0
    if eps_alpha_n <= 2.5:
        return -0.666 * eps_alpha_n + 2.366
    return 0.7


def _interp(x: float, xs: tuple[float, ...], ys: tuple[float, ...], key: str) -> float:
    if not xs[0] <= x <= xs[-1]:
        raise RatingInputError(key, x, f"in [{xs[0]:g}, {xs[-1]:g}] MPa (the table of ρ' in ISO 6336-3)")
    for i in range(1, len(xs)):
        if x <= xs[i]:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return ys[-1]


def slip_layer(material: Material) -> float:
    """ρ' [mm] (B7)."""
    k = material.kind
    if k in _HARD_ROOT:
        return 0.0030
    if k in _NITRIDED:
        return 0.1005
    if k is _K.GGG_FERRITIC:
        return 0.3095
    if k is _K.GG:
        if material.tensile_strength is None:
            raise RatingInputError("material.tensile_strength", None, "σ_B [MPa] of the grey cast iron (ρ', ISO 6336-3)")
        return _interp(material.tensile_strength, (150.0, 300.0), (0.3124, 0.3095), "material.tensile_strength")
    if material.yield_strength is None:
        raise RatingInputError("material.yield_strength", None, f"σ_S or σ_0.2 [MPa] of {k.value} (ρ', ISO 6336-3)")
    if k in _ST:
        return _interp(material.yield_strength, (300.0, 400.0), (0.0833, 0.0445), "material.yield_strength")
    return _interp(material.yield_strength, (500.0, 600.0, 800.0, 1000.0), (0.0281, 0.0194, 0.0064, 0.0014),
                   "material.yield_strength")


def notch_sensitivity(material: Material, notch_parameter: float) -> float:
    """Y_δrelT (B6) at the reference point, for q_s = ``notch_parameter``."""
    q = check_range("notch_parameter", notch_parameter, 1.0, 8.0, hi_open=True, why="ISO 6336-3: 1 <= q_s < 8")
    rho = slip_layer(material)
    return (1.0 + math.sqrt(rho * 0.2 * (1.0 + 2.0 * q))) / (1.0 + math.sqrt(rho * 1.2))


def notch_sensitivity_static(material: Material, stress_correction: float) -> float:
    """Y_δrelT,st (B10) for Y_S = ``stress_correction``."""
    k, ys = material.kind, stress_correction
    if k in _HARD_ROOT:
        return 0.44 * ys + 0.12
    if k in _NITRIDED:
        return 0.20 * ys + 0.60
    if k in _IRON:
        return 1.0
    if material.yield_strength is None:
        raise RatingInputError("material.yield_strength", None, f"σ_S or σ_0.2 [MPa] of {k.value} (static Y_δrelT)")
    if k in _ST:
        f = 0.93 * (200.0 / material.yield_strength) ** 0.25
    else:
        f = 0.82 * (300.0 / material.yield_strength) ** 0.25
    return (1.0 + f * (ys - 1.0)) / (1.0 + f)


def surface_factor(material: Material, rz_root: float) -> float:
    """Y_RrelT (B8) for the root roughness Rz [µm]."""
    rz = check_range("root_roughness", rz_root, 0.0, 40.0, why="ISO 6336-3: Y_RrelT for Rz <= 40 µm")
    k = material.kind
    if k in _ST:
        return 1.070 if rz < 1.0 else 5.306 - 4.203 * (rz + 1.0) ** 0.01
    if k in _IRON or k in _NITRIDED:
        return 1.025 if rz < 1.0 else 4.299 - 3.259 * (rz + 1.0) ** 0.0058
    return 1.120 if rz < 1.0 else 1.674 - 0.529 * (rz + 1.0) ** 0.1


def size_factor(material: Material, normal_module: float) -> float:
    """Y_X (B9)."""
    m = normal_module
    if m <= 5.0:
        return 1.0
    k = material.kind
    if k in _HARD_ROOT or k in _NITRIDED:
        return max(1.05 - 0.01 * m, 0.8)
    if k in _IRON:
        return max(1.075 - 0.015 * m, 0.7)
    return max(1.03 - 0.006 * m, 0.85)
