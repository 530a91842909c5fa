r"""Surface durability (pitting) of ISO 6336-2, method B: contact stress and the factors of its limit.

Contact stress at the pitch point and at the inner points of single pair contact (:math:`F_t` at the reference
circle, :math:`d_1`, :math:`b` the common face width, :math:`u = z_2/z_1`, :math:`\kappa = +1` external, -1 internal):

.. math::
    \sigma_{H0} = Z_H Z_E Z_\varepsilon Z_\beta \sqrt{\frac{F_t}{d_1 b}\,\frac{u + \kappa}{u}} \quad (H1)

    \sigma_{H1,2} = Z_{B,D}\,\sigma_{H0}\sqrt{K_A K_\gamma K_v K_{H\beta} K_{H\alpha}} \quad (H2)

    Z_H = \sqrt{\frac{2\cos\beta_b\cos\alpha_{wt}}{\cos^2\alpha_t\sin\alpha_{wt}}} \quad (H3),\qquad
    Z_E = \sqrt{\frac{1}{\pi\big(\frac{1 - \nu_1^2}{E_1} + \frac{1 - \nu_2^2}{E_2}\big)}} \quad (H4)

    Z_\varepsilon = \sqrt{\frac{4 - \varepsilon_\alpha}{3}(1 - \varepsilon_\beta) + \frac{\varepsilon_\beta}{\varepsilon_\alpha}}
    \ (\varepsilon_\beta < 1),\qquad Z_\varepsilon = \sqrt{1/\varepsilon_\alpha}\ (\varepsilon_\beta \ge 1) \quad (H5)

    Z_\beta = \frac{1}{\sqrt{\cos\beta}} \quad (H6)

Single pair contact factors from the radii of curvature one base pitch inside the tips (ISO's :math:`M_1, M_2`),
written with the pinion radius :math:`\rho_1` and the wheel radius :math:`\rho_2 = T_1T_2 - \rho_1` (external) or
:math:`\rho_1 + (\rho_{C2} - \rho_{C1})` (internal) at that point, :math:`\rho_C` at the pitch point:

.. math::
    M_{1,2} = \sqrt{\frac{\rho_{C1}\rho_{C2}}{\rho_1\rho_2}},\quad
    \rho_1 = \rho_{a1} - p_{bt}\ (M_1),\quad \rho_2 = \rho_{a2} - p_{bt}\ (M_2,\ \text{external}) \quad (H7)

    Z_{B,D} = \max(1, M_{1,2})\ (\varepsilon_\beta = 0),\quad
    \max\big(1, M - \varepsilon_\beta(M - 1)\big)\ (0 < \varepsilon_\beta < 1),\quad 1\ (\varepsilon_\beta \ge 1);\quad
    Z_D = 1 \text{ for an internal wheel} \quad (H8)

(H7) is ISO's :math:`M_1 = \tan\alpha_{wt}/\sqrt{[\sqrt{d_{a1}^2/d_{b1}^2 - 1} - 2\pi/z_1][\sqrt{d_{a2}^2/d_{b2}^2 - 1}
- (\varepsilon_\alpha - 1)2\pi/z_2]}` for external pairs (and its mirror :math:`M_2`).

Pitting stress limit and safety (:math:`S_{H\min}` the required safety):

.. math::
    \sigma_{HG} = \sigma_{H\lim} Z_{NT} Z_L Z_v Z_R Z_W Z_X,\qquad \sigma_{HP} = \sigma_{HG}/S_{H\min},\qquad
    S_H = \sigma_{HG}/\sigma_H \quad (H9)

    Z_L = C_{ZL} + \frac{4(1 - C_{ZL})}{(1.2 + 134/\nu_{40})^2},\qquad
    Z_v = C_{Zv} + \frac{2(1 - C_{Zv})}{\sqrt{0.8 + 32/v}},\qquad C_{Zv} = C_{ZL} + 0.02 \quad (H10)

    C_{ZL} = 0.83\ (\sigma_{H\lim} < 850),\quad \frac{\sigma_{H\lim}}{4375} + 0.6357\ (850 \le \sigma_{H\lim} \le 1200),
    \quad 0.91\ (\sigma_{H\lim} > 1200) \quad (H11)

    Z_R = \Big(\frac{3}{R_{z10}}\Big)^{C_{ZR}},\quad R_{z10} = \frac{R_{z1} + R_{z2}}{2}\Big(\frac{10}{\rho_{red}}\Big)^{1/3},\quad
    C_{ZR} = 0.15\ (<850),\ 0.32 - 0.0002\sigma_{H\lim}\ (850..1200),\ 0.08\ (>1200) \quad (H12)

    Z_W = 1.2 - \frac{HB - 130}{1700}\ \ (130 \le HB \le 470;\ 1.2 \text{ below}, 1.0 \text{ above}) \quad (H13)

:math:`\nu_{40}` [mm²/s], :math:`v` the circumferential speed at the reference circle [m/s], :math:`R_z` the flank
roughness [µm], :math:`\rho_{red}` (G9) [mm]; (H10)-(H12) take the lower :math:`\sigma_{H\lim}` of the two
materials and hold for both gears of the pair (as the KISSsoft report of the tests applies them). (H13) applies to a through-hardened gear meshing with a
surface-hardened mate (otherwise Z_W = 1); it is the hardness-only form (the form of ISO 6336-2 that also weighs
the mate's roughness is not implemented). Z_X = 1 (ISO 6336-2 gives no size effect for the flank). For limited
life the product Z_L Z_v Z_R goes to 1 at the static point (:mod:`.life`, L3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.rating.errors import check_range
from tca.rating.geometry import PairGeometry

__all__ = ["ContactFactors", "contact_factors", "nominal_contact_stress", "lubricant_factors", "roughness_factor",
           "work_hardening_factor", "elasticity_factor"]


@dataclass(frozen=True)
class ContactFactors:
    """Z_H, Z_E, Z_ε, Z_β and the single pair contact factors of a pair (H3)-(H8)."""

    z_h: float
    z_e: float
    z_eps: float
    z_beta: float
    m1: float
    m2: float
    z_b: float
    z_d: float


def elasticity_factor(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Z_E (H4) [sqrt(MPa)]."""
    return math.sqrt(1.0 / (math.pi * ((1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2)))


def _single_contact(m: float, eps_beta: float) -> float:
    if eps_beta >= 1.0:
        return 1.0
    return max(1.0, m - eps_beta * (m - 1.0))


def contact_factors(geom: PairGeometry, e: tuple[float, float], nu: tuple[float, float]) -> ContactFactors:
    """(H3)-(H8) for ``geom`` and the elastic constants (E [MPa], ν) of pinion and wheel."""
    at, awt, bb = geom.transverse_pressure_angle, geom.working_pressure_angle, geom.base_helix_angle
    z_h = math.sqrt(2.0 * math.cos(bb) * math.cos(awt) / (math.cos(at) ** 2 * math.sin(awt)))
    z_e = elasticity_factor(e[0], nu[0], e[1], nu[1])
    ea, eb = geom.eps_alpha, geom.eps_beta
    if eb < 1.0:
        z_eps = math.sqrt((4.0 - ea) / 3.0 * (1.0 - eb) + eb / ea)
    else:
        z_eps = math.sqrt(1.0 / ea)
    z_beta = 1.0 / math.sqrt(math.cos(geom.helix_angle))
    # (H7) along the line of action, radii of curvature of the transverse profiles
    rc1, rc2 = geom.pitch_curvature
    ra1, ra2 = geom.tip_curvature
    pbt = geom.transverse_base_pitch
    if geom.internal:
        r1 = ra1 - pbt
        m1 = math.sqrt(rc1 * rc2 / (r1 * (r1 + rc2 - rc1)))
        m2 = 1.0
    else:
        t1t2 = rc1 + rc2
        r1 = ra1 - pbt
        m1 = math.sqrt(rc1 * rc2 / (r1 * (t1t2 - r1)))
        r2 = ra2 - pbt
        m2 = math.sqrt(rc1 * rc2 / (r2 * (t1t2 - r2)))
    z_b = _single_contact(m1, eb)
    z_d = 1.0 if geom.internal else _single_contact(m2, eb)
    return ContactFactors(z_h, z_e, z_eps, z_beta, m1, m2, z_b, z_d)


def nominal_contact_stress(geom: PairGeometry, f_t: float, cf: ContactFactors) -> float:
    """σ_H0 (H1) [MPa] for the nominal tangential force ``f_t`` [N] at the reference circle."""
    u = geom.gear_ratio
    return cf.z_h * cf.z_e * cf.z_eps * cf.z_beta * math.sqrt(
        f_t / (geom.reference_diameter[0] * geom.common_face_width) * (u + geom.kappa) / u)


def _c_zl(sigma_h_lim: float) -> float:
    if sigma_h_lim < 850.0:
        return 0.83
    if sigma_h_lim <= 1200.0:
        return sigma_h_lim / 4375.0 + 0.6357
    return 0.91


def lubricant_factors(sigma_h_lim: float, viscosity_40: float, v: float) -> tuple[float, float]:
    """(Z_L, Z_v) (H10), (H11) for ν40 [mm²/s] and circumferential speed v [m/s]."""
    check_range("viscosity_40", viscosity_40, 0.0, lo_open=True)
    check_range("circumferential_speed", v, 0.0, lo_open=True)
    c_zl = _c_zl(sigma_h_lim)
    c_zv = c_zl + 0.02
    z_l = c_zl + 4.0 * (1.0 - c_zl) / (1.2 + 134.0 / viscosity_40) ** 2
    z_v = c_zv + 2.0 * (1.0 - c_zv) / math.sqrt(0.8 + 32.0 / v)
    return z_l, z_v


def roughness_factor(sigma_h_lim: float, rz_pinion: float, rz_wheel: float, relative_curvature: float) -> float:
    """Z_R (H12) for the flank roughnesses Rz [µm] and ρ_red [mm]."""
    check_range("flank_roughness", rz_pinion, 0.0, lo_open=True)
    check_range("flank_roughness", rz_wheel, 0.0, lo_open=True)
    rz10 = 0.5 * (rz_pinion + rz_wheel) * (10.0 / relative_curvature) ** (1.0 / 3.0)
    if sigma_h_lim < 850.0:
        c = 0.15
    elif sigma_h_lim <= 1200.0:
        c = 0.32 - 0.0002 * sigma_h_lim
    else:
        c = 0.08
    return (3.0 / rz10) ** c


def work_hardening_factor(brinell_hardness: float) -> float:
    """Z_W (H13) of a through-hardened gear [HB] meshing with a surface-hardened mate."""
    hb = float(brinell_hardness)
    if hb < 130.0:
        return 1.2
    if hb > 470.0:
        return 1.0
    return 1.2 - (hb - 130.0) / 1700.0
