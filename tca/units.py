"""Angle units: the one definition of the constants used to convert at the edges (internal unit: rad).

Case files and outputs carry degrees, arcminutes and arcseconds in their key names (``helix_deg``,
``d_gamma_arcmin``, ``te_peak_to_peak_arcsec``); everything inside gearfe is in radians.
"""

import math

__all__ = ["DEG", "ARCMIN", "ARCSEC"]

DEG = math.pi / 180.0  # one degree [rad]
ARCMIN = DEG / 60.0  # one arcminute [rad]
ARCSEC = DEG / 3600.0  # one arcsecond [rad]
