r"""Generating rack-cutter in normal section: straight or parabolic flank, rounded tip, tip line.

Coordinates of the normal section (Fig. 1.3(a)): ``h`` points toward the tip of the generated
tooth, ``eta`` across the tooth toward its +y flank; the generated tooth occupies
``|eta| < eta_flank(h)`` and is centred on ``eta = 0``. Profile shift ``x`` moves the rack by
``x m`` toward the tooth tip, thickening the tooth at the pitch circle (external and internal).

Flank (side +1), parameter ``u`` [mm] along the straight profile from the point ``Q0`` on the
generating pitch line, with the parabolic modification of Eq. (1.5)
:math:`\Delta = a_c (u - u_0)^2` applied along the flank normal, into the tooth:

.. math::
    P(u) = Q_0 + u\,(\cos\alpha_n, -\sin\alpha_n) - a_c (u-u_0)^2 (\sin\alpha_n, \cos\alpha_n),
    \qquad Q_0 = (0,\; \pi m/4 + x m \tan\alpha_n).

Tip relief (a tool property: the rack flank is relieved where it generates the gear's tip),
amount :math:`C_a` from :math:`u_s` to :math:`u_a` (the parameters generating the start circle and the
tip circle of the gear), linear (:math:`n = 1`) or parabolic (:math:`n = 2`), removed along the
flank normal like the parabola:
:math:`\Delta_r(u) = C_a \max(0, (u-u_s)/(u_a-u_s))^n`. The parabolic relief is tangent to the flank
at :math:`u_s`; the linear one has a kink there.

The tip of the rack (addendum ``h_a0 m`` below the reference line) is rounded by an arc of
radius ``rho_f m`` tangent to the flank and to the tip line; the arc generates the fillet and
the tip line the root circle of the gear. The transverse section of the skew rack stretches
``eta`` by ``1 / cos(beta_ref)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.errors import GeometryError, InputError

__all__ = ["RackCutter", "RackSegment", "rack_segments"]


@dataclass(frozen=True)
class RackCutter:
    """Generating rack-cutter of a gear flank pair, in normal section."""

    module: float  # normal module m_n [mm]
    pressure_angle: float  # normal pressure angle alpha_n [rad]
    addendum: float = 1.25  # tool addendum h_a0 / m
    tip_radius: float = 0.25  # tool tip rounding rho_f / m
    parabola_pos: float = 0.0  # a_c of the flank generating the +y tooth flank [1/mm]
    parabola_neg: float = 0.0  # a_c of the flank generating the -y tooth flank [1/mm]
    parabola_apex: float = 0.0  # u_0, parabola apex measured from the pitch point [mm]
    relief: float = 0.0  # tip relief C_a generated on the gear's tip [mm] (both flanks), 0: none
    relief_start: float = 0.0  # u_s: rack flank parameter where the relief starts [mm]
    relief_end: float = 1.0  # u_a: parameter generating the gear's tip circle, where the relief is C_a [mm]
    relief_power: int = 1  # 1 linear, 2 parabolic

    def __post_init__(self):
        if not (self.module > 0):
            raise InputError("module_mm", self.module, "> 0")
        if not (0 < self.pressure_angle < math.radians(45)):
            raise InputError("pressure_angle_deg", math.degrees(self.pressure_angle), "in (0, 45)")
        if not (0 < self.addendum <= 3):
            raise InputError("tool_addendum", self.addendum, "in (0, 3] modules")
        if not (0 < self.tip_radius < 1):
            raise InputError("tool_tip_radius", self.tip_radius, "in (0, 1) modules (a sharp tool tip has no fillet)")
        for name in ("parabola_pos", "parabola_neg"):
            v = getattr(self, name)
            if not (0 <= v < 0.5):
                raise InputError(name + "_per_mm", v, "in [0, 0.5) 1/mm (parabola coefficient, Eq. 1.5)")

        if self.relief < 0 or (self.relief > 0 and not (self.relief_end > self.relief_start)) or self.relief_power not in (1, 2):
            raise InputError("tip_relief", (self.relief, self.relief_start, self.relief_end, self.relief_power),
                             "amount >= 0 mm starting below the tip, linear (1) or parabolic (2)")

    def parabola(self, side: int) -> float:
        """Parabola coefficient a_c of the rack flank generating tooth flank `side` [1/mm]."""
        return self.parabola_pos if side > 0 else self.parabola_neg


@dataclass(frozen=True)
class RackSegment:
    """One piece of the rack profile for tooth side +1: point and 3 derivatives in (h, eta_n)."""

    kind: str  # "root" (tip line), "fillet" (tip arc) or "flank"
    t0: float  # parameter range, increasing toward the tooth tip
    t1: float
    coef: tuple  # piece-specific constants

    def eval(self, t):
        """(P, P', P'', P''') in normal-section coordinates (h, eta), each (..., 2)."""
        t = np.asarray(t, dtype=float)
        z = np.zeros_like(t)
        if self.kind == "flank":
            ca, sa, eta0, a, u0 = self.coef[:5]
            du = t - u0
            # material removed along the flank normal: the parabola (Eq. 1.5) plus the tip relief (module docstring)
            d0, d1, d2 = a * du**2, 2 * a * du, 2 * a + z
            if len(self.coef) > 5 and self.coef[5] > 0:
                ca_r, us, ua, n = self.coef[5:]
                x = np.clip((t - us) / (ua - us), 0.0, None)
                on = t > us
                d0 = d0 + ca_r * x**n
                d1 = d1 + np.where(on, ca_r * n * x ** (n - 1) / (ua - us), 0.0)
                d2 = d2 + (np.where(on, ca_r * 2 / (ua - us) ** 2, 0.0) if n == 2 else z)
            P = np.stack([t * ca - d0 * sa, eta0 - t * sa - d0 * ca], -1)
            P1 = np.stack([ca - d1 * sa, -sa - d1 * ca], -1)
            P2 = np.stack([-d2 * sa, -d2 * ca], -1)
            P3 = np.zeros_like(P)
        elif self.kind == "fillet":
            ch, ceta, rho = self.coef
            c, s = np.cos(t), np.sin(t)
            P = np.stack([ch - rho * c, ceta - rho * s], -1)
            P1 = np.stack([rho * s, -rho * c], -1)
            P2 = np.stack([rho * c, rho * s], -1)
            P3 = np.stack([-rho * s, rho * c], -1)
        elif self.kind == "root":
            (htip,) = self.coef
            P = np.stack([z + htip, -t], -1)
            P1 = np.stack([z, z - 1.0], -1)
            P2 = np.zeros_like(P)
            P3 = np.zeros_like(P)
        else:  # pragma: no cover - constructed internally only
            raise ValueError(self.kind)
        return P, P1, P2, P3


def rack_segments(rack: RackCutter, side: int, profile_shift: float, flank_tip_h: float) -> dict[str, RackSegment]:
    """Root, fillet and flank pieces of the rack generating tooth flank `side` (+1 / -1).

    All pieces are returned for side +1 geometry; the -y flank is its mirror image and differs
    only through its own parabola coefficient. ``flank_tip_h`` [mm] is the height ``h`` up to
    which the flank parameter range is extended (beyond the gear's tip).
    """
    m, al = rack.module, rack.pressure_angle
    ca, sa = math.cos(al), math.sin(al)
    a, u0 = rack.parabola(side), rack.parabola_apex
    eta0 = math.pi * m / 4 + profile_shift * m * math.tan(al)
    relief = (rack.relief, rack.relief_start, rack.relief_end, rack.relief_power) if rack.relief > 0 else ()
    flank = RackSegment("flank", 0.0, 0.0, (ca, sa, eta0, a, u0) + relief)
    h_tip = (profile_shift - rack.addendum) * m
    rho = rack.tip_radius * m

    def junction_residual(u):
        P, P1, _, _ = flank.eval(np.array([u]))
        T = P1[0] / np.linalg.norm(P1[0])
        n_out = np.array([-T[1], T[0]])
        return P[0, 0] + rho * n_out[0] - (h_tip + rho), P[0], n_out

    # Newton on the tangency of the tip arc with the (parabolic) flank, from the straight-flank value.
    u = (h_tip + rho * (1 - sa)) / ca
    for _ in range(50):
        f, _, _ = junction_residual(u)
        df = (junction_residual(u + 1e-7)[0] - junction_residual(u - 1e-7)[0]) / 2e-7
        step = f / df
        u -= step
        if abs(step) < 1e-14:
            break
    f, Pj, n_out = junction_residual(u)
    if abs(f) > 1e-9:
        raise GeometryError("rack-cutter", "tip rounding", f"no tangent tip arc (residual {abs(f):.2e} mm)")
    uj = u
    C = Pj + rho * n_out
    w_j = math.atan2(n_out[1], n_out[0])
    if C[1] > math.pi * m / 2 + 1e-12:
        raise GeometryError(
            "rack-cutter", "tip radius too large",
            f"tool_tip_radius {rack.tip_radius} m leaves no tip land (arc centre at eta {C[1]:.4f} mm > half pitch {math.pi * m / 2:.4f} mm)",
        )
    u_tip = (flank_tip_h) / ca + 0.0
    # extend the flank range beyond the tip height (parabola bends it; be generous)
    u_tip = max(u_tip, uj) + 0.5 * m
    return {
        "root": RackSegment("root", -math.pi * m / 2, -C[1], (h_tip,)),
        "fillet": RackSegment("fillet", 0.0, w_j, (C[0], C[1], rho)),
        "flank": RackSegment("flank", uj, u_tip, (ca, sa, eta0, a, u0) + relief),
    }
