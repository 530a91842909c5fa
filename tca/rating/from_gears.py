r"""A gearfe gear pair rated by ISO 6336: its :class:`~tca.pair.gear_pair.GearPair` to a :class:`~.rating.RatingCase`.

The pair's geometry comes from the gears themselves, so a case file is rated as it is analysed:

* basic data (:class:`~.geometry.PairData`): normal module, normal pressure angle and the helix of the rack
  (``Gear.beta_ref``) of the pinion, teeth, face widths, profile shifts, tip and root diameters (``2 r_tip``,
  ``2 r_root`` of the generated gears) and the nominal centre distance ``GearPair.E`` (the misalignment's
  ΔE is an error, not the design); the basic rack h_aP/m_n, h_fP/m_n as the mean of the two gears'
  ``addendum`` and ``tool_addendum`` (they enter only C_B of ISO 6336-1 here, the diameters being given);
* the pinion is the gear with fewer teeth (ISO's gear 1), whichever drives; an internal gear is the wheel;
* Y_F, Y_S and the notch parameter :math:`q_s = s_{Fn}/(2\rho_F)` of each gear from its generated tooth
  (:func:`tca.rating.root_stress.root_factors`, ISO 6336-3 method B), source "gearfe";
* the tip relief C_a of each gear from its ``Gear.tip_relief`` (amount at the tip), else ISO's running-in C_ay;
* the mesh misalignment of method C (K_Hβ) from the pair's alignment errors (R1):

.. math::
    f_{ma} = b\,\big(|\Delta\gamma|\cos\alpha_{wt} + |\Delta\gamma_v|\sin\alpha_{wt}\big) \quad (R1)

  (the tilt of gear 2's axis about the line of centres moves the flanks along the plane of action by
  :math:`\cos\alpha_{wt}` of the tilt, the tilt about the perpendicular axis by :math:`\sin\alpha_{wt}`; the two
  added as magnitudes, the upper bound of their combination);
* torques: ISO's T_1 is the pinion's, :math:`T_1 = T_{driven}\,z_1/z_{driven}` (or :math:`T_{driver}\,z_1/z_{driver}`);
  speeds likewise :math:`n_1 = n\,z/z_1` from the driver's or the driven gear's speed.

Cases outside ISO's assumptions are rated with a warning: ε_α < 1 or ε_α ≥ 2 (method B's load at the outer point
of single contact: Y_F, Y_S evaluated with ε_α clipped to [1, 2), which puts the load at the tip for ε_α < 1),
β > 30°, a profile-crowned (parabolic) rack (rated as the involute of its reference rack: Z-factors and curvatures
are the involute's). Units: mm, N, MPa, rad; roughness and tip relief in µm as ISO writes them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Mapping

from tca.errors import InputError
from tca.geometry.gear import Gear
from tca.pair.gear_pair import GearPair
from tca.rating.errors import RatingInputError, RatingWarning, check_range
from tca.rating.face_load import ShaftData
from tca.rating.factors import Given, Source
from tca.rating.geometry import GearBlank, PairData, pair_geometry
from tca.rating.materials import Material
from tca.rating.rating import GearRatingData, Operation, RatingCase
from tca.rating.root_stress import RootFactors, root_factors

__all__ = ["GearSpec", "Service", "Load", "RatedPair", "pinion_first", "pair_data", "rating_case", "mesh_misalignment",
           "GIVEN_KEYS",
           "NominalContact", "nominal_contact"]

GIVEN_KEYS = ("k_gamma", "k_v", "k_h_beta", "k_f_beta", "k_h_alpha", "k_f_alpha")  # factors a user may give


@dataclass(frozen=True)
class GearSpec:
    """What the rating needs of one gear besides its geometry (its ``[rating.gears.<name>]`` table).

    Roughness Rz [µm] of the flank and of the root; ``accuracy_grade`` of ISO 1328-1:1995; ``rim_thickness``
    s_R [mm] (None: solid, Y_B = 1); ``mean_stress_factor`` Y_M (1 one-way bending, 0.7 an idler's reversed);
    ``contacts_per_revolution`` (a sun meshing with 3 planets: 3).
    """

    material: Material
    accuracy_grade: int
    flank_roughness: float = 3.0
    root_roughness: float = 10.0
    rim_thickness: float | None = None
    mean_stress_factor: float = 1.0
    contacts_per_revolution: int = 1

    def __post_init__(self):
        if not isinstance(self.material, Material):
            raise RatingInputError("material", type(self.material).__name__, "a Material record")


@dataclass(frozen=True)
class Service:
    """Speed [1/min] of the gear ``speed_of`` ("driver" or "driven"), life [h], K_A, ν40 [mm²/s], S_min, Z/Y(10^10)."""

    speed: float
    speed_of: str = "driver"
    life_hours: float = 20000.0
    viscosity_40: float = 220.0
    application_factor: float = 1.0
    min_safety_contact: float = 1.0
    min_safety_bending: float = 1.0
    long_life_contact: float = 0.85
    long_life_bending: float = 0.85
    limited_pitting: bool = False

    def __post_init__(self):
        check_range("speed", self.speed, 0.0, lo_open=True, why="[1/min]")
        if self.speed_of not in ("driver", "driven"):
            raise RatingInputError("speed_of", self.speed_of, "'driver' or 'driven'")


@dataclass(frozen=True)
class Load:
    """Torque [N mm] on the gear ``of`` ("driver" or "driven") and the factors the user gives (``Given``)."""

    torque: float
    of: str = "driven"
    given: Mapping[str, Given] = field(default_factory=dict)

    def __post_init__(self):
        check_range("torque", self.torque, 0.0, lo_open=True, why="[N mm]")
        if self.of not in ("driver", "driven"):
            raise RatingInputError("torque_of", self.of, "'driver' or 'driven'")
        for k in self.given:
            if k not in GIVEN_KEYS:
                raise RatingInputError(k, self.given[k], "one of " + ", ".join(GIVEN_KEYS))
        object.__setattr__(self, "given", MappingProxyType(dict(self.given)))


@dataclass(frozen=True)
class RatedPair:
    """A gearfe pair as ISO sees it: the :class:`RatingCase`, which gear is the pinion, Y_F/Y_S sections, warnings."""

    case: RatingCase
    pinion: str  # gear names
    wheel: str
    roots: tuple[RootFactors, RootFactors]  # (pinion, wheel), ISO 6336-3 method B
    warnings: tuple[RatingWarning, ...]


def pinion_first(pair: GearPair) -> tuple[Gear, Gear]:
    """(pinion, wheel): the gear with fewer teeth first (ISO's gear 1); an internal gear is always the wheel."""
    g1, g2 = pair.gear1, pair.gear2
    if g1.internal or (not g2.internal and g2.teeth < g1.teeth):
        return g2, g1
    return g1, g2


def mesh_misalignment(pair: GearPair, working_pressure_angle: float) -> float:
    """f_ma [µm] of the pair's alignment errors, Eq. (R1)."""
    m = pair.misalignment
    b = min(pair.gear1.face_width, pair.gear2.face_width)
    return 1e3 * b * (abs(m.d_gamma) * math.cos(working_pressure_angle) + abs(m.d_gamma_v) * math.sin(working_pressure_angle))


def _blank(g: Gear) -> GearBlank:
    return GearBlank(g.teeth, g.face_width, g.profile_shift, tip_diameter=2 * g.r_tip, root_diameter=2 * g.r_root)


def pair_data(pair: GearPair) -> PairData:
    """Basic data of ISO 6336 from the pair (module docstring); errors name the case keys of the gears."""
    p, w = pinion_first(pair)
    for key, a, b, scale in (("module_mm", p.module, w.module, 1.0), ("pressure_angle_deg", p.pressure_angle,
                                                                        w.pressure_angle, 180 / math.pi),
                             ("helix_deg", p.beta_ref, w.beta_ref, 180 / math.pi)):
        if abs(a - b) > 1e-9 * max(1.0, abs(a)):
            raise RatingInputError(f"gears.{w.name}.{key}", b * scale, f"{a * scale:g}, the value of {p.name} "
                                   "(ISO 6336 rates gears of one basic rack)")
    try:
        return PairData(p.module, p.pressure_angle, p.beta_ref, _blank(p), _blank(w), centre_distance=pair.E,
                        internal=w.internal, addendum=0.5 * (p.addendum + w.addendum),
                        dedendum=0.5 * (p.tool_addendum + w.tool_addendum))
    except RatingInputError as e:
        names = {"addendum": "addendum", "dedendum": "tool_addendum"}
        if e.key in names:
            raise RatingInputError(f"gears.{p.name}.{names[e.key]}", e.value, e.valid, "ISO 6336's basic rack") from None
        raise


def _roots(g: Gear, eps_alpha: float) -> tuple[RootFactors, list[RatingWarning]]:
    eps = min(max(eps_alpha, 1.0), 2.0 - 1e-9)
    warn = []
    if eps != eps_alpha:
        warn.append(RatingWarning("root_load_point", f"{g.name}: ε_α = {eps_alpha:.4f} outside [1, 2): method B's "
                                  f"load at the outer point of single contact does not exist; Y_F, Y_S taken with "
                                  f"ε_α = {eps:.4f} ({'the tip' if eps_alpha < 1 else 'one base pitch inside the tip'})"))
    try:
        return root_factors(g, eps), warn
    except InputError as e:
        raise RatingInputError(f"gears.{g.name}", e.value, e.valid, "ISO 6336-3 method B: " + e.why) from None


def rating_case(pair: GearPair, specs: Mapping[str, GearSpec], service: Service, load: Load,
                elastic: tuple[float, float] | None = None) -> RatedPair:
    """The :class:`RatingCase` of ``pair`` (module docstring). ``specs`` by gear name; ``elastic`` (E [MPa], ν)
    replaces both materials' elastic constants (the FE model's, so that Z_E and the FE agree)."""
    p, w = pinion_first(pair)
    for g in (p, w):
        if g.name not in specs:
            raise RatingInputError(f"rating.gears.{g.name}", None, "a table with the material of every gear of the pair")
    data = pair_data(pair)
    geom = pair_geometry(data)
    warnings: list[RatingWarning] = []
    if any(g.parabola_pos or g.parabola_neg for g in (p, w)):
        warnings.append(RatingWarning("profile_crowned", "a profile-crowned (parabolic) rack: rated as the involute of "
                                      "its reference rack (Z_H, Z_B/Z_D and the curvatures are the involute's)"))
    data_g = []
    roots = []
    for g in (p, w):
        s = specs[g.name]
        rf, wr = _roots(g, geom.eps_alpha)
        warnings += wr
        roots.append(rf)
        mat = s.material if elastic is None else replace(s.material, youngs_modulus=elastic[0], poisson=elastic[1])
        relief = None if g.tip_relief is None else g.tip_relief.amount * 1e3
        try:
            data_g.append(GearRatingData(mat, s.accuracy_grade, s.flank_roughness, s.root_roughness, rf.y_f, rf.y_s,
                                         rf.s_fn / (2 * rf.rho_f), tip_relief=relief, rim_thickness=s.rim_thickness,
                                         contacts_per_revolution=s.contacts_per_revolution,
                                         mean_stress_factor=s.mean_stress_factor, form_source=Source.GEARFE))
        except RatingInputError as e:
            raise RatingInputError(f"rating.gears.{g.name}.{e.key}", e.value, e.valid, e.why) from None
    driver, driven = pair.gear1, pair.gear2
    ref = driver if load.of == "driver" else driven
    t1 = load.torque * p.teeth / ref.teeth
    sref = driver if service.speed_of == "driver" else driven
    n1 = service.speed * sref.teeth / p.teeth
    op = Operation(t1, n1, service.life_hours, service.viscosity_40, service.application_factor)
    shaft = ShaftData(mesh_misalignment=mesh_misalignment(pair, geom.working_pressure_angle))
    case = RatingCase(data, data_g[0], data_g[1], op, shaft=shaft, min_safety_contact=service.min_safety_contact,
                      min_safety_bending=service.min_safety_bending, long_life_contact=service.long_life_contact,
                      long_life_bending=service.long_life_bending, limited_pitting=service.limited_pitting,
                      **dict(load.given))
    return RatedPair(case, p.name, w.name, (roots[0], roots[1]), tuple(warnings))


@dataclass(frozen=True)
class NominalContact:
    """ISO 6336-2's nominal contact stress of a gearfe pair under one torque, no load factors [MPa]."""

    sigma_h0: float  # at the pitch point, with Z_ε (load sharing allowance)
    at_inner_point_pinion: float  # σ_H0 Z_B / Z_ε: the pinion's inner point of single contact, one pair, whole load
    at_inner_point_wheel: float  # σ_H0 Z_D / Z_ε
    z_h: float
    z_e: float
    z_eps: float
    z_beta: float
    z_b: float
    z_d: float
    pinion: str
    wheel: str


def nominal_contact(pair: GearPair, torque: float, elastic: tuple[float, float], torque_of: str = "driven") -> NominalContact:
    """σ_H0 (H1) of the pair under ``torque`` [N mm] on the gear ``torque_of``, materials of modulus E [MPa] and
    Poisson ratio ν (``elastic``), with Z_B, Z_D and Z_ε to carry it to the inner points of single contact."""
    from tca.rating.contact import contact_factors, nominal_contact_stress

    p, w = pinion_first(pair)
    geom = pair_geometry(pair_data(pair))
    ref = pair.gear1 if torque_of == "driver" else pair.gear2
    f_t = 2.0 * abs(torque) * p.teeth / ref.teeth / geom.reference_diameter[0]
    cf = contact_factors(geom, (elastic[0], elastic[0]), (elastic[1], elastic[1]))
    s = nominal_contact_stress(geom, f_t, cf)
    return NominalContact(s, s * cf.z_b / cf.z_eps, s * cf.z_d / cf.z_eps, cf.z_h, cf.z_e, cf.z_eps, cf.z_beta, cf.z_b,
                          cf.z_d, p.name, w.name)
