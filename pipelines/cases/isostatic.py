"""Reader of an isostatic planetary train (Part 3): gears, crowning, constraints, errors, run and solver."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from tca.geometry.modifications.crowning import DiskPlunge
from tca.isostatic.dof import TrainConstraints
from tca.errors import InputError
from tca.isostatic.analysis import IsostaticOptions, phi1_grid
from tca.isostatic.train import IsostaticTrain, PlanetPlacement

from pipelines.cases.planetary import check_train_meshes
from pipelines.cases.reader import read_gears
from pipelines.cases.schema import Table
from pipelines.models.trains.depth import check_pin_errors, depth_range

__all__ = ["read_train", "read_run", "read_solver"]

def _axis(t: Table, key: str, default: str) -> bool:
    return t.get(key, str, default, choices=("fixed", "floating")) == "floating"


def _vec_um(t: Table, key: str):
    v = t.get(key, list, [0.0, 0.0])
    if len(v) != 2 or not all(isinstance(a, (int, float)) and not isinstance(a, bool) and math.isfinite(a) for a in v):
        raise InputError(t._key(key), v, "a list of two numbers [x, y] in um")
    if max(abs(a) for a in v) > 1000:
        raise InputError(t._key(key), v, "|value| <= 1000 um")
    return (v[0] * 1e-3, v[1] * 1e-3)


def read_train(case: Table) -> IsostaticTrain:
    """The planetary train of an isostatic case (gears, crowning choice, constraints, errors)."""
    gears = read_gears(case)
    for name in ("sun", "planet", "ring"):
        if name not in gears:
            raise InputError(f"gears.{name}", None, "a gear table [gears.sun], [gears.planet] and [gears.ring]")
    extra = sorted(set(gears) - {"sun", "planet", "ring"})
    if extra:
        raise InputError(f"gears.{extra[0]}", extra[0], "only sun, planet and ring")
    sun, planet, ring = gears["sun"], gears["planet"], gears["ring"]
    variant = case.get("planets", str, "involute", choices=("involute", "double_crowned"))
    if planet.parabola_pos or planet.parabola_neg or planet.plunge is not None:
        raise InputError("gears.planet", "parabola/plunge keys", "an involute planet: the double crowning is given "
                         "in [crowning] and applied with planets = 'double_crowned'")
    cr = case.table("crowning", required=False)
    if cr is not None:
        a_p = cr.get("parabola_per_mm", float, lo=0.0, hi=0.5, hi_open=True)
        r_d = cr.get("disk_radius_mm", float, lo=0.0, lo_open=True)
        a_l = cr.get("plunge_parabola_per_mm", float, 0.0, lo=0.0, hi=0.1, hi_open=True)
        cr.done()
    elif variant == "double_crowned":
        raise InputError("crowning", None, "a [crowning] table when planets = 'double_crowned'")
    if variant == "double_crowned":
        planet = dataclasses.replace(planet, parabola_pos=a_p, parabola_neg=a_p,
                                     plunge=DiskPlunge(r_d, a_l) if a_l > 0 else None)
    t = case.table("train")
    n = t.get("planets", int, 3, lo=1, hi=12)
    cons = TrainConstraints(n, sun_axis_free=_axis(t, "sun_axis", "floating"),
                            carrier_axis_free=_axis(t, "carrier_axis", "fixed"),
                            ring_axis_free=_axis(t, "ring_axis", "fixed"))
    centres = {k: _vec_um(t, f"{k}_center_error_um") for k in ("sun", "carrier", "ring")}
    placements = [PlanetPlacement() for _ in range(n)]
    planets = [planet] * n
    seen = {}
    for e in t.tables("planet_errors", required=False):
        i = e.get("planet", int, lo=1, hi=n)
        if i - 1 in seen:
            raise InputError(f"{e.path}.planet", i, "each planet at most once")
        seen[i - 1] = e.path
        placements[i - 1] = PlanetPlacement(e.get("tangential_um", float, 0.0, lo=-1000, hi=1000) * 1e-3,
                                            e.get("radial_um", float, 0.0, lo=-1000, hi=1000) * 1e-3)
        ro = e.get("runout_um", float, 0.0, lo=0.0, hi=1000.0) * 1e-3
        ph = math.radians(e.get("runout_phase_deg", float, 0.0, lo=-360.0, hi=360.0))
        if ro:
            planets[i - 1] = dataclasses.replace(planet, name=f"planet{i}", runout=ro, runout_phase=ph)
        e.done()
    t.done()
    check_train_meshes(sun, planet, ring, sun.r_p + planet.r_p, gears)
    check_pin_errors(depth_range(sun, planet, ring), [(p.radial, p.tangential) for p in placements],
                     lambda i: f"{seen[i]}.radial_um")  # the planet's tips clear its mates' roots (one line, the key)
    return IsostaticTrain(sun, tuple(planets), ring, constraints=cons, placements=tuple(placements),
                          sun_center=centres["sun"], carrier_center=centres["carrier"], ring_center=centres["ring"])


def read_run(case: Table, train: IsostaticTrain) -> np.ndarray:
    r = case.table("run")
    spans = {k: r.get(k, float, None, lo=0.0, lo_open=True, hi=200.0)
             for k in ("sun_revolutions", "carrier_revolutions", "planet_revolutions")}
    positions = r.get("positions", int, 720, lo=1, hi=200000)
    start = math.radians(r.get("start_deg", float, 0.0, lo=-360.0, hi=360.0))
    r.done()
    return phi1_grid(train, positions, start=start, **spans)


def read_solver(case: Table) -> IsostaticOptions:
    s = case.table("solver", required=False)
    if s is None:
        return IsostaticOptions()
    o = IsostaticOptions(method=s.get("method", str, "fictitious", choices=("fictitious", "direct")))
    s.done()
    return o
