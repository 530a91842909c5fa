"""The record of a train case for the loaded TCA (read by :mod:`pipelines.cases.trains`)."""

from __future__ import annotations

from dataclasses import dataclass

from pipelines.models.trains.geometry import TrainErrors
from pipelines.models.trains.options import TrainOptions

__all__ = ["TrainCase"]


@dataclass(frozen=True, eq=False)
class TrainCase:
    """What gearfe ltca runs for a train: the gears, planets, errors, options; ``twin`` for Part 1 trains."""

    kind: str  # 'isostatic' or 'planetary'
    title: str
    sun: object  # Gear
    planet: object
    ring: object
    planets: int
    errors: TrainErrors  # small rigid errors entered as offsets (isostatic)
    opts: TrainOptions
    twin: object = None  # DoubleHelicalTrain (planetary)
    shaft_errors: tuple = ()  # ShaftErrors per shaft (planetary)
    regulation: object = None  # RegulationSettings (planetary)
    rating: object = None  # RatingSpec of an optional [rating] table (planetary: ISO 6336 with the run's K_gamma)
