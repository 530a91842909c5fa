"""Options of a loaded TCA: positions, torques, the flank grid and the local flattening law.
Read from the ``[ltca]`` table by :mod:`pipelines.cases.ltca`."""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.errors import InputError

__all__ = ["LTCAOptions", "LOCAL", "check_flank_grid"]

LOCAL = ("strip", "weber")


def check_flank_grid(o) -> None:
    """The flank grid of a pair's or a train's options: sizes [mm] > 0 or None, reach [mm] > 0, a known local law."""
    for k in ("profile_size", "axial_size", "slice"):
        v = getattr(o, k)
        if v is not None and not (v > 0 and math.isfinite(v)):
            raise InputError(f"ltca.{k}_mm", v, "> 0 mm")
    if not (o.reach > 0 and math.isfinite(o.reach)):
        raise InputError("ltca.reach_um", o.reach * 1e3, "> 0 um")
    if o.local not in LOCAL:
        raise InputError("ltca.local", o.local, "one of " + ", ".join(repr(x) for x in LOCAL))


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
        check_flank_grid(self)
        if not (isinstance(self.check_positions, int) and 0 <= self.check_positions <= self.positions):
            raise InputError("ltca.check_positions", self.check_positions, f"an integer in [0, positions = {self.positions}]")

    def sizes(self, module: float, face_width: float = math.inf) -> tuple[float, float, float]:
        """(profile, axial, slice) sizes [mm] for gears of module m and face width b [mm]: defaults 0.15 m,
        min(0.5 m, b/14) (at least 14 axial elements: a narrow spur face at 0.5 m is 2.5 % too stiff,
        docs/ltca.md) and 0.25 m."""
        return (self.profile_size if self.profile_size is not None else 0.15 * module,
                self.axial_size if self.axial_size is not None else min(0.5 * module, face_width / 14.0),
                self.slice if self.slice is not None else 0.25 * module)
