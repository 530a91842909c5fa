"""The loaded TCA of a planetary train (``gearfe ltca``): an isostatic (Part 3) or planetary (Part 1) case as shipped,
with an optional ``[ltca]`` table. Keys of ``[ltca]`` (all optional, every key checked)::

    [ltca]
    torques_nm = [3120.0]         # torques on the sun [N m]; default: 200 N/mm of face width per planet (docs/trains.md)
    positions_per_cycle = 10      # positions per mesh cycle (one sun pitch relative to the carrier)
    carrier_revolutions = 1.0     # the run: N3 mesh cycles per carrier revolution
    profile_size_mm = 0.6         # flank grid (default 0.15 m), axial size (default min(0.5 m, b/14)), slice (0.25 m)
    axial_size_mm = 2.0
    slice_mm = 1.0
    reach_um = 50.0
    teeth = 3                     # teeth of each flank model (odd, 3..9)
    sun_support_n_per_um = 500.0  # a held sun axis on a support of this stiffness (isostatic: sun_axis = "fixed")
    pin_stiffness_n_per_um = 300.0  # elastic planet pins (default rigid)
    regulation = "tca"            # planetary: axial regulation "none", "first_order" (dZ^(1)) or "tca" (dZ^(2))

Isostatic cases may be helical (``helix_deg``, ``hand``, optional ``reference_helix_deg`` in the gear tables, normal
module; the planet of the opposite hand to the sun, the ring of the planet's; involute planets): the loaded TCA
builds helical meshes, while the unloaded Part 3 TCA (``gearfe tca``) stays planar and refuses them.
``[train] sun_axis`` (floating or fixed), the planet pin errors (tangential, radial) and run-outs,
the sun's run-out and centre error, the carrier's centre error; the carrier and the ring held (their axes fixed).
Planetary cases: the installment errors of every shaft and the regulation are built into the meshes.

Refused before any work (one line, exit 2): a pin error beyond the range of :mod:`pipelines.models.trains.depth`
(a tip meets a root, or the planet leaves a mesh; checked by the isostatic reader), and flank models whose
estimated memory exceeds ``GEARFE_MAX_MEMORY_GB`` (:mod:`pipelines.models.trains.plan`).
"""

from __future__ import annotations

import copy
import math

from tca.errors import InputError
from tca.pair.analysis import TCAOptions

from pipelines.cases.ltca_options import read_flank_grid_keys, read_torques
from pipelines.cases.rating import read_rating, train_names
from pipelines.cases.schema import Table
from pipelines.models.trains.case import TrainCase
from pipelines.models.trains.geometry import TrainErrors
from pipelines.models.trains.options import TrainOptions
from pipelines.models.trains.plan import check_train_plan

__all__ = ["read_isostatic_ltca", "read_planetary_ltca", "default_torque", "LINE_LOAD"]

LINE_LOAD = 200.0  # [N/mm] default tangential load per planet mesh and mm of face width at the sun's pitch circle


def default_torque(sun, planets: int, members: int = 1) -> float:
    """T [N mm] = n · members · LINE_LOAD · b · r_1 (the sun's pitch radius r_1)."""
    return planets * members * LINE_LOAD * sun.face_width * sun.r_p


def _read_ltca(t: Table | None, torque: float, tca: TCAOptions, **fixed) -> TrainOptions:
    if t is None:
        return TrainOptions(torques=(torque,), tca=tca, **fixed)
    torques = read_torques(t, torque)
    stiff = dict(lo=0.0, lo_open=True, hi=1e6)
    sup = t.get("sun_support_n_per_um", float, None, **stiff)
    pins = t.get("pin_stiffness_n_per_um", float, None, **stiff)
    kw = dict(
        positions_per_cycle=t.get("positions_per_cycle", int, 10, lo=1, hi=1000),
        carrier_revolutions=t.get("carrier_revolutions", float, 1.0, lo=0.0, lo_open=True, hi=20.0),
        torques=torques,
        **read_flank_grid_keys(t),
        teeth=t.get("teeth", int, 3, lo=3, hi=9),
        sun_support=None if sup is None else sup * 1e3,
        pin_stiffness=None if pins is None else pins * 1e3,
        tca=tca,
    )
    if "regulation" in fixed:
        kw["regulation"] = t.get("regulation", str, "tca", choices=("none", "first_order", "tca"))
        fixed = {k: v for k, v in fixed.items() if k != "regulation"}
    t.done()
    return TrainOptions(**kw, **fixed)


def read_isostatic_ltca(case: Table) -> TrainCase:
    """An isostatic case (Part 3) for gearfe ltca (module docstring)."""
    from pipelines.cases.isostatic import read_run, read_solver, read_train

    lt = case.table("ltca", required=False)
    title = case.get("title", str, "")
    helical = _take_helix(case)  # the Part 3 train and its unloaded TCA are planar: read as spur, then helical
    train = read_train(case)
    read_run(case, train)  # the unloaded run's keys are checked (the loaded run has its own positions)
    read_solver(case)
    c = train.constraints
    if c.carrier_axis_free or c.ring_axis_free:
        raise InputError("train.carrier_axis" if c.carrier_axis_free else "train.ring_axis", "floating",
                         "'fixed' for gearfe ltca (the loaded TCA holds the ring and the carrier's axis)")
    sun, ring = train.sun, train.ring
    planet = train.planets[0]
    n = train.n_planets
    if helical is not None:
        sun, planet, ring = _helical_gears(case, helical, train)
    _check_assembly(sun, planet, ring, n)
    rv = [tuple(float(v) for v in g.tooth_transform(0)[1][:2]) for g in train.planets]
    errors = TrainErrors(pins=tuple((p.radial, p.tangential) for p in train.placements), planet_runout=tuple(rv),
                         sun_runout=tuple(float(v) for v in sun.tooth_transform(0)[1][:2]),
                         ring_runout=tuple(float(v) for v in ring.tooth_transform(0)[1][:2]),
                         sun_center=tuple(train.sun_center), carrier_center=tuple(train.carrier_center),
                         ring_center=tuple(train.ring_center))
    axis = "floating" if c.sun_axis_free else "fixed"
    opts = _read_ltca(lt, default_torque(sun, n), TCAOptions(), sun_axis=axis)
    if opts.sun_support is not None and axis == "floating":
        raise InputError("ltca.sun_support_n_per_um", opts.sun_support * 1e-3,
                         "left out where [train] sun_axis = 'floating' (set sun_axis = 'fixed' for a supported sun)")
    if opts.sun_support is not None:
        from dataclasses import replace

        opts = replace(opts, sun_axis="fixed")
    check_train_plan(sun, planet, ring, opts)  # GEARFE_MAX_MEMORY_GB, before any work
    return TrainCase("isostatic", title, sun, planet, ring, n, errors, opts)


HELIX_KEYS = ("helix_deg", "reference_helix_deg", "hand")


def _take_helix(case: Table) -> dict | None:
    """The gear tables as written when one has a helix key (which are then taken out of the case for the planar
    Part 3 reader), else None."""
    g = case.data.get("gears")
    if not isinstance(g, dict) or not any(isinstance(v, dict) and any(k in v for k in HELIX_KEYS) for v in g.values()):
        return None
    full = copy.deepcopy(g)
    for v in g.values():
        if isinstance(v, dict):
            for k in HELIX_KEYS:
                v.pop(k, None)
    return full


def _helical_gears(case: Table, tables: dict, train) -> tuple:
    """Sun, planet and ring read with their helix keys (a user's helical single-member train): the planet of the
    opposite hand to the sun, the ring of the planet's; the meshes' pair checks and the pin error range redone on
    the helical gears."""
    from pipelines.cases.planetary import check_train_meshes
    from pipelines.cases.reader import read_gears
    from pipelines.models.trains.depth import check_pin_errors, depth_range

    if case.data.get("planets", "involute") != "involute":
        raise InputError("planets", case.data["planets"], "'involute' for a helical train (the double crowning of "
                         "Part 3 is planar)")
    g = read_gears(Table({"gears": tables}, ""))
    sun, planet, ring = g["sun"], g["planet"], g["ring"]
    hand = {1: "right", -1: "left"}
    if planet.helix != sun.helix or ring.helix != sun.helix:
        bad = "planet" if planet.helix != sun.helix else "ring"
        raise InputError(f"gears.{bad}.helix_deg", math.degrees(g[bad].helix), f"the sun's {math.degrees(sun.helix):g}")
    if sun.helix and planet.hand == sun.hand:
        raise InputError("gears.planet.hand", hand[planet.hand], f"{hand[-sun.hand]!r} (opposite to the sun)")
    if sun.helix and ring.hand != planet.hand:
        raise InputError("gears.ring.hand", hand[ring.hand], f"{hand[planet.hand]!r} (the planet's hand)")
    check_train_meshes(sun, planet, ring, sun.r_p + planet.r_p, g)
    check_pin_errors(depth_range(sun, planet, ring), [(p.radial, p.tangential) for p in train.placements],
                     lambda i: "train.planet_errors.radial_um")
    return sun, planet, ring


def read_planetary_ltca(case: Table) -> TrainCase:
    """A Part 1 planetary case (double-helical twins) for gearfe ltca (module docstring)."""
    from pipelines.cases.planetary import read_installment, read_regulation_options, read_train
    from pipelines.cases.reader import read_tca_options

    lt = case.table("ltca", required=False)
    title = case.get("title", str, "")
    train = read_train(case)
    errors = read_installment(case.table("installment", required=False), train.planets)
    reg = read_regulation_options(case.table("regulation", required=False))
    tca = read_tca_options(case.table("tca", required=False))
    _check_assembly(train.sun, train.planet, train.ring, train.planets)
    opts = _read_ltca(lt, default_torque(train.sun, train.planets, 2), tca, regulation="tca")
    rating = read_rating(case.table("rating", required=False), train_names(train))  # rated at the run's torques
    check_train_plan(train.sun, train.planet, train.ring, opts)  # GEARFE_MAX_MEMORY_GB, before any work
    return TrainCase("planetary", title, train.sun, train.planet, train.ring, train.planets, TrainErrors(), opts,
                     train, tuple(errors), reg, rating)


def _check_assembly(sun, planet, ring, n: int) -> None:
    """(N1 + N3)/n an integer, N3 = N1 + 2 N2 and planets that do not collide (InputError otherwise)."""
    N1, N2, N3 = sun.teeth, planet.teeth, ring.teeth
    if (N1 + N3) % n:
        raise InputError("train.planets", n, f"a divisor of N1 + N3 = {N1 + N3} (equally spaced planets assemble "
                         "only then)")
    if N3 != N1 + 2 * N2:
        raise InputError("gears.ring.teeth", N3, f"N1 + 2 N2 = {N1 + 2 * N2} (standard centre distances)")
    E = sun.r_p + planet.r_p
    tip = planet.r_p + planet.module * planet.addendum
    if n > 1 and 2 * E * math.sin(math.pi / n) <= 2 * tip:
        raise InputError("train.planets", n, f"at most {int(math.pi / math.asin(min(1.0, tip / E)))} planets: "
                         f"neighbouring planets' tip circles (radius {tip:.3f} mm) collide at centre distance "
                         f"{E:.3f} mm")
