"""Options of the loaded TCA of a planetary train: positions, torques, the flank grid, supports, the FE check.
Read from the ``[ltca]`` table of a train case by :mod:`pipelines.cases.trains`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from fem.material import Material
from tca.errors import InputError
from tca.pair.analysis import TCAOptions

from pipelines.models.ltca.options import check_flank_grid
from fem.material import STEEL
from pipelines.models.stress.model import ELEMENTS

__all__ = ["TrainOptions", "SUN_AXIS"]

SUN_AXIS = ("fixed", "floating")


@dataclass(frozen=True)
class TrainOptions:
    """Positions (per ring mesh cycle, over carrier revolutions), torques on the sun [N mm], flank grid [mm]
    (None: defaults from the module m, :meth:`sizes`), the sun's axis, the stiffnesses of the sun's support and
    of the planet pins [N/mm] (None: rigid), material, element, TCA resolution, modelled teeth, FE check."""

    positions_per_cycle: int = 10
    carrier_revolutions: float = 1.0
    torques: tuple = (1e6,)
    profile_size: float | None = None
    axial_size: float | None = None
    slice: float | None = None
    reach: float = 0.05  # [mm]
    local: str = "strip"
    sun_axis: str = "fixed"
    sun_support: float | None = None  # [N/mm] of a held sun axis (None: rigid)
    pin_stiffness: float | None = None  # [N/mm] (None: rigid pins)
    material: Material = STEEL
    element: str = "C3D8I"
    solver: str = "auto"
    tca: TCAOptions = field(default_factory=TCAOptions)
    teeth: int = 3
    regulation: str = "tca"  # Part 1: 'none', 'first_order' (ΔZ^(1), Eq. 1.16) or 'tca' (ΔZ^(2))
    check_positions: int = 0

    def __post_init__(self):
        if not (isinstance(self.positions_per_cycle, int) and 1 <= self.positions_per_cycle <= 1000):
            raise InputError("ltca.positions_per_cycle", self.positions_per_cycle, "an integer in [1, 1000]")
        if not (0 < self.carrier_revolutions <= 20 and math.isfinite(self.carrier_revolutions)):
            raise InputError("ltca.carrier_revolutions", self.carrier_revolutions, "a number in (0, 20]")
        t = tuple(float(x) for x in self.torques)
        if not t or any(not (x > 0 and math.isfinite(x)) for x in t):
            raise InputError("ltca.torques_nm", [x * 1e-3 for x in t], "a non-empty list of torques > 0 N m")
        object.__setattr__(self, "torques", t)
        check_flank_grid(self)
        if self.sun_axis not in SUN_AXIS:
            raise InputError("ltca.sun_axis", self.sun_axis, "one of " + ", ".join(repr(x) for x in SUN_AXIS))
        for key, v in (("sun_support_n_per_um", self.sun_support), ("pin_stiffness_n_per_um", self.pin_stiffness)):
            if v is not None and not (v > 0 and math.isfinite(v)):
                raise InputError(f"ltca.{key}", v * 1e-3 if isinstance(v, (int, float)) else v, "> 0 N/um (leave it out: rigid)")
        if self.sun_support is not None and self.sun_axis == "floating":
            raise InputError("ltca.sun_support_n_per_um", self.sun_support * 1e-3, "left out for a floating sun "
                             "(a floating sun has no support)")
        if self.element not in ELEMENTS:
            raise InputError("ltca.element", self.element, "one of " + ", ".join(repr(e) for e in ELEMENTS))
        if not (isinstance(self.teeth, int) and 3 <= self.teeth <= 9 and self.teeth % 2 == 1):
            raise InputError("ltca.teeth", self.teeth, "an odd integer in [3, 9]")
        if self.regulation not in ("none", "first_order", "tca"):
            raise InputError("ltca.regulation", self.regulation, "one of 'none', 'first_order', 'tca'")
        if not (isinstance(self.check_positions, int) and 0 <= self.check_positions <= 20):
            raise InputError("ltca.check_positions", self.check_positions, "an integer in [0, 20]")

    def sizes(self, module: float, face_width: float = math.inf) -> tuple[float, float, float]:
        """(profile, axial, slice) [mm]: the pair LTCA's defaults 0.15 m, min(0.5 m, b/14), 0.25 m."""
        return (self.profile_size if self.profile_size is not None else 0.15 * module,
                self.axial_size if self.axial_size is not None else min(0.5 * module, face_width / 14.0),
                self.slice if self.slice is not None else 0.25 * module)
