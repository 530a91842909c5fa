"""Gears of Table 1.1 (Part 1) and Table 3.1 (Part 3) shared by the mesher tests (built once)."""

from __future__ import annotations

import math
from functools import lru_cache

from tca import DiskPlunge, Gear

R = math.radians


@lru_cache(maxsize=None)
def gear(name: str) -> Gear:
    """Table 1.1 sun/planet/ring (regulated helices 10.25 / 10 / 9.75 deg on the 10 deg transverse
    geometry) and Table 3.1 sun3/planet3/ring3 (module 4, spur)."""
    if name == "sun":
        return Gear("sun", 41, 2.0, R(20), 30.0, helix=R(10.25), hand=1, reference_helix=R(10))
    if name == "planet":
        return Gear("planet", 34, 2.0, R(20), 30.0, helix=R(10), hand=-1, parabola_pos=0.008, parabola_neg=0.005,
                    plunge=DiskPlunge(100.0, 0.002))
    if name == "ring":
        return Gear("ring", 109, 2.0, R(20), 30.0, helix=R(9.75), hand=-1, reference_helix=R(10), internal=True,
                    parabola_pos=0.002, parabola_neg=0.002)
    if name == "sun3":
        return Gear("sun3", 65, 4.0, R(20), 40.0)
    if name == "planet3":
        return Gear("planet3", 43, 4.0, R(20), 40.0, parabola_pos=1.25e-3, parabola_neg=1.25e-3,
                    plunge=DiskPlunge(100.0, 6.25e-5))
    if name == "ring3":
        return Gear("ring3", 151, 4.0, R(20), 40.0, internal=True)
    raise KeyError(name)


ALL = ("sun", "planet", "ring", "sun3", "planet3", "ring3")
