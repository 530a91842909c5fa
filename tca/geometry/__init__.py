"""Gear geometry: tools (rack-cutter, plunging disk), generated tooth surfaces, gear data and working areas.

Tooth modifications (crowning, tip and end relief) live in :mod:`tca.geometry.modifications`.
"""

from tca.geometry.gear import FlankArea, Gear
from tca.geometry.modifications.tip_relief import TipRelief
from tca.geometry.rack import RackCutter, RackSegment
from tca.geometry.surfaces import DeviatedSurface, HelicoidSurface, SurfacePoints, ToothSurface

__all__ = ["FlankArea", "Gear", "TipRelief", "RackCutter", "RackSegment", "DeviatedSurface", "HelicoidSurface", "SurfacePoints", "ToothSurface"]
