"""A stress load case: the record of a gear-level contact-stress job (model, gears, position, torque,
mesh rules, FE settings). Its reader, with every case-file key, is :mod:`pipelines.cases.stress`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from tca.errors import InputError
from tca.pair.gear_pair import GearPair
from tca.pair.analysis import ARCSEC, TCAOptions
from tca.pair.te import GRID, NAMED, POSITIONS, path_angle
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors

from pipelines.models.stress.model import FESettings
from pipelines.models.stress.scene import PHASES
from pipelines.models.stress.sizing import SizeRules

__all__ = ["StressCase", "MODELS", "REGULATION"]

MODELS = ("pair", "twin", "train")


REGULATION = ("tca", "none", "given")


@dataclass(frozen=True)
class StressCase:
    """A stress load case: model, gears, position, torque [N mm], mesh rules and FE settings."""

    model: str
    torque: float  # [N mm] magnitude, on the driven gear (pair), the ring (twin) or the sun (train)
    title: str = ""
    pair: GearPair | None = None
    train: DoubleHelicalTrain | None = None
    errors: ShaftErrors = field(default_factory=ShaftErrors)
    regulation: str = "tca"
    dz: tuple = (0.0, 0.0)  # [mm] given axial regulation of members a, b
    regulation_tol: float = 1e-3 * ARCSEC  # [rad]
    regulation_maxiter: int = 12
    member_phase: str = ""  # 'assembled' or 'nominal'; '' -> 'nominal' without regulation, else 'assembled'
    position: object = "max_te"  # 'max_te', 'min_te', a grid index; pair model also 'pitch', 'hpstc', 'lpstc'
    phi1: float | None = None  # [rad] instead of position
    roll: float | None = None  # [rad] driver's roll angle at mid-face, instead of position (pair model)
    tca: TCAOptions = field(default_factory=TCAOptions)
    mesh: SizeRules = field(default_factory=SizeRules)
    fe: FESettings = field(default_factory=FESettings)
    rating: object = None  # pipelines.cases.rating.RatingSpec of the case's [rating] table; None: not rated
    train_case: object = None  # pipelines.models.trains.case.TrainCase of a 'train' model (an isostatic train case)

    def __post_init__(self):
        if self.model not in MODELS:
            raise InputError("model", self.model, "one of " + ", ".join(repr(m) for m in MODELS))
        if not (self.torque > 0 and math.isfinite(self.torque)):
            raise InputError("torque_nm", self.torque * 1e-3, "a torque > 0 N m")
        if self.model == "pair" and (self.pair is None or self.train is not None):
            raise InputError("model", self.model, "a gear pair (driver, driven) for model 'pair'")
        if self.model == "twin" and (self.train is None or self.pair is not None):
            raise InputError("model", self.model, "a planetary train (sun, planet, ring) for model 'twin'")
        if self.model == "train" and (self.train_case is None or self.pair is not None or self.train is not None):
            raise InputError("model", self.model, "an isostatic train case (sun, planets, ring) for model 'train'")
        if self.model == "train" and not (isinstance(self.position, int) and not isinstance(self.position, bool)
                                          and self.position >= 0):
            raise InputError("stress.position", self.position, "an integer >= 0: the index of a position of the train "
                             "LTCA's run")
        if self.regulation not in REGULATION:
            raise InputError("regulation.mode", self.regulation, "one of " + ", ".join(repr(m) for m in REGULATION))
        if not self.member_phase:
            object.__setattr__(self, "member_phase", "nominal" if self.regulation == "none" else "assembled")
        if self.member_phase not in PHASES:
            raise InputError("regulation.member_phase", self.member_phase, "one of " + ", ".join(repr(p) for p in PHASES))
        dz = tuple(float(x) for x in self.dz)
        if len(dz) != 2 or any(not math.isfinite(x) for x in dz):
            raise InputError("regulation.dz_mm", self.dz, "two finite numbers (members a and b)")
        object.__setattr__(self, "dz", dz)
        if self.train is not None:
            lim = 0.5 * self.train.planet.face_width
            if any(abs(x) > lim for x in dz):
                raise InputError("regulation.dz_a_mm", dz, f"|value| <= half the face width, {lim:g} mm")
        pos = self.position
        allowed = POSITIONS if self.model == "pair" else GRID
        if not (pos in allowed or (isinstance(pos, int) and not isinstance(pos, bool))):
            raise InputError("position", pos, ", ".join(repr(p) for p in allowed) + " or an integer index of the TCA positions"
                             + ("" if self.model == "pair" else " (named positions on the path of contact: pair model)"))
        if self.phi1 is not None and not math.isfinite(self.phi1):
            raise InputError("phi1_deg", self.phi1, "a finite angle")
        if self.roll is not None and (self.model != "pair" or self.phi1 is not None or not math.isfinite(self.roll)):
            raise InputError("roll_deg", math.degrees(self.roll), "a finite angle, pair model, without phi1_deg")
        if self.model == "pair" and self.phi1 is None and (self.roll is not None or pos in NAMED):
            path_angle(self.pair, pos, self.roll)  # a position off the path of contact fails here, before any work
