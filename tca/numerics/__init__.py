"""Numerical building blocks of the TCA: batched Newton solves, Chebyshev fits, rotations and mounts.
"""

from tca.numerics.newton import NewtonOptions, NewtonResult, PreferredPoint, newton
from tca.numerics.chebyshev import Cheb2D, cheb_points
from tca.numerics.transforms import Mount, rot_x, rot_y, rot_z

__all__ = ["NewtonOptions", "NewtonResult", "PreferredPoint", "newton", "Cheb2D", "cheb_points", "Mount", "rot_x",
           "rot_y", "rot_z"]
