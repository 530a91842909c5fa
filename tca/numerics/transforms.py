"""Rotations and mounts: how a gear frame sits in the fixed frame S_f as it turns.

A :class:`Mount` places gear frame :math:`S_i` in :math:`S_f` as
:math:`r_f = o + R_0\\,R_z(\\phi + \\phi_0)\\,r_i` (cf. the matrices of Eqs. 3.7 and 3.12–3.16);
misalignments change :math:`o` and :math:`R_0`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["rot_x", "rot_y", "rot_z", "Mount"]


def rot_z(a):
    """Rotation matrices about z, shape (..., 3, 3)."""
    a = np.asarray(a, float)
    c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def rot_x(a):
    """Rotation matrices about x, shape (..., 3, 3)."""
    a = np.asarray(a, float)
    c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def rot_y(a):
    """Rotation matrices about y, shape (..., 3, 3)."""
    a = np.asarray(a, float)
    c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


_DRZ = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])


@dataclass(frozen=True, eq=False)
class Mount:
    """Gear frame in S_f: r_f = origin + R0 @ Rz(phi + phase) @ r  (origin [mm], phase [rad])."""

    origin: np.ndarray
    R0: np.ndarray
    phase: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "origin", np.asarray(self.origin, float).reshape(3))
        object.__setattr__(self, "R0", np.asarray(self.R0, float).reshape(3, 3))

    def rotation(self, phi):
        """R(phi) = R0 Rz(phi + phase) and dR/dphi, each (..., 3, 3)."""
        Rz = rot_z(np.asarray(phi, float) + self.phase)
        R = self.R0 @ Rz
        return R, R @ _DRZ

    @property
    def axis(self) -> np.ndarray:
        """Unit axis of rotation in S_f."""
        return self.R0[:, 2]

    def moved(self, translation=(0.0, 0.0, 0.0), rotation=None) -> "Mount":
        """Copy moved rigidly: rotation (about S_f origin) then translation."""
        Rm = np.eye(3) if rotation is None else np.asarray(rotation, float)
        return Mount(Rm @ self.origin + np.asarray(translation, float), Rm @ self.R0, self.phase)
