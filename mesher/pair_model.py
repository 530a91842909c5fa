r"""Finite element model of a gear pair at a position found by TCA (Steps 5–6, Figs. 1.7–1.8).

Placement follows :mod:`mesher.placement` (the one path shared with the stress scenes). The TCA
(:func:`tca.pair.analysis.run_pair_tca`, :func:`tca.pair.te.mesh_contact`) gives at position i the angles :math:`\phi_1, \phi_2`,
the index k of the pair in contact and the contact point on the reference teeth (parameters
:math:`u_1, v_1, u_2, v_2`). The reference pair solved at :math:`\phi_1 - 2\pi k/N_1` is, at
:math:`\phi_1`, tooth :math:`j_0 = -k \bmod N` of each gear (both teeth turned by −k pitches), so
each gear is meshed with ``teeth`` teeth centred on its tooth :math:`j_0`, graded around its
contact point (which is a node of both meshes) and placed by its mount,
:math:`x_f = o + R_0 R_z(\phi + \phi_0)\,x` (:class:`tca.numerics.transforms.Mount`). The two loaded flanks
then touch at the TCA point: the two contact nodes coincide to the TCA residual.

Double-helical members (``MeshOptions.gap`` = F): member a of both gears is centred at
:math:`z_f = c = (B_1 + F)/2`, member b (opposite hands) at :math:`-c`. Member a's TCA is solved
exactly: shifting the scene by :math:`-c\,e_z` leaves gear 1's member centred and moves gear 2's
origin by :math:`\Delta = c_2 R_0 e_z - c\,e_z` (:math:`c_2` its member offset in its own frame),
which is expressed as extra centre-distance, :math:`\Delta E_x` and axial misalignments of gear 2.
Both members of a gear turn together (one shaft); member b is placed at member a's angles (for an
aligned pair its contact is the mirror image; with misalignment the FE solution decides).

Contact pairs: tooth j of gear 1 meets tooth j of gear 2 (same index offset from the loaded pair),
flank ``side1`` against flank ``side2`` of the :class:`tca.pair.gear_pair.GearPair`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from tca.errors import InputError
from tca.pair.gear_pair import GearPair
from tca.pair.analysis import ContactKind, PairTCAResult, TCAOptions, run_pair_tca
from tca.pair.te import grid_index, mesh_contact

from mesher.body import Focus, MeshOptions
from mesher.placement import gear_pose, loaded_tooth, mesh_placed
from fem.mesh.hexmesh import HexMesh, merge_meshes

__all__ = ["PairModel", "member_pair", "choose_position", "mesh_pair"]

_SIDE = {1: "pos", -1: "neg"}


@dataclass(frozen=True, eq=False)
class PairModel:
    """Meshed pair in S_f with the TCA result and the position used."""

    mesh: HexMesh
    tca: PairTCAResult
    index: int
    loaded_teeth: tuple[int, int]
    contact_point: np.ndarray  # TCA contact point in S_f (member a) [mm]
    contact_nodes: tuple[int, int]  # node of each gear at the contact point
    contact_node_gap: float  # distance between them [mm]
    member_offset: float  # c [mm], 0 for single members


def _axis_sign(pair: GearPair) -> float:
    """+1 when gear 2's nominal axis is +z_f, -1 when it is -z_f (external pair)."""
    return math.copysign(1.0, replace(pair, misalignment=type(pair.misalignment)()).mounts()[1].R0[2, 2])


def member_pair(pair: GearPair, c: float) -> GearPair:
    """Pair whose gear 2 is shifted so that member pairs centred at z_f = c solve as centred members."""
    if c == 0.0:
        return pair
    c2 = c * _axis_sign(pair)
    _, m2 = pair.mounts()
    axis = m2.R0[:, 2]
    delta = c2 * axis - c * np.array([0.0, 0.0, 1.0])
    A = np.stack([np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]), axis], -1)
    a, b, ax = np.linalg.solve(A, delta)
    ms = pair.misalignment
    dx = a if pair.kind == "external" else -a  # gear 2's centre x is E + dE (external), -(E + dE) or E - dE
    return pair.with_misalignment(d_center=float(ms.d_center + dx), d_ex=float(ms.d_ex + b), d_axial=float(ms.d_axial + ax))


def choose_position(tca: PairTCAResult, position) -> int:
    """Index of a TCA grid position: an integer index, 'max_te' or 'min_te' (:func:`tca.pair.te.grid_index`)."""
    return grid_index(tca.te, position)


def mesh_pair(pair: GearPair, position="max_te", opts1: MeshOptions = MeshOptions(),
              opts2: MeshOptions | None = None, tca_options: TCAOptions = TCAOptions(),
              tca: PairTCAResult | None = None) -> PairModel:
    """Mesh both gears of a pair at a TCA position (see module docstring); bodies named after the gears."""
    opts2 = opts1 if opts2 is None else opts2
    g1, g2 = pair.gear1, pair.gear2
    if g1.name == g2.name:
        raise InputError("gear2.name", g2.name, f"a name other than gear 1's {g1.name!r} (body names)")
    if (opts1.gap is None) != (opts2.gap is None):
        raise InputError("mesh.gap_mm", (opts1.gap, opts2.gap), "set for both gears or for neither")
    c = 0.0 if opts1.gap is None else 0.5 * (g1.face_width + opts1.gap)
    mp = member_pair(pair, c)
    if tca is None:
        tca = run_pair_tca(mp, tca_options)
    i = choose_position(tca, position)
    c_i = mesh_contact(tca, float(tca.phi1[i]))  # the contact at the grid angle (the scenes' one path)
    k = c_i.k
    u1, v1, u2, v2 = (float(x) for x in c_i.params)
    kind = int(c_i.kind)
    if kind == ContactKind.NONE:
        raise InputError("position", i, "a position with contact")
    m1, m2 = pair.mounts()
    c2 = c * _axis_sign(pair)
    j1, j2 = loaded_tooth(g1, k), loaded_tooth(g2, k)
    meshes = []
    for g, o, j, f, phi, mnt, off in ((g1, opts1, j1, Focus(pair.side1, u1, v1), c_i.phi1, m1, c),
                                      (g2, opts2, j2, Focus(pair.side2, u2, v2), c_i.phi2, m2, c2)):
        meshes.append(mesh_placed(g, o, j, f, gear_pose(mnt, phi), member_offset=off if o.gap is not None else None))
    teeth1 = meshes[0].meta["bodies"][g1.name]["teeth"]
    teeth2 = meshes[1].meta["bodies"][g2.name]["teeth"]
    if len(teeth1) != len(teeth2):
        raise InputError("mesh.teeth", (len(teeth1), len(teeth2)), "the same number of teeth on both gears")
    order = sorted(range(len(teeth1)), key=lambda q: (teeth1[q] != j1, q))  # the loaded pair first
    pairs = tuple((f"{g1.name}/tooth{teeth1[q]}/flank_{_SIDE[pair.side1]}",
                   f"{g2.name}/tooth{teeth2[q]}/flank_{_SIDE[pair.side2]}") for q in order)
    p_f = np.asarray(c_i.point, float) + np.array([0.0, 0.0, c])
    nodes = []
    for hm, g, j, side in ((meshes[0], g1, j1, pair.side1), (meshes[1], g2, j2, pair.side2)):
        ids = hm.point_sets[f"{g.name}/tooth{j}/flank_{_SIDE[side]}"]
        d = np.linalg.norm(hm.points[ids] - p_f, axis=1)
        nodes.append(int(ids[np.argmin(d)]))
    gap = float(np.linalg.norm(meshes[0].points[nodes[0]] - meshes[1].points[nodes[1]]))
    meta = {"bodies": {**meshes[0].meta["bodies"], **meshes[1].meta["bodies"]},
            "position": {"index": i, "phi1_deg": math.degrees(c_i.phi1), "phi2_deg": math.degrees(c_i.phi2),
                         "te_arcsec": float(tca.te_arcsec[i]), "active_pair": k, "kind": ContactKind.names[kind],
                         "contact_point_mm": p_f.tolist(), "params_mm": [u1, v1, u2, v2],
                         "loaded_teeth": [j1, j2], "contact_node_gap_mm": gap, "member_offset_mm": c},
            "driver": g1.name, "driven": g2.name}
    n0 = meshes[0].n_points
    merged = merge_meshes(meshes, contact_pairs=pairs, meta=meta)
    return PairModel(merged, tca, i, (j1, j2), p_f, (nodes[0], n0 + nodes[1]), gap, c)

