"""A loaded-TCA case: a stress case (``kind = "stress"``, ``model = "pair"``) with an optional ``[ltca]`` table.

Keys of ``[ltca]`` (all optional; every key is checked, unknown keys are rejected)::

    [ltca]
    positions = 100               # positions over one mesh cycle (one angular pitch of the driver)
    torques_nm = [78.0, 156.0]    # torques on the driven gear [N m]; default [torque_nm]
    profile_size_mm = 0.3         # flank grid: profile size; default 0.15 m
    axial_size_mm = 1.0           # flank grid: axial size, also the size of the body's elements; default min(0.5 m, b/14)
    slice_mm = 0.5                # length of a contact-line slice; default 0.25 m
    reach_um = 50.0               # pairs of teeth separated by more than this (TCA) are left out
    check_positions = 0           # positions also solved by the full contact FE (gearfe stress) for the check

The flank models take ``[mesh] teeth`` of the stress case (rim depth 3 m, elements of the axial size
away from the flanks) and the material and element of ``[fe]``; the full-FE check runs the stress
case itself (its ``[mesh]`` and ``[fe]``) at the checked positions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.errors import InputError

from pipelines.cases.schema import Table
from pipelines.cases.stress import StressCase, read_stress_case

__all__ = ["LTCAOptions", "read_ltca_case", "LOCAL"]

LOCAL = ("strip", "weber")


@dataclass(frozen=True)
class LTCAOptions:
    """Positions, torques [N mm] and the flank grid [mm] of a loaded TCA (None: module defaults from the module m)."""

    positions: int = 100
    torques: tuple = ()
    profile_size: float | None = None
    axial_size: float | None = None
    slice: float | None = None
    reach: float = 0.05  # [mm]
    check_positions: int = 0
    local: str = "strip"  # constant of the flattening formula (pipelines.models.ltca.compliance): 'strip' or 'weber'

    def __post_init__(self):
        if not (isinstance(self.positions, int) and 1 <= self.positions <= 100000):
            raise InputError("ltca.positions", self.positions, "an integer in [1, 100000]")
        t = tuple(float(x) for x in self.torques)
        if any(not (x > 0 and math.isfinite(x)) for x in t):
            raise InputError("ltca.torques_nm", [x * 1e-3 for x in t], "a list of torques > 0 N m")
        object.__setattr__(self, "torques", t)
        for k in ("profile_size", "axial_size", "slice"):
            v = getattr(self, k)
            if v is not None and not (v > 0 and math.isfinite(v)):
                raise InputError(f"ltca.{k}_mm", v, "> 0 mm")
        if not (self.reach > 0 and math.isfinite(self.reach)):
            raise InputError("ltca.reach_um", self.reach * 1e3, "> 0 um")
        if self.local not in LOCAL:
            raise InputError("ltca.local", self.local, "one of " + ", ".join(repr(x) for x in LOCAL))
        if not (isinstance(self.check_positions, int) and 0 <= self.check_positions <= self.positions):
            raise InputError("ltca.check_positions", self.check_positions, f"an integer in [0, positions = {self.positions}]")

    def sizes(self, module: float, face_width: float = math.inf) -> tuple[float, float, float]:
        """(profile, axial, slice) sizes [mm] for gears of module m and face width b [mm]: defaults 0.15 m,
        min(0.5 m, b/14) (at least 14 axial elements: a narrow spur face at 0.5 m is 2.5 % too stiff,
        docs/ltca.md) and 0.25 m."""
        return (self.profile_size if self.profile_size is not None else 0.15 * module,
                self.axial_size if self.axial_size is not None else min(0.5 * module, face_width / 14.0),
                self.slice if self.slice is not None else 0.25 * module)


def _read_ltca(t: Table | None, torque: float) -> LTCAOptions:
    if t is None:
        return LTCAOptions(torques=(torque,))
    pos = dict(lo=0.0, lo_open=True, hi=100.0)
    tq = t.get("torques_nm", list, None)
    if tq is not None:
        if not tq or any(isinstance(x, bool) or not isinstance(x, (int, float)) or not (0 < x <= 1e7) for x in tq):
            raise InputError("ltca.torques_nm", tq, "a non-empty list of torques in (0, 1e7] N m")
        torques = tuple(float(x) * 1e3 for x in tq)
    else:
        torques = (torque,)
    o = LTCAOptions(
        positions=t.get("positions", int, 100, lo=1, hi=100000),
        torques=torques,
        profile_size=t.get("profile_size_mm", float, None, **pos),
        axial_size=t.get("axial_size_mm", float, None, **pos),
        slice=t.get("slice_mm", float, None, **pos),
        reach=t.get("reach_um", float, 50.0, lo=0.0, lo_open=True, hi=5000.0) * 1e-3,
        check_positions=t.get("check_positions", int, 0, lo=0, hi=100),
        local=t.get("local", str, "strip", choices=LOCAL),
    )
    t.done()
    return o


def read_ltca_case(case: Table) -> tuple[StressCase, LTCAOptions]:
    """The stress case and the ``[ltca]`` options of a case table; InputError on any bad key or value."""
    lt = case.table("ltca", required=False)
    sc = read_stress_case(case)
    if sc.model != "pair":
        raise InputError("model", sc.model, "'pair' (gearfe ltca models a gear pair; the twin drive is not supported yet)")
    return sc, _read_ltca(lt, sc.torque)
