r"""Transverse load factors of ISO 6336-1, method B: K_Hα and K_Fα.

With :math:`F_{tH} = F_t K_A K_\gamma K_v K_{H\beta}` and the mesh stiffness :math:`c_{\gamma\alpha}`:

.. math::
    \varepsilon_\gamma \le 2:\ K_{H\alpha} = K_{F\alpha} = \frac{\varepsilon_\gamma}{2}
        \Big(0.9 + 0.4\,\frac{c_{\gamma\alpha}(f_{pb} - y_\alpha)}{F_{tH}/b}\Big) \quad (T1)

    \varepsilon_\gamma > 2:\ K_{H\alpha} = K_{F\alpha} = 0.9 + 0.4\sqrt{\frac{2(\varepsilon_\gamma - 1)}{\varepsilon_\gamma}}
        \,\frac{c_{\gamma\alpha}(f_{pb} - y_\alpha)}{F_{tH}/b} \quad (T2)

limited by

.. math::
    1 \le K_{H\alpha} \le \frac{\varepsilon_\gamma}{\varepsilon_\alpha Z_\varepsilon^2},\qquad
    1 \le K_{F\alpha} \le \frac{\varepsilon_\gamma}{0.25\varepsilon_\alpha + 0.75} \quad (T3)

:math:`f_{pb}` is the larger base pitch deviation of pinion and wheel; where the larger profile form deviation
:math:`f_{f\alpha}` exceeds it, :math:`f_{f\alpha}` is used (T4) (this reproduces the K_Hα = 1.069 of a KISSsoft
03/2017 report to ISO 6336-1:2006, tests; the ISO text was not available to check the rule). :math:`y_\alpha` is the
running-in allowance for :math:`f_{pb}`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.rating.errors import check_range

__all__ = ["TransverseLoad", "transverse_load_factors"]


@dataclass(frozen=True)
class TransverseLoad:
    """K_Hα, K_Fα of method B; ``unlimited`` is the value of (T1)/(T2) before the limits (T3)."""

    k_h_alpha: float
    k_f_alpha: float
    unlimited: float
    limit_h: float
    limit_f: float


def transverse_load_factors(*, eps_alpha: float, eps_gamma: float, z_eps: float, c_gamma_alpha: float,
                            f_pb: float, f_falpha: float, y_alpha: float, line_load_h: float) -> TransverseLoad:
    """K_Hα, K_Fα (T1)-(T4); ``line_load_h`` = F_tH / b [N/mm], deviations [µm]."""
    w = check_range("line_load_h", line_load_h, 0.0, lo_open=True)
    dev = max(max(f_pb, f_falpha) - y_alpha, 0.0)
    term = c_gamma_alpha * dev / w
    if eps_gamma <= 2.0:
        k = 0.5 * eps_gamma * (0.9 + 0.4 * term)
    else:
        k = 0.9 + 0.4 * math.sqrt(2.0 * (eps_gamma - 1.0) / eps_gamma) * term
    lim_h = eps_gamma / (eps_alpha * z_eps ** 2)
    lim_f = eps_gamma / (0.25 * eps_alpha + 0.75)
    return TransverseLoad(min(max(k, 1.0), max(lim_h, 1.0)), min(max(k, 1.0), max(lim_f, 1.0)), k, lim_h, lim_f)
