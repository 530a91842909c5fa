"""Reader of a face-gear planetary train (Part 2): the four gears, the shaper, the installation angle, options."""

from __future__ import annotations

import math

from tca.errors import InputError
from tca.face.face_gear import FaceGear
from tca.face.train import FaceTrain

from pipelines.cases.reader import read_gear
from pipelines.cases.schema import Table

__all__ = ["read_face_train"]

_DEFAULT_MEMBERS = {"reducer": ("gear4", "carrier", "gear1"), "multiplier": ("gear1", "carrier", "gear4")}


def _face_gear(t: Table, name: str, shaper) -> FaceGear:
    ri = t.get("inner_radius_mm", float, None, lo=0.0, lo_open=True)
    ro = t.get("outer_radius_mm", float, None, lo=0.0, lo_open=True)
    try:
        g = FaceGear(
            name=name,
            teeth=t.get("teeth", int, lo=3, hi=2000),
            shaper=shaper,
            shaft_angle=math.radians(t.get("shaft_angle_deg", float, lo=30.0, hi=150.0)),
            crowning=t.get("crowning_per_mm", float, 0.0, lo=0.0, hi=0.1, hi_open=True),
            addendum=t.get("addendum", float, 1.0, lo=0.0, lo_open=True, hi=1.5),
            pinion_addendum=t.get("pinion_addendum", float, 1.0, lo=0.0, lo_open=True, hi=2.0),
            inner_radius=ri,
            outer_radius=ro,
        )
    except InputError as e:  # name the key as in the case file
        raise InputError(f"{t.path}.{e.field.split('.', 1)[-1]}", e.value, e.valid) from None
    t.done()
    return g


def read_face_train(case: Table) -> tuple[FaceTrain, dict]:
    """The train and the analysis options of a face_train case (teeth checked before any geometry)."""
    use = case.get("use", str, "reducer", choices=("reducer", "multiplier"))
    delta = case.get("delta_rad", float, lo=-2 * math.pi, hi=2 * math.pi)
    loss = case.get("loss_per_mesh", float, 0.02, lo=0.0, hi=0.5, hi_open=True)
    n = {k: case.table(k).get("teeth", int, lo=3, hi=2000) for k in ("gear1", "pinion2", "pinion3", "gear4")}
    if n["gear1"] * n["pinion3"] == n["pinion2"] * n["gear4"]:
        raise InputError("gear1.teeth, pinion2.teeth, pinion3.teeth, gear4.teeth",
                         (n["gear1"], n["pinion2"], n["pinion3"], n["gear4"]),
                         "N1 N3 != N2 N4", f"{n['gear1']}*{n['pinion3']} = {n['pinion2']}*{n['gear4']}: the planetary "
                         f"train would not move (ratio of Eq. 2.2 infinite)")
    tt = case.table("train", required=False)
    fixed, driver, driven = _DEFAULT_MEMBERS[use]
    if tt is not None:
        members = ("gear1", "gear4", "carrier")
        fixed = tt.get("fixed", str, fixed, choices=members)
        driver = tt.get("input", str, driver, choices=members)
        driven = tt.get("output", str, driven, choices=members)
        tt.done()
    shaper = read_gear(case.table("shaper"), "shaper")
    g1 = _face_gear(case.table("gear1"), "gear1", shaper)
    g4 = _face_gear(case.table("gear4"), "gear4", shaper)
    p2 = read_gear(case.table("pinion2"), "pinion2")
    p3 = read_gear(case.table("pinion3"), "pinion3")
    for g in (shaper, p2, p3):
        if g.end_relief is not None:  # the face-gear TCA (tca.face.face_gear) has no search of relieved zones
            raise InputError(f"{g.name}.end_relief", "given", "no [end_relief] in a face-gear drive (pair TCA only)")
    train = FaceTrain(g1, g4, p2, p3, delta, use)
    t = case.table("tca", required=False)
    opts = {"cycles": 3, "steps_per_cycle": 60, "mesh_steps_per_cycle": 120, "delta_samples": 73}
    if t is not None:
        opts["cycles"] = t.get("cycles", int, 3, lo=1, hi=50)
        opts["steps_per_cycle"] = t.get("steps_per_cycle", int, 60, lo=4, hi=2000)
        opts["mesh_steps_per_cycle"] = t.get("mesh_steps_per_cycle", int, 120, lo=8, hi=5000)
        opts["delta_samples"] = t.get("delta_samples", int, 73, lo=8, hi=2000)
        t.done()
    p = case.table("plots", required=False)
    opts["delta_offsets"] = [0.0, -0.05, 0.05, 0.1]
    if p is not None:
        offs = p.get("delta_offsets_rad", list, opts["delta_offsets"])
        if not offs or len(offs) > 8 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in offs):
            raise InputError("plots.delta_offsets_rad", offs, "a list of 1 to 8 numbers [rad]")
        opts["delta_offsets"] = [float(v) for v in offs]
        p.done()
    opts.update(use=use, loss=loss, members=(fixed, driver, driven))
    return train, opts
