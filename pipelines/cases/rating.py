"""Reader of the ``[rating]`` table (ISO 6336 method B, :mod:`tca.rating`) of pair, stress and train cases.

Keys (every key checked, unknown keys rejected; ranges are ISO 6336's or this library's)::

    [rating]
    driver_speed_rpm = 1500.0        # speed of the driving gear [1/min], or driven_speed_rpm (exactly one)
    life_hours = 20000.0             # required life [h], > 0
    viscosity_40_mm2s = 220.0        # lubricant's kinematic viscosity at 40 °C (Z_L), in [1, 10000]
    application_factor = 1.25        # K_A of ISO 6336-1, in [1, 4]; default 1
    accuracy_grade = 6               # ISO 1328-1:1995 grade of both gears, 0..12 (or per gear)
    min_safety_contact = 1.0         # S_Hmin (σ_HP = σ_HG / S_Hmin), in [0.5, 5]
    min_safety_bending = 1.0         # S_Fmin, in [0.5, 5]
    long_life_contact = 0.85         # Z_NT at 10^10 cycles, in [0.85, 1]
    long_life_bending = 0.85         # Y_NT at 10^10 cycles, in [0.85, 1]
    limited_pitting = false          # Z_NT of ISO 6336-2 with limited pitting allowed (St, V, GGG, GTS)
    # driven_torque_nm = 120.0       # only where the case has no torque (a 'pair' case); or driver_torque_nm
    # k_gamma = 1.15                 # factors given by the user (source "input"): K_γ in [1, 3], K_v in [1, 5],
    # k_v, k_h_beta, k_h_alpha       # K_Hβ in [1, 10], K_Hα in [1, 5] (each replaces ISO's method)
    [rating.gears.pinion]            # one table per gear of the pair (per gear of the train)
    material = "Eh"                  # ISO 6336-5 group: St, St (cast), GGG (perl., bai.), GG, V (carbon), V (alloy),
                                     # Eh, IF, NT (nitr.), NV (nitr.), NV (nitrocar.)
    quality = "MQ"                   # ML, MQ or ME
    hardness = 700.0                 # HV10 or HBW as the ISO 6336-5 row says, inside the row's range
    flank_rz_um = 3.0                # Rz of the flank [µm] (Z_R), in (0, 40]; default 3
    root_rz_um = 10.0                # Rz of the root [µm] (Y_RrelT), in [0, 40]; default 10
    # accuracy_grade = 5             # this gear's grade (default [rating] accuracy_grade)
    # rim_thickness_mm = 12.0        # s_R (Y_B); default: solid
    # mean_stress_factor = 0.7       # Y_M: 1 one-way bending (default), 0.7 an idler or planet
    # yield_strength_mpa = 600.0     # σ_S / σ_0.2 (Y_δrelT of St, V, GGG, GTS)
    # tensile_strength_mpa = 200.0   # σ_B (GG)
    # brinell_hardness = 290.0       # HB of a through-hardened gear whose hardness is given in HV10 (Z_W)

The torque is the case's, as its record gives it (``torque_nm`` of a stress case: on the driven gear); speed
and torque are converted to the pinion's by the teeth (:mod:`tca.rating.from_gears`). Bad input: one line
naming the key, the value and the valid range (:class:`tca.errors.InputError`), before any work.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Mapping

from tca.errors import InputError
from tca.pair.gear_pair import GearPair
from tca.planetary.train import DoubleHelicalTrain
from tca.rating.bending import slip_layer
from tca.rating.dynamics import MeshKind
from tca.rating.errors import RatingInputError
from tca.rating.factors import Given, Source
from tca.rating.from_gears import GearSpec, Load, RatedPair, Service, rating_case
from tca.rating.materials import Material, iso_material
from tca.rating.rating import rate

from pipelines.cases.schema import Table

__all__ = ["RatingSpec", "MeshRating", "read_rating", "with_rating", "rated_meshes", "check_rating", "train_names",
           "GIVEN_RANGES", "train_meshes"]

# user-given factors: case key -> (RatingCase field, range ISO allows)
GIVEN_RANGES = {"k_gamma": (1.0, 3.0), "k_v": (1.0, 5.0), "k_h_beta": (1.0, 10.0), "k_h_alpha": (1.0, 5.0)}


@dataclass(frozen=True)
class RatingSpec:
    """The ``[rating]`` table read: per gear its :class:`GearSpec`, the service, given factors, an own torque."""

    gears: Mapping[str, GearSpec]
    service: Service
    given: Mapping[str, Given] = field(default_factory=dict)
    torque: float | None = None  # [N mm], only when the case has none
    torque_of: str = "driven"

    def load(self, torque: float | None = None, torque_of: str = "driven") -> Load:
        """The :class:`Load` of a rating: the case's torque [N mm] (or this table's) with the given factors."""
        if torque is None:
            torque, torque_of = self.torque, self.torque_of
        return Load(torque, torque_of, dict(self.given))


def _one_of(t: Table, keys: tuple[str, str], required: bool, **rng):
    have = [k for k in keys if t.has(k)]
    if len(have) > 1:
        raise InputError(t._key(have[1]), t.data[have[1]], f"one of {keys[0]} and {keys[1]}, not both")
    if not have:
        if required:
            raise InputError(t._key(keys[0]), None, f"exactly one of {keys[0]} and {keys[1]}", "missing key")
        return None, None
    return t.get(have[0], float, **rng), have[0].split("_", 1)[0]


def _material(t: Table) -> Material:
    kind = t.get("material", str)
    quality = t.get("quality", str, choices=("ML", "MQ", "ME"))
    hardness = t.get("hardness", float, lo=0.0, lo_open=True)
    extra = {}
    for key, name, lo, hi in (("yield_strength_mpa", "yield_strength", 100.0, 3000.0),
                              ("tensile_strength_mpa", "tensile_strength", 100.0, 3000.0),
                              ("brinell_hardness", "brinell_hardness", 50.0, 800.0)):
        v = t.get(key, float, None, lo=lo, hi=hi)
        if v is not None:
            extra[name] = v
    try:
        mat = iso_material(kind, quality, hardness, **extra)
    except RatingInputError as e:
        key = {"material.kind": "material", "material": "material"}.get(e.key, "hardness")
        raise InputError(t._key(key), e.value if key != "hardness" else hardness, e.valid, e.why) from None
    try:
        slip_layer(mat)  # Y_δrelT needs σ_S (St, V, GGG, GTS) or σ_B (GG)
    except RatingInputError as e:
        key = {"material.yield_strength": "yield_strength_mpa"}.get(e.key, "tensile_strength_mpa")
        raise InputError(t._key(key), None if e.value is None else e.value, e.valid, e.why or "missing key") from None
    return mat


def _gear(t: Table, grade: int | None) -> GearSpec:
    mat = _material(t)
    g = t.get("accuracy_grade", int, grade, lo=0, hi=12)
    if g is None:
        raise InputError(t._key("accuracy_grade"), None, "an integer in [0, 12] (ISO 1328-1:1995), here or in [rating]",
                         "missing key")
    spec = GearSpec(mat, g, t.get("flank_rz_um", float, 3.0, lo=0.0, lo_open=True, hi=40.0),
                    t.get("root_rz_um", float, 10.0, lo=0.0, hi=40.0),
                    t.get("rim_thickness_mm", float, None, lo=0.0, lo_open=True),
                    t.get("mean_stress_factor", float, 1.0, lo=0.7, hi=1.0))
    t.done()
    return spec


def read_rating(t: Table | None, gear_names: tuple[str, ...], case_has_torque: bool = True) -> RatingSpec | None:
    """The :class:`RatingSpec` of a ``[rating]`` table (module docstring), None when the case has none.

    ``gear_names``: the gears the case rates (each needs its table); ``case_has_torque``: False for a case without
    a torque of its own (then ``[rating]`` gives one).
    """
    if t is None:
        return None
    speed, of = _one_of(t, ("driver_speed_rpm", "driven_speed_rpm"), True, lo=0.0, lo_open=True, hi=1e6)
    torque, t_of = _one_of(t, ("driven_torque_nm", "driver_torque_nm"), not case_has_torque, lo=0.0, lo_open=True,
                           hi=1e7)
    if torque is not None and case_has_torque:
        key = f"{t_of}_torque_nm"
        raise InputError(t._key(key), t.data[key], "no torque in [rating]: the case's own torque is rated")
    service = Service(
        speed, of,
        life_hours=t.get("life_hours", float, lo=0.0, lo_open=True, hi=1e7),
        viscosity_40=t.get("viscosity_40_mm2s", float, lo=1.0, hi=10000.0),
        application_factor=t.get("application_factor", float, 1.0, lo=1.0, hi=4.0),
        min_safety_contact=t.get("min_safety_contact", float, 1.0, lo=0.5, hi=5.0),
        min_safety_bending=t.get("min_safety_bending", float, 1.0, lo=0.5, hi=5.0),
        long_life_contact=t.get("long_life_contact", float, 0.85, lo=0.85, hi=1.0),
        long_life_bending=t.get("long_life_bending", float, 0.85, lo=0.85, hi=1.0),
        limited_pitting=t.get("limited_pitting", bool, False))
    given = {}
    for key, (lo, hi) in GIVEN_RANGES.items():
        v = t.get(key, float, None, lo=lo, hi=hi)
        if v is not None:
            given[key] = Given(v, Source.INPUT, f"given in the case ([rating] {key})")
    grade = t.get("accuracy_grade", int, None, lo=0, hi=12)
    gt = t.table("gears")
    gears = {}
    for name in gear_names:
        gears[name] = _gear(gt.table(name), grade)
    extra = sorted(set(gt.data) - set(gear_names))
    if extra:
        raise InputError(gt._key(extra[0]), gt.data[extra[0]], "a gear of the case: " + ", ".join(gear_names))
    t.done()
    return RatingSpec(MappingProxyType(gears), service, MappingProxyType(given), None if torque is None else torque * 1e3,
                      t_of or "driven")


@dataclass(frozen=True)
class MeshRating:
    """One mesh to rate: its label ("pair", "sun-planet", "planet-ring"), the gearfe pair and its rating case."""

    label: str
    pair: GearPair
    rated: RatedPair


def train_names(train: DoubleHelicalTrain) -> tuple[str, ...]:
    """The gears of a Part 1 train that ``[rating.gears]`` names."""
    return (train.sun.name, train.planet.name, train.ring.name)


def train_meshes(train: DoubleHelicalTrain, spec: RatingSpec, ring_torque: float,
                  elastic) -> list[MeshRating]:
    r"""Sun-planet and planet-ring meshes of one member of a Part 1 train (carrier at rest, as the twin model).

    The double-helical train is rated member by member, each a single helical pair carrying half the load of its
    planet (ISO 6336 does not rate double-helical gears): per mesh the ring torque :math:`T_3/(2n)`, the sun speed
    relative to the carrier (``driver_speed_rpm``; ``driven_speed_rpm`` is the ring's), K_γ as given (else 1).
    """
    s, p, r, n = train.sun, train.planet, train.ring, train.planets
    a = train.center_distance
    sp, pr = GearPair(s, p, center_distance=a), GearPair(p, r, center_distance=a)
    sv = spec.service
    n_sun = sv.speed if sv.speed_of == "driver" else sv.speed * r.teeth / s.teeth
    gears = dict(spec.gears)
    for g in (s, r):  # the sun and the ring mesh with every planet once per revolution relative to the carrier
        gears[g.name] = replace(gears[g.name], contacts_per_revolution=n)
    per = ring_torque / (2 * n)
    out = []
    for label, pair, torque, speed, mesh in (
            ("sun-planet", sp, per * p.teeth / r.teeth, n_sun, MeshKind.SUN_PLANET),
            ("planet-ring", pr, per, n_sun * s.teeth / p.teeth, MeshKind.PLANET_RING)):
        rp = rating_case(pair, gears, replace(sv, speed=speed, speed_of="driver"), spec.load(torque, "driven"), elastic)
        case = replace(rp.case, mesh=mesh, planets=n, sun_is_pinion=rp.pinion == s.name)
        out.append(MeshRating(label, pair, replace(rp, case=case)))
    return out


def rated_meshes(record) -> list[MeshRating]:
    """The meshes of a case record with a rating (a StressCase: pair or twin model), in the FE model's material."""
    spec = record.rating
    if spec is None:
        return []
    elastic = (record.fe.material.E, record.fe.material.nu)
    if record.model == "pair":
        return [MeshRating("pair", record.pair, rating_case(record.pair, spec.gears, spec.service,
                                                             spec.load(record.torque, "driven"), elastic))]
    return train_meshes(record.train, spec, record.torque, elastic)


def check_rating(meshes: list[MeshRating]) -> None:
    """Rate every mesh once (milliseconds): values outside ISO's ranges fail here, before any work."""
    for m in meshes:
        try:
            rate(m.rated.case)
        except RatingInputError as e:
            raise InputError(f"rating.{e.key}", e.value, e.valid, (e.why + "; " if e.why else "") +
                             f"ISO 6336, mesh {m.label}, pinion {m.rated.pinion}, wheel {m.rated.wheel}") from None


def with_rating(case: Table, record):
    """``record`` (a :class:`pipelines.models.stress.case.StressCase`) with its ``[rating]`` read and checked.

    The one hook of the stress reader; the rating is computed once here (milliseconds) so that a value outside
    ISO's ranges is refused before any work.
    """
    t = case.table("rating", required=False)
    if t is None:
        return record
    names = (record.pair.gear1.name, record.pair.gear2.name) if record.model == "pair" else train_names(record.train)
    out = replace(record, rating=read_rating(t, names))
    check_rating(rated_meshes(out))
    return out
