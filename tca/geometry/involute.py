r"""Involute relations of a pair of rack-generated gears: working pressure angle, centre distance, backlash.

Transverse section; :math:`\alpha_t` the transverse pressure angle of the rack, :math:`\alpha_n` the normal
one, :math:`x_i` the profile shifts (positive thickens the tooth, external and internal gears alike:
:attr:`tca.geometry.gear.Gear.profile_shift`), :math:`z_i` the numbers of teeth, :math:`a_0` the standard
centre distance (pitch circles tangent: :math:`r_1 + r_2` external, :math:`r_2 - r_1` internal) and
:math:`\mathrm{inv}\,\alpha = \tan\alpha - \alpha`.

Tooth thickness on a circle of radius :math:`r` with pressure angle :math:`\alpha_r`
(:math:`\cos\alpha_r = r_b/r`), from its thickness :math:`s = m_t(\pi/2 + 2x\tan\alpha_n)` on the
reference circle :math:`r_p` (ISO 21771, Eq. 42; the internal tooth widens outward):

.. math::  s_r = r\left(\frac{s}{r_p} \mp 2(\mathrm{inv}\,\alpha_r - \mathrm{inv}\,\alpha_t)\right)
   \qquad (-\ \text{external},\ +\ \text{internal}) .                                              (I1)

At a centre distance :math:`a` the operating pitch circles are :math:`r_{wi} = r_{bi}/\cos\alpha_w`
with :math:`\cos\alpha_w = a_0\cos\alpha_t/a`, and the circumferential backlash on them is

.. math::  j_t = p_w - s_{w1} - s_{w2},\qquad p_w = 2\pi r_{w1}/z_1                                (I2)

(for an internal gear :math:`p_w - s_{w2}` is its space width, so the same expression holds). Zero
backlash, :math:`j_t = 0`, gives the working pressure angle of the profile shifts

.. math::  \mathrm{inv}\,\alpha_w = \mathrm{inv}\,\alpha_t + 2\tan\alpha_n\,\frac{x_1 + x_2}{z_1 + z_2}
   \ \text{(external)},\qquad
   \mathrm{inv}\,\alpha_w = \mathrm{inv}\,\alpha_t - 2\tan\alpha_n\,\frac{x_1 + x_2}{z_2 - z_1}
   \ \text{(internal gear 2)}                                                                       (I3)

and the operating centre distance of zero backlash :math:`a_w = a_0\cos\alpha_t/\cos\alpha_w` (I4)
(ISO 21771 Eqs. 61-62 for external pairs; the internal form follows from (I1)-(I2) with this sign of
:math:`x`). Without profile shifts :math:`a_w = a_0` exactly.
"""

from __future__ import annotations

import math

__all__ = ["inv", "inv_inverse", "standard_center_distance", "zero_backlash_center_distance",
           "working_pressure_angle", "backlash"]


def inv(alpha: float) -> float:
    """Involute function tan(alpha) - alpha."""
    return math.tan(alpha) - alpha


def inv_inverse(y: float) -> float:
    """The angle in (0, pi/2) [rad] whose involute function is y >= 0 (Newton from (3 y)^(1/3))."""
    if not y >= 0.0 or not math.isfinite(y):
        raise ValueError(f"inv_inverse({y!r}): no angle in [0, pi/2)")
    a = min((3.0 * y) ** (1.0 / 3.0), 1.5)
    for _ in range(60):
        f = math.tan(a) - a - y
        da = f / (math.tan(a) ** 2)  # d inv / d alpha = tan^2(alpha)
        a = min(max(a - da, 0.5 * a), 0.5 * (a + 0.5 * math.pi))
        if abs(da) < 1e-15:
            break
    return a


def _roles(g1, g2):
    """(external gear, internal gear or None)."""
    if g1.internal:
        return g2, g1
    if g2.internal:
        return g1, g2
    return g1, None


def standard_center_distance(g1, g2) -> float:
    """Pitch circles tangent: r1 + r2 (external) or r_internal - r_external [mm]."""
    return g1.r_p + g2.r_p if not (g1.internal or g2.internal) else abs(g2.r_p - g1.r_p)


def zero_backlash_center_distance(g1, g2) -> float:
    """Operating centre distance of zero backlash (I3)-(I4) [mm]; the standard one when x1 + x2 = 0."""
    a0 = standard_center_distance(g1, g2)
    xs = g1.profile_shift + g2.profile_shift
    if xs == 0.0:
        return a0
    at = g1.transverse_pressure_angle
    ext, intl = _roles(g1, g2)
    if intl is None:
        y = inv(at) + 2.0 * math.tan(g1.pressure_angle) * xs / (g1.teeth + g2.teeth)
    else:
        y = inv(at) - 2.0 * math.tan(g1.pressure_angle) * xs / (intl.teeth - ext.teeth)
    if y <= 0.0:  # a negative shift sum so large that no pressure angle closes the backlash
        return math.nan
    return a0 * math.cos(at) / math.cos(inv_inverse(y))


def working_pressure_angle(g1, g2, a: float) -> float:
    """Transverse working pressure angle at centre distance a [mm] [rad] (nan where none exists)."""
    c = standard_center_distance(g1, g2) * math.cos(g1.transverse_pressure_angle) / a
    return math.acos(c) if 0.0 < c < 1.0 else math.nan


def backlash(g1, g2, a: float) -> float:
    """Circumferential backlash on the operating pitch circles at centre distance a (I2) [mm]; negative: overlap."""
    aw = working_pressure_angle(g1, g2, a)
    if not math.isfinite(aw):
        return math.nan
    at = g1.transverse_pressure_angle
    d = inv(aw) - inv(at)

    def thickness(g):
        s = g.transverse_module * (0.5 * math.pi + 2.0 * g.profile_shift * math.tan(g.pressure_angle))
        rw = g.r_b / math.cos(aw)
        return rw * (s / g.r_p + (2.0 if g.internal else -2.0) * d)

    pw = 2.0 * math.pi * (g1.r_b / math.cos(aw)) / g1.teeth
    return pw - thickness(g1) - thickness(g2)
