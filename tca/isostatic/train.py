r"""A planar planetary train: sun 1, carrier c with :math:`N_p` pinned planets 2, ring 3 (Part 3).

Fixed frame :math:`S_f` (the plane of the mechanism, z towards the viewer); the sun drives
counter-clockwise, the ring is held, the carrier is the output. Members and their maps (in-plane
parts of Eqs. 3.6–3.7 and 3.12–3.17):

* sun: :math:`\mathbf P = \mathbf E_1 + R(\phi_1)\,(R(2\pi i_s/N_1)\,\mathbf g_1 + \boldsymbol\varepsilon_1)`,
  reference tooth on +x at :math:`\phi_1 = 0`; :math:`\mathbf E_1 = (\Delta E_{1x}, \Delta E_{1y})`
  is an unknown when the sun floats, an installment error otherwise;
* planet *i* (:math:`i = 1..N_p`) on the carrier turned by :math:`q_c = \phi_c + 2\pi(i-1)/N_p`
  about :math:`\mathbf E_c`, pinned at :math:`(r_c + \Delta r_c^{(i)},\ \Delta E_t^{(i)})` of the carrier
  (Eq. 3.12) and turned by :math:`\phi_2^{(i)}` relative to it. Its gear frame turns clockwise
  relative to the carrier, so (as in :class:`tca.pair.gear_pair.GearPair`) it is the frame :math:`D`
  (:math:`x \to -x`, i.e. :math:`R_y(\pi)` in the plane) turned by :math:`\phi_2 + \pi/N_2`:
  :math:`\mathbf P = \mathbf E_c + R(q_c)\,[\mathbf C_i + D R(\phi_2 + \pi/N_2)(R(2\pi i_p/N_2)\mathbf g_2 + \boldsymbol\varepsilon_2)]`;
  the sun drives the planet's side −1 (coast, :math:`a_{cc}`) flank, the planet drives the ring
  with its side +1 flank (:math:`a_{cd}`), as in Part 1;
* ring: :math:`\mathbf P = \mathbf E_3 + D R(\rho_0)(R(2\pi i_r/N_3)\,\mathbf g_3 + \boldsymbol\varepsilon_3)`,
  its side −1 flank in mesh.

Reference (zero-backlash, symmetric) configuration: :math:`\phi_1 = \phi_c = 0`, no errors,
:math:`\phi_2^{(i)} = -(N_1/N_2)\,\theta_i` with :math:`\theta_i = 2\pi(i-1)/N_p`. Each sun–planet
mesh is then the pair of :mod:`tca.pair.gear_pair` seen in the frame turned by :math:`q_c`, and the ring
phase follows from the internal pair's ideal relation,
:math:`\rho_0 = -\pi + \pi(N_2 + 2)/N_3 \pmod{2\pi/N_3}`, the same for every planet when the
assembly condition :math:`(N_1 + N_3)/N_p \in \mathbb Z` holds. Ideal motion:
:math:`\phi_c = m_{c1}\phi_1`, :math:`m_{c1} = N_1/(N_1 + N_3)`,
:math:`\phi_2^{(i)} = (N_1/N_2)(\phi_1 - \phi_c - \theta_i)`; transmission errors (Eq. 3.23)
:math:`\Delta\phi_c = \phi_c - m_{c1}\phi_1` are therefore absolute (negative: the carrier lags).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from tca.isostatic.dof import DOFCount, TrainConstraints, count_dof
from tca.isostatic.flanks import PlanarFlank, TrainFlanks
from tca.errors import GeometryError, InputError
from tca.geometry.gear import Gear

__all__ = ["PlanetPlacement", "IsostaticTrain"]


@dataclass(frozen=True)
class PlanetPlacement:
    """Errors of the pin of one planet on the carrier (Eq. 3.12) [mm]."""

    tangential: float = 0.0  # Delta E_t: indexing error of the carrier, along +q_c (direction of rotation)
    radial: float = 0.0  # Delta r_c

    def __post_init__(self):
        for name in ("tangential", "radial"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and abs(v) <= 1.0):
                raise InputError(f"planet.{name}_error_um", v * 1e3 if isinstance(v, (int, float)) else v,
                                 "a number with |value| <= 1000 um")


_SAME = ("teeth", "module", "pressure_angle", "face_width", "helix", "hand", "reference_helix", "internal",
         "profile_shift", "addendum", "tool_addendum", "tool_tip_radius", "parabola_pos", "parabola_neg",
         "parabola_apex", "plunge")


def _vec2(v, name):
    try:
        a = np.asarray(v, float).reshape(-1)
    except (TypeError, ValueError):
        raise InputError(name, v, "two numbers (x, y)") from None
    if a.shape != (2,) or not np.all(np.isfinite(a)) or np.abs(a).max() > 1.0:
        raise InputError(name, (a * 1e3).tolist() if a.size else v, "two finite numbers (x, y) with |value| <= 1000 um")
    return a


@dataclass(frozen=True, eq=False)
class IsostaticTrain:
    """Sun, N_p planets (equal teeth; each may carry its own run-out) and ring, with floating choices and errors."""

    sun: Gear
    planets: tuple[Gear, ...]
    ring: Gear
    constraints: TrainConstraints | None = None  # default: case 2 (sun floats) with len(planets) planets
    placements: tuple[PlanetPlacement, ...] | None = None  # default: no pin errors
    sun_center: tuple[float, float] = (0.0, 0.0)  # installment error of a fixed sun axis [mm]
    carrier_center: tuple[float, float] = (0.0, 0.0)  # Delta E_cx, Delta E_cy of a fixed carrier axis (Eq. 3.13) [mm]
    ring_center: tuple[float, float] = (0.0, 0.0)  # of a fixed ring axis [mm]
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        planets = tuple(self.planets)
        object.__setattr__(self, "planets", planets)
        n = len(planets)
        if n == 0:
            raise InputError("planets.count", 0, "at least 1 planet")
        if self.constraints is None:
            object.__setattr__(self, "constraints", TrainConstraints(n, sun_axis_free=True))
        c = self.constraints
        if c.n_planets != n:
            raise InputError("planets.count", n, f"= constraints.n_planets = {c.n_planets}")
        pl = self.placements if self.placements is not None else tuple(PlanetPlacement() for _ in range(n))
        pl = tuple(pl)
        if len(pl) != n:
            raise InputError("planets.errors", len(pl), f"one entry per planet ({n})")
        object.__setattr__(self, "placements", pl)
        for name, free in (("sun_center", c.sun_axis_free), ("carrier_center", c.carrier_axis_free),
                           ("ring_center", c.ring_axis_free)):
            v = _vec2(getattr(self, name), f"{name}_error_um")
            object.__setattr__(self, name, (float(v[0]), float(v[1])))
            if free and np.any(v != 0):
                raise InputError(f"{name}_error_um", tuple(v * 1e3), "(0, 0) for a floating axis (its position is an "
                                 "unknown of the simulation)")
        s, p0, r = self.sun, planets[0], self.ring
        if s.internal or not r.internal:
            raise InputError("ring.internal", r.internal, "true for the ring, false for the sun")
        for g in (s, *planets, r):
            if g.helix != 0.0:
                raise InputError(f"{g.name}.helix_deg", math.degrees(g.helix), "0 (the isostatic train is planar: spur gears)")
            if g.profile_shift != 0.0:
                raise InputError(f"{g.name}.profile_shift", g.profile_shift, "0 (standard centre distances)")
            if g.internal and g is not r:
                raise InputError(f"{g.name}.internal", True, "false (only the ring is internal)")
        for g in (s, r):
            if g.module != p0.module or g.pressure_angle != p0.pressure_angle:
                raise InputError(f"{g.name}.module_mm", g.module, f"the planet's module {p0.module} mm and pressure angle")
        for i, p in enumerate(planets[1:], 2):
            for f in _SAME:
                if getattr(p, f) != getattr(p0, f):
                    raise InputError(f"planet{i}.{f}", getattr(p, f), f"{getattr(p0, f)!r} as planet 1 (planets may "
                                     "differ only by their run-out)")
        N1, N2, N3 = s.teeth, p0.teeth, r.teeth
        if N3 != N1 + 2 * N2:
            raise InputError("ring.teeth", N3, f"sun.teeth + 2 planet.teeth = {N1 + 2 * N2} (standard centre distances)")
        if (N1 + N3) % n:
            raise InputError("planets.count", n, f"a divisor of sun.teeth + ring.teeth = {N1 + N3} "
                             "(assembly condition for equally spaced planets)")
        for i, (pin, p) in enumerate(zip(self.pins, planets), 1):  # tips must clear the roots of the mates
            dist = float(np.hypot(*pin))
            for what, c in (("sun tip / planet root", dist - s.r_tip - p.r_root),
                            ("planet tip / sun root", dist - p.r_tip - s.r_root),
                            ("planet tip / ring root", r.r_root - dist - p.r_tip),
                            ("ring tip / planet root", r.r_tip - dist - p.r_root)):
                if c <= 0:
                    raise GeometryError(p.name, "tip interference",
                                        f"planet {i}: {what} clearance is {c * 1e3:.1f} um with the pin at "
                                        f"{dist:.4f} mm from the carrier axis (radial error too large)")
        if n > 1:
            gap = 2 * self.r_c * math.sin(math.pi / n) - 2 * p0.r_tip
            if gap <= 0:
                raise GeometryError(p0.name, "neighbouring planets overlap",
                                    f"tip circles of adjacent planets intersect ({gap:.3f} mm clearance) with {n} planets")

    # ------------------------------------------------------------------ data
    @property
    def n_planets(self) -> int:
        return len(self.planets)

    @property
    def planet(self) -> Gear:
        return self.planets[0]

    @property
    def dof(self) -> DOFCount:
        return count_dof(self.constraints)

    @property
    def r_c(self) -> float:
        """Carrier radius r_p1 + r_p2 [mm]."""
        return self.sun.r_p + self.planets[0].r_p

    @property
    def ratio(self) -> float:
        """m_c1 = N1 / (N1 + N3) (carrier over sun, ring held)."""
        return self.sun.teeth / (self.sun.teeth + self.ring.teeth)

    @property
    def planet_ratio(self) -> float:
        """Planet turn relative to the carrier per sun turn, (1 - m_c1) N1 / N2 (section 3.4.5)."""
        return (1 - self.ratio) * self.sun.teeth / self.planets[0].teeth

    @property
    def pressure_angle(self) -> float:
        """Transverse pressure angle [rad]."""
        return self.sun.transverse_pressure_angle

    @property
    def theta(self) -> np.ndarray:
        """Nominal angular positions of the planets on the carrier, 2 pi (i - 1) / N_p [rad]."""
        return 2 * math.pi * np.arange(self.n_planets) / self.n_planets

    @property
    def ring_phase(self) -> float:
        """rho_0 of the ring's frame D R(rho_0) in the zero-backlash configuration [rad]."""
        N2, N3 = self.planets[0].teeth, self.ring.teeth
        return -math.pi + math.pi * (N2 + 2) / N3

    @property
    def pins(self) -> np.ndarray:
        """Planet centres in the carrier frame (Eq. 3.12), (N_p, 2) [mm]."""
        return np.array([[self.r_c + p.radial, p.tangential] for p in self.placements])

    def flanks(self, z0: float = 0.0) -> TrainFlanks:
        """The four flanks in mesh, sections at z = z0 [mm] (built once per train and section)."""
        key = ("flanks", z0)
        if key not in self._cache:
            p = self.planet
            self._cache[key] = TrainFlanks(PlanarFlank(self.sun, 1, z0), PlanarFlank(p, -1, z0), PlanarFlank(p, 1, z0),
                                           PlanarFlank(self.ring, -1, z0))
        return self._cache[key]

    def with_(self, **kw) -> "IsostaticTrain":
        """Copy with some fields replaced."""
        d = {f.name: getattr(self, f.name) for f in fields(self) if f.init}
        d.update(kw)
        return IsostaticTrain(**d)
