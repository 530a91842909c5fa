r"""Dynamic factor K_v of ISO 6336-1, method B (resonance ratio and the four speed ranges).

Reduced mass of the pair on the line of action, per unit face width [kg/mm], from the mean diameters
:math:`d_m = (d_a + d_f)/2`, base diameters :math:`d_b`, bore ratios :math:`q = d_i/d_m` and densities
:math:`\rho` [kg/mm³] (solid or bored disc bodies):

.. math::
    m_i^* = \frac{\pi}{8}\,\rho_i\,\frac{d_{mi}^4}{d_{bi}^2}\,(1 - q_i^4) \quad (D1)

    m_{red} = \frac{m_1^* m_2^*}{m_1^* + m_2^*}\ \text{(pair)},\qquad
    m_{red} = \frac{m_P^* m_S^*}{m_S^* + N_p m_P^*}\ \text{(sun-planet, } N_p \text{ planets)},\qquad
    m_{red} = m_P^*\ \text{(planet-ring)} \quad (D2)

Resonance speed of the pinion [1/min] and resonance ratio (:math:`c_{\gamma\alpha}` in N/(mm µm)):

.. math::
    n_{E1} = \frac{30000}{\pi z_1}\sqrt{\frac{c_{\gamma\alpha}}{m_{red}}},\qquad N = \frac{n_1}{n_{E1}} \quad (D3)

With :math:`w = F_t K_A K_\gamma / b` [N/mm], the effective deviations :math:`f_{pb,eff} = f_{pb} - y_\alpha`,
:math:`f_{f\alpha,eff} = f_{f\alpha} - y_f` (larger of pinion and wheel, ISO 1328-1:1995) and the tip relief
:math:`C_a`:

.. math::
    B_p = \frac{c' f_{pb,eff}}{w},\quad B_f = \frac{c' f_{f\alpha,eff}}{w},\quad
    B_k = \Big|1 - \frac{c' C_a}{w}\Big| \quad (D4)

    N_S = 0.5 + 0.35\sqrt{w/100}\ (w < 100),\quad N_S = 0.85\ (w \ge 100) \quad (D5)

    N \le N_S:\ K_v = N(C_{v1}B_p + C_{v2}B_f + C_{v3}B_k) + 1 \quad (D6)

    N_S < N \le 1.15:\ K_v = C_{v1}B_p + C_{v2}B_f + C_{v4}B_k + 1 \quad (D7)

    1.15 < N < 1.5:\ K_v = K_{v(N=1.5)} + \frac{K_{v(N=1.15)} - K_{v(N=1.5)}}{0.35}(1.5 - N) \quad (D8)

    N \ge 1.5:\ K_v = C_{v5}B_p + C_{v6}B_f + C_{v7} \quad (D9)

.. math::
    1 < \varepsilon_\gamma \le 2:\ C_{v1..7} = 0.32,\ 0.34,\ 0.23,\ 0.90,\ 0.47,\ 0.47,\ 0.75;\qquad
    \varepsilon_\gamma > 2:\ C_{v1} = 0.32,\ C_{v2} = \frac{0.57}{\varepsilon_\gamma - 0.3},\
    C_{v3} = \frac{0.096}{\varepsilon_\gamma - 1.56},\ C_{v4} = \frac{0.57 - 0.05\varepsilon_\gamma}{\varepsilon_\gamma - 1.44},

    C_{v5} = 0.47,\ C_{v6} = \frac{0.12}{\varepsilon_\gamma - 1.74};\qquad
    C_{v7} = 0.75\ (\varepsilon_\gamma \le 1.5),\ 0.125\sin[\pi(\varepsilon_\gamma - 2)] + 0.875\ (1.5 < \varepsilon_\gamma \le 2.5),\
    1\ (\varepsilon_\gamma > 2.5) \quad (D10)

Without specified tip relief, :math:`C_a` is the running-in amount
:math:`C_{ay} = \frac1{18}(\sigma_{H\lim}/97 - 18.45)^2 + 1.5` µm of each gear (mean of the two) (D11).
ISO 6336-1:2006's numbering of these, as quoted in the comments of the open-source ``gfsReboucas/Drivetrain``
(``ISO_6336.m``; the standard's text itself was not available): (D1), (D2) clause 6.5.9, Eq. (30); (D3) Eqs. (6), (9);
(D4) Eqs. (15)-(17); (D5) Eqs. (11), (12); (D6) clause 6.5.4, Eqs. (13), (14); (D7) clause 6.5.5, Eq. (20); (D9)
clause 6.5.6, Eq. (21); (D8) clause 6.5.7, Eq. (22); (D10) Table 8.
(D1)-(D11) reproduce the m_red, n_E1, N and K_v of a KISSsoft 03/2017 report (parallel helical and planetary stages)
and K_v = 1.003 of ISO/TR 6336-30 Example 1 (tests). The main resonance range (D7) is rated with a warning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

from tca.rating.errors import RatingInputError, RatingWarning, check_range
from tca.rating.geometry import PairGeometry

__all__ = ["MeshKind", "DynamicFactor", "ToothDeviations", "reduced_mass", "running_in_tip_relief", "dynamic_factor",
           "cv_coefficients"]


class MeshKind(str, Enum):
    """Which reduced mass (D2) applies."""

    PAIR = "pair"
    SUN_PLANET = "sun-planet"
    PLANET_RING = "planet-ring"


@dataclass(frozen=True)
class DynamicFactor:
    """K_v of method B with its intermediate values."""

    k_v: float
    speed_range: str  # "subcritical", "main resonance", "intermediate", "supercritical"
    resonance_ratio: float  # N
    resonance_speed: float  # n_E1 [1/min]
    reduced_mass: float  # m_red [kg/mm]
    n_s: float
    b_p: float
    b_f: float
    b_k: float
    cv: tuple[float, ...]  # C_v1..C_v7
    warnings: tuple[RatingWarning, ...] = ()


@dataclass(frozen=True)
class ToothDeviations:
    """What excites the mesh in (D4) [µm]: effective base pitch and profile form deviations, tip relief C_a."""

    f_pb_eff: float  # f_pb - y_α
    f_falpha_eff: float  # f_fα - y_f
    tip_relief: float  # C_a


def _disc_mass(rho: float, dm: float, db: float, di: float) -> float:
    q = di / dm
    if not 0.0 <= q < 1.0:
        raise RatingInputError("bore_diameter", di, f"< mean diameter {dm:.4f} mm")
    return math.pi / 8.0 * rho * dm ** 4 / db ** 2 * (1.0 - q ** 4)


def reduced_mass(geom: PairGeometry, densities: tuple[float, float], mesh: MeshKind = MeshKind.PAIR,
                 planets: int = 1, sun_is_pinion: bool = True) -> float:
    """m_red [kg/mm] by (D1), (D2). Sun-planet: ``sun_is_pinion`` says which gear is the sun (the pinion is the
    gear with fewer teeth, which may be the planet); planet-ring: the pinion is the planet."""
    mesh = MeshKind(mesh)
    m1 = _disc_mass(densities[0], geom.mean_diameter[0], geom.base_diameter[0], geom.bore_diameter[0])
    m2 = _disc_mass(densities[1], geom.mean_diameter[1], geom.base_diameter[1], geom.bore_diameter[1])
    if mesh is MeshKind.PAIR:
        return m1 * m2 / (m1 + m2)
    if isinstance(planets, bool) or int(planets) != planets or planets < 1:
        raise RatingInputError("planets", planets, "an integer >= 1")
    if mesh is MeshKind.SUN_PLANET:
        sun, planet = (m1, m2) if sun_is_pinion else (m2, m1)
        return sun * planet / (sun + planets * planet)
    if not geom.internal:
        raise RatingInputError("mesh", mesh.value, "'pair' or 'sun-planet' for an external pair")
    return m1  # the ring is taken as fixed: the planet alone


def running_in_tip_relief(sigma_h_lim: float) -> float:
    """C_ay [µm] (D11) of one gear."""
    return (sigma_h_lim / 97.0 - 18.45) ** 2 / 18.0 + 1.5


def cv_coefficients(eps_gamma: float) -> tuple[float, ...]:
    """C_v1..C_v7 (D10)."""
    e = eps_gamma
    if e <= 2.0:
        c = [0.32, 0.34, 0.23, 0.90, 0.47, 0.47]
    else:
        c = [0.32, 0.57 / (e - 0.3), 0.096 / (e - 1.56), (0.57 - 0.05 * e) / (e - 1.44), 0.47, 0.12 / (e - 1.74)]
    if e <= 1.5:
        c7 = 0.75
    elif e <= 2.5:
        c7 = 0.125 * math.sin(math.pi * (e - 2.0)) + 0.875
    else:
        c7 = 1.0
    return tuple(c + [c7])


def dynamic_factor(geom: PairGeometry, *, pinion_speed: float, line_load: float, c_prime: float,
                   c_gamma_alpha: float, reduced_mass: float, deviations: ToothDeviations) -> DynamicFactor:
    """K_v (D3)-(D10). ``pinion_speed`` n_1 [1/min] (relative to the carrier in a planetary stage),
    ``line_load`` w = F_t K_A K_γ / b [N/mm], stiffness [N/(mm µm)], ``reduced_mass`` [kg/mm], ``deviations`` and
    tip relief C_a [µm]."""
    f_pb_eff, f_falpha_eff, tip_relief = deviations.f_pb_eff, deviations.f_falpha_eff, deviations.tip_relief
    check_range("pinion_speed", pinion_speed, 0.0, lo_open=True)
    check_range("line_load", line_load, 0.0, lo_open=True)
    check_range("reduced_mass", reduced_mass, 0.0, lo_open=True)
    check_range("tip_relief", tip_relief, 0.0)
    n_e1 = 30000.0 / (math.pi * geom.teeth[0]) * math.sqrt(c_gamma_alpha / reduced_mass)
    n = pinion_speed / n_e1
    w = line_load
    b_p = c_prime * max(f_pb_eff, 0.0) / w
    b_f = c_prime * max(f_falpha_eff, 0.0) / w
    b_k = abs(1.0 - c_prime * tip_relief / w)
    n_s = 0.5 + 0.35 * math.sqrt(w / 100.0) if w < 100.0 else 0.85
    cv = cv_coefficients(geom.eps_gamma)
    cv1, cv2, cv3, cv4, cv5, cv6, cv7 = cv
    main = cv1 * b_p + cv2 * b_f + cv4 * b_k + 1.0  # (D7)
    sup = cv5 * b_p + cv6 * b_f + cv7  # (D9)
    warnings = []
    if n <= n_s:
        k_v, rng = n * (cv1 * b_p + cv2 * b_f + cv3 * b_k) + 1.0, "subcritical"
    elif n <= 1.15:
        k_v, rng = main, "main resonance"
        warnings.append(RatingWarning("main_resonance", f"resonance ratio N = {n:.3f} in the main resonance range "
                                      f"({n_s:.2f}, 1.15]: ISO 6336-1 advises against operation there; K_v (D7) is "
                                      "an estimate"))
    elif n < 1.5:
        k_v, rng = sup + (main - sup) / 0.35 * (1.5 - n), "intermediate"
    else:
        k_v, rng = sup, "supercritical"
    return DynamicFactor(k_v, rng, n, n_e1, reduced_mass, n_s, b_p, b_f, b_k, cv, tuple(warnings))
