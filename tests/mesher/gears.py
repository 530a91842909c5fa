"""Gears of Table 1.1 (Part 1) and Table 3.1 (Part 3) shared by the mesher tests (built once)."""

from __future__ import annotations

from functools import lru_cache

from tca import Gear
from tca.report_data import (table_1_1_planet, table_1_1_ring, table_1_1_sun, table_3_1_planet, table_3_1_ring,
                              table_3_1_sun)

_BUILDERS = {
    "sun": table_1_1_sun,
    "planet": table_1_1_planet,
    "ring": table_1_1_ring,
    "sun3": lambda: table_3_1_sun("sun3"),
    "planet3": lambda: table_3_1_planet(crowned=True, name="planet3"),
    "ring3": lambda: table_3_1_ring("ring3"),
}


@lru_cache(maxsize=None)
def gear(name: str) -> Gear:
    """Table 1.1 sun/planet/ring (regulated helices 10.25 / 10 / 9.75 deg on the 10 deg transverse
    geometry) and Table 3.1 sun3/planet3/ring3 (module 4, spur, double-crowned planet)."""
    return _BUILDERS[name]()


ALL = ("sun", "planet", "ring", "sun3", "planet3", "ring3")
