r"""Where a gear's modelled teeth go at a contact position: its loaded tooth and its frame in :math:`S_f`.

This is the one path by which a pair is placed and meshed at a TCA position: :func:`mesher.mesh_pair`
(a pair at a TCA grid position) and the gear stress scenes (:mod:`pipelines.models.stress.scene`, any
angle, several meshes) both take the contact from :func:`tca.pair.te.mesh_contact` and place and mesh
each gear with the functions here.

The TCA's pair k in contact at :math:`\phi_1` is the reference pair solved at :math:`\phi_1 - 2\pi k/N_1`:
at :math:`\phi_1` it is tooth :math:`j = -k \bmod N` of each gear (:func:`loaded_tooth`). A gear turned
by :math:`\phi` on its mount sits at :math:`x_m = o + R_0 R_z(\phi + \phi_0)\,x`
(:class:`tca.numerics.transforms.Mount`); a scene may map the pair frame into :math:`S_f` by a further
affine frame :math:`x_f = F x_m + f` (the twin drive's planet shafts), so
:math:`x_f = R x + t` with :math:`R = F R_m`, :math:`t = F o + f` (:func:`gear_pose`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem.mesh.hexmesh import HexMesh
from tca.geometry.gear import Gear
from tca.numerics.transforms import Mount

from mesher.body import Focus, MeshOptions, mesh_gear

__all__ = ["Pose", "IDENTITY", "gear_pose", "loaded_tooth", "mesh_placed"]


@dataclass(frozen=True, eq=False)
class Pose:
    """An affine placement x_f = R x + t of a gear frame [mm]."""

    R: np.ndarray
    t: np.ndarray


IDENTITY = Pose(np.eye(3), np.zeros(3))


def gear_pose(mount: Mount, phi: float, frame: Pose = IDENTITY) -> Pose:
    """Pose of a gear turned by phi [rad] on its mount, in the frame ``frame`` of the scene (module docstring)."""
    Rm, _ = mount.rotation(phi)
    return Pose(frame.R @ Rm, frame.R @ mount.origin + frame.t)


def loaded_tooth(gear: Gear, k: int) -> int:
    """The gear's own index of the tooth of TCA pair k at the analysed angle."""
    return (-int(k)) % gear.teeth


def mesh_placed(gear: Gear, opts: MeshOptions, centre: int, focus: Focus, pose: Pose, *, others: tuple = (),
                member_offset: float | None = None) -> HexMesh:
    """The modelled teeth of a gear around its loaded tooth ``centre``, graded at ``focus`` (and ``others``),
    placed by ``pose``."""
    m = mesh_gear(gear, opts, centre=centre, focus=focus, member_offset=member_offset, others=others)
    return m.transformed(pose.R, pose.t)
