"""Structured hexahedral tooth bodies: six subvolumes per tooth, named sets, export (report section 1.6).

Data flow: :class:`tca.geometry.gear.Gear` -> :func:`mesh_gear` (teeth of one gear, gear frame) or
:class:`tca.pair.gear_pair.GearPair` + TCA position -> :func:`mesh_pair` (both gears in S_f) ->
:class:`HexMesh` -> :func:`check_quality` / :func:`check_conformity` -> :func:`write_vtu`,
:func:`write_inp`, :func:`write_msh`.

What the FE solver (``fem/``) gets in a :class:`HexMesh`
-------------------------------------------------------
* ``points`` [mm] and ``cells`` (8-node hexahedra, VTK = C3D8 order, positive Jacobian at every
  Gauss point — :func:`check_quality` raises otherwise), ``cell_body`` / ``bodies`` (one body per
  gear, named after the gear; a double-helical gear's two members are one body). Bodies share no
  nodes; within a body all hexahedra conform (no duplicate nodes, every interior face shared by
  exactly two elements).
* Face sets ``(cell, local face)`` with local faces as :data:`HEX_FACES` (= ABAQUS S1..S6, outward
  normals) and node sets of the same names, per body ``<body>/...``:

  - ``tooth<j>/flank_pos`` (+y flank: the driving flank of a positively turning gear),
    ``tooth<j>/flank_neg`` (-y, coast), ``tooth<j>/fillet_pos|neg``, ``tooth<j>/root_pos|neg``,
    ``tooth<j>/top_land`` — j is the gear's own tooth index 0..N-1 (counter-clockwise);
  - ``rim_side1``, ``rim_side2`` (the two radial sides of the rim portion), ``rim_bottom`` (bore of
    an external gear, outer cylinder of a ring) and their union ``rim`` — to fix (sun) or to make
    the rigid surface of a rigid body (planet, ring) with the reference point (Fig. 1.7);
  - ``end_zmin``, ``end_zmax`` (the gear's axial end faces; of both members when double-helical).
* ``reference_points[<body>]``: point on the gear axis (centre of the face width) and the unit
  axis, in the frame of the mesh (S_f for :func:`mesh_pair`).
* ``contact_pairs``: ``(gear-1 face set, gear-2 face set)`` for every pair of teeth that may touch,
  e.g. ``("sun/tooth0/flank_pos", "planet/tooth0/flank_neg")``; the first is the TCA pair in contact.
* ``meta``: ``meta["position"]`` (TCA index, phi1/phi2 [deg], TE [arcsec], contact kind, contact
  point in S_f [mm], params (u1, v1, u2, v2), ``loaded_teeth`` (j1, j2), ``contact_node_gap_mm``)
  and ``meta["bodies"][<body>]`` (teeth, ``loaded_tooth``, ``loaded_side`` (+1/-1), rim radius,
  element sizes, per-member offsets). The TCA contact point is a node of both gears.
"""

from mesher.body import Focus, MeshOptions, mesh_gear, model_teeth, plan_tooth
from mesher.export import abaqus_name, gmsh_quality, inp_names, to_meshio, write_inp, write_msh, write_vtu
from fem.mesh.hexmesh import HEX_FACES, HexMesh, ReferencePoint, merge_meshes
from mesher.pair_model import PairModel, choose_position, member_pair, mesh_pair
from mesher.parts import join_parts
from mesher.quality import Quality, check_conformity, check_quality, element_volumes, face_counts, quality
from mesher.tooth import ToothGeometry, ToothPlan
from mesher.volume import section_area, tooth_region_volume

__all__ = [
    "Focus", "HEX_FACES", "HexMesh", "MeshOptions", "PairModel", "Quality", "ReferencePoint", "ToothGeometry",
    "ToothPlan", "abaqus_name", "check_conformity", "check_quality", "choose_position", "element_volumes",
    "face_counts", "gmsh_quality", "inp_names", "join_parts", "member_pair", "merge_meshes", "mesh_gear", "mesh_pair",
    "model_teeth", "plan_tooth", "quality", "section_area", "to_meshio", "tooth_region_volume", "write_inp",
    "write_msh", "write_vtu",
]
