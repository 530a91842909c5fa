"""Isotropic linear elastic material.

Hooke's law with Lamé constants

    lambda = E nu / ((1 + nu)(1 - 2 nu)),   mu = E / (2 (1 + nu)),
    sigma = lambda tr(eps) I + 2 mu eps.

The report (Numerical Example 1.3) uses steel, E = 2.068e5 MPa, nu = 0.29.
"""

from __future__ import annotations

from dataclasses import dataclass

from fem.errors import FEInputError

__all__ = ["Material", "STEEL"]


@dataclass(frozen=True)
class Material:
    """Isotropic elastic material: Young's modulus E [MPa] and Poisson's ratio nu [-]."""

    E: float = 2.068e5
    nu: float = 0.29

    def __post_init__(self):
        if not (self.E > 0.0):
            raise FEInputError("material.E", self.E, "a Young's modulus > 0 MPa")
        if not (-1.0 < self.nu < 0.5):
            raise FEInputError("material.nu", self.nu, "a Poisson's ratio in (-1, 0.5)")

    @property
    def lam(self) -> float:
        """First Lamé constant [MPa]."""
        return self.E * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu))

    @property
    def mu(self) -> float:
        """Shear modulus [MPa]."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def plane_strain_modulus(self) -> float:
        """E / (1 - nu^2) [MPa], the modulus of Hertz contact formulas."""
        return self.E / (1.0 - self.nu**2)


STEEL = Material(2.068e5, 0.29)
