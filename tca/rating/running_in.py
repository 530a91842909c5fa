r"""Running-in allowances of ISO 6336-1 (method B): y_α, y_f (profile) and y_β (helix) [µm].

By material of the pair (ISO 6336-1, clause on the running-in allowance; :math:`\sigma_{H\lim}` in MPa):

.. math::
    \text{St, V, GTS, GGG (perl., bai.)}:\quad y_\alpha = \frac{160}{\sigma_{H\lim}} f_{pb},\quad
    y_\beta = \frac{320}{\sigma_{H\lim}} F_{\beta x} \quad (R1)

    \text{GG, GGG (ferr.)}:\quad y_\alpha = 0.275 f_{pb},\quad y_\beta = 0.55 F_{\beta x} \quad (R2)

    \text{Eh, IF, NT, NV}:\quad y_\alpha = 0.075 f_{pb} \le 3,\quad y_\beta = 0.15 F_{\beta x} \le 6 \quad (R3)

For (R1), (R2) the deviation that enters is capped with the pitch line velocity: :math:`f_{pb}, F_{\beta x}
\le 80` µm for :math:`5 < v \le 10` m/s and :math:`\le 40` µm above 10 m/s (no cap up to 5 m/s). When pinion and
wheel are of different materials the allowance is the mean of the two values (R4). :math:`y_f` is (R1)-(R3) for
:math:`y_\alpha` with :math:`f_{f\alpha}` in place of :math:`f_{pb}` (R5).
"""

from __future__ import annotations

from tca.rating.materials import Material, MaterialKind

__all__ = ["profile_allowance", "helix_allowance"]

_SOFT = frozenset({MaterialKind.ST, MaterialKind.ST_CAST, MaterialKind.V_CARBON, MaterialKind.V_ALLOY,
                   MaterialKind.GTS, MaterialKind.GGG})
_IRON = frozenset({MaterialKind.GG, MaterialKind.GGG_FERRITIC})


def _cap(deviation: float, v: float) -> float:
    if v > 10.0:
        return min(deviation, 40.0)
    if v > 5.0:
        return min(deviation, 80.0)
    return deviation


def _one_profile(m: Material, f: float, v: float) -> float:
    if m.kind in _SOFT:
        return 160.0 / m.sigma_h_lim * _cap(f, v)
    if m.kind in _IRON:
        return 0.275 * _cap(f, v)
    return min(0.075 * f, 3.0)


def _one_helix(m: Material, f: float, v: float) -> float:
    if m.kind in _SOFT:
        return 320.0 / m.sigma_h_lim * _cap(f, v)
    if m.kind in _IRON:
        return 0.55 * _cap(f, v)
    return min(0.15 * f, 6.0)


def profile_allowance(pinion: Material, wheel: Material, deviation: float, v: float) -> float:
    """y_α (``deviation`` = f_pb) or y_f (``deviation`` = f_fα) [µm] at pitch line velocity ``v`` [m/s], (R1)-(R5)."""
    return 0.5 * (_one_profile(pinion, deviation, v) + _one_profile(wheel, deviation, v))


def helix_allowance(pinion: Material, wheel: Material, f_beta_x: float, v: float) -> float:
    """y_β [µm] for the initial equivalent misalignment F_βx [µm] at ``v`` [m/s], (R1)-(R4)."""
    return 0.5 * (_one_helix(pinion, f_beta_x, v) + _one_helix(wheel, f_beta_x, v))
