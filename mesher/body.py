r"""A gear body: several neighbouring tooth bodies on a common rim, one or two members (Steps 4–6).

Step 4 (Fig. 1.6(d)): the six blocks of every tooth (:mod:`mesher.tooth`) are numbered on one
section topology (:mod:`mesher.topology`) and extruded through the axial levels into 8-node
hexahedra. Teeth are the reference tooth turned by :meth:`tca.geometry.gear.Gear.tooth_transform`; the
space-centre node rows are shared, so the hexahedra conform across subvolumes, across teeth and
with the rim.

Grading ("model only what the scene needs"): a :class:`Focus` (flank side, parameter u and level z
of the TCA contact point on the loaded tooth) refines the loaded flank around the contact point
(``contact_size`` growing by ``growth`` up to ``coarse_size``), the axial levels around z, the depth
below both flanks of the loaded tooth and its fillets (``fillet_size``); the contact point itself is
a node. Unloaded teeth keep ``coarse_size``. On a gear with an end relief (:mod:`tca.geometry.modifications.end_relief`) the
axial level nearest each relief start z_s is moved onto it (unless it carries the contact point), so
a mesh line follows the ridge of a linear relief.

Steps 5–6 (Fig. 1.7): named sets are made for every tooth j (the gear's own counter-clockwise index,
0..N-1): ``tooth<j>/flank_pos`` (+y, driving side), ``tooth<j>/flank_neg``, ``tooth<j>/fillet_pos|neg``,
``tooth<j>/root_pos|neg``, ``tooth<j>/top_land``; the rim's ``rim_side1`` (at the first tooth's −y side),
``rim_side2``, ``rim_bottom`` (bore of an external gear, outer cylinder of a ring) and their union
``rim``; the end faces ``end_zmin``/``end_zmax``. Each is a face set and a node set.

Double-helical members: two members of opposite hands with axial offsets ±(B + F)/2 (F the gap);
member b is generated from its own (mirror) gear and graded at the mirrored focus.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from tca.errors import InputError
from tca.geometry.gear import Gear

from mesher.grading import MinField, SizeField, count, distribute, uniform
from fem.mesh.hexmesh import HEX_FACES, HexMesh, ReferencePoint
from mesher.quality import check_quality
from mesher.topology import SectionTopology
from mesher.tooth import BLOCKS, SIDES, ToothGeometry, ToothPlan

__all__ = ["MeshOptions", "Focus", "plan_tooth", "mesh_gear", "model_teeth", "plan_gear", "build_gear", "GearPlan",
           "MemberPlan"]


@dataclass(frozen=True)
class MeshOptions:
    """Size of the model and its element sizes; None takes the default in modules of the gear."""

    teeth: int = 3
    rim_depth: float | None = None  # [mm] below the root circle; default 3 m
    coarse_size: float | None = None  # [mm] where nothing happens; default 0.5 m
    contact_size: float | None = None  # [mm] at the contact point; default 0.125 m
    fillet_size: float | None = None  # [mm] on the loaded tooth's fillets; default 1.5 * contact_size
    growth: float = 1.3  # size ratio of neighbouring elements away from the focus
    gap: float | None = None  # [mm] gap F between double-helical members; None: single member
    axial_contact_size: float | None = None  # [mm] of the axial levels at the contact; default contact_size
    neighbour_size: float | None = None  # [mm] profile size on the loaded side of the other teeth; default coarse
    axial_coarse_size: float | None = None  # [mm] largest axial level spacing of a graded member; default coarse
    section_growth: float | None = None  # growth of the layers under the loaded fillet and its root; default growth
    depth_growth: float | None = None  # growth of the layers under the contact and the other flank; default section
    axial_growth: float | None = None  # growth of the axial levels away from the zones; default growth
    back_size: float | None = None  # [mm] layer under the loaded tooth's other flank and fillet; default fillet_size

    def __post_init__(self):
        if not (isinstance(self.teeth, int) and self.teeth >= 1):
            raise InputError("mesh.teeth", self.teeth, "an integer >= 1")
        for k in ("rim_depth", "coarse_size", "contact_size", "fillet_size", "axial_contact_size", "neighbour_size",
                  "axial_coarse_size"):
            v = getattr(self, k)
            if v is not None and not (v > 0 and math.isfinite(v)):
                raise InputError(f"mesh.{k}_mm", v, "> 0 mm")
        if not (1.0 <= self.growth <= 3.0):
            raise InputError("mesh.growth", self.growth, "in [1, 3]")
        for k in ("section_growth", "depth_growth", "axial_growth"):
            v = getattr(self, k)
            if v is not None and not (1.0 <= v <= 3.0):
                raise InputError(f"mesh.{k}", v, "in [1, 3]")
        if self.back_size is not None and not (self.back_size > 0 and math.isfinite(self.back_size)):
            raise InputError("mesh.back_size_mm", self.back_size, "> 0 mm")
        if self.gap is not None and not (self.gap >= 0):
            raise InputError("mesh.gap_mm", self.gap, ">= 0 mm")

    def sizes(self, gear: Gear) -> dict:
        """Element sizes and rim depth [mm] for a gear (defaults scale with its module)."""
        m = gear.module
        coarse = self.coarse_size if self.coarse_size is not None else 0.5 * m
        contact = self.contact_size if self.contact_size is not None else min(0.125 * m, coarse)
        fillet = self.fillet_size if self.fillet_size is not None else min(1.5 * contact, coarse)
        if contact > coarse:
            raise InputError("mesh.contact_size_mm", contact, f"<= coarse_size_mm {coarse:g}")
        if fillet > coarse:
            raise InputError("mesh.fillet_size_mm", fillet, f"<= coarse_size_mm {coarse:g}")
        axial = self.axial_contact_size if self.axial_contact_size is not None else contact
        if axial > coarse:
            raise InputError("mesh.axial_contact_size_mm", axial, f"<= coarse_size_mm {coarse:g}")
        rim = self.rim_depth if self.rim_depth is not None else 3.0 * m
        nb = min(self.neighbour_size, coarse) if self.neighbour_size is not None else coarse
        ac = self.axial_coarse_size if self.axial_coarse_size is not None else coarse
        qs = self.section_growth if self.section_growth is not None else self.growth
        if ac < axial:
            raise InputError("mesh.axial_coarse_size_mm", ac, f">= axial_contact_size_mm {axial:g}")
        return {"coarse": coarse, "contact": contact, "fillet": fillet, "rim": rim, "growth": self.growth, "axial": axial,
                "neighbour": nb, "axial_coarse": ac,
                "section_growth": qs,
                "depth_growth": self.depth_growth if self.depth_growth is not None else qs,
                "axial_growth": self.axial_growth if self.axial_growth is not None else self.growth,
                "back": min(self.back_size, coarse) if self.back_size is not None else fillet}


@dataclass(frozen=True)
class Focus:
    """The loaded flank's contact point: side (+1/-1), flank parameter u [mm], level z [mm] (reference tooth).

    ``extent_u`` / ``extent_z`` [mm]: half-lengths (along the flank profile / the axis) of a zone
    around the point kept at the contact sizes before the growth starts (e.g. a contact ellipse).
    """

    side: int
    u: float
    z: float
    extent_u: float = 0.0
    extent_z: float = 0.0

    def __post_init__(self):
        if self.side not in (1, -1):
            raise InputError("focus.side", self.side, "+1 or -1")
        for k in ("extent_u", "extent_z"):
            v = getattr(self, k)
            if not (v >= 0.0 and math.isfinite(v)):
                raise InputError(f"focus.{k}_mm", v, ">= 0 mm")


def _table_param(table, frac):
    par, s = table
    return np.interp(np.asarray(frac) * s[-1], s, par)


def _pin(a: np.ndarray, k: int, value: float) -> None:
    """Set interior node k exactly to value (the end nodes stay where they are)."""
    if 0 < k < len(a) - 1:
        a[k] = value


def plan_tooth(geom: ToothGeometry, sz: dict, z_ref: float, focus: Focus | None, label: str = "tooth",
               side: int | None = None) -> ToothPlan:
    """Element distributions of one tooth: graded around `focus` (loaded tooth) or uniform coarse.

    An unloaded tooth's flank on ``side`` gets the profile size ``sz['neighbour']`` instead of the coarse
    size: the neighbouring pairs come into contact near a change of the pair in contact, and a coarse
    faceted flank lies inside the curved one by h^2/(8 rho) (~0.1 mm at 3 mm elements), more than the
    elastic approach that closes their gap.
    """
    g = geom.gear
    c, q = sz["coarse"], sz["growth"]
    qs = sz["section_growth"]  # under the loaded fillet and along the root: bending only, no contact
    qd = sz["depth_growth"]  # under the contact (Hertz) and under the other flank
    flank_t = {s: geom.flank_table(s, z_ref) for s in SIDES}
    fil_t = {s: geom.fillet_table(s, z_ref) for s in SIDES}
    root_t = {s: geom.root_table(s, z_ref) for s in SIDES}
    base_l = {s: geom.base_length(s, z_ref) for s in SIDES}
    loaded = focus is not None
    # flank (profile direction)
    fields, pins = {}, {}
    for s in SIDES:
        L = flank_t[s][1][-1]
        if loaded and s == focus.side:
            u0, u1 = flank_t[s][0][0], flank_t[s][0][-1]
            uc = min(max(focus.u, u0), u1)
            sc = float(np.interp(uc, flank_t[s][0], flank_t[s][1]))
            fields[s], pins[s] = SizeField(c, sz["contact"], sc, q, focus.extent_u), uc
        elif not loaded and s == side:
            fields[s] = SizeField(sz.get("neighbour", c))
        else:
            fields[s] = SizeField(c)
    n_fl = max(count(flank_t[s][1][-1], fields[s], 3) for s in SIDES)
    flank_u = {}
    for s in SIDES:
        L = flank_t[s][1][-1]
        f = distribute(L, fields[s], n_fl, pin=s in pins)
        u = _table_param(flank_t[s], f)
        if s in pins:  # the contact point is a node (unless an end node serves it)
            _pin(u, int(np.argmin(np.abs(f * L - fields[s].focus))), pins[s])
        u[0], u[-1] = flank_t[s][0][0], flank_t[s][0][-1]
        flank_u[s] = u
    # fillet and root
    hf = sz["fillet"] if loaded else c
    # fillet: local size hf * min(1, sqrt(rho / m)) (rho its radius of curvature): the sagitta of an
    # element stays below hf^2 / (8 m) on the strongly curved fillets of internal gears, and the
    # count still doubles when hf halves; nodes equidistributed in that measure
    meas = {}
    for s in SIDES:
        ds = np.diff(fil_t[s][1])
        kappa = np.abs(np.diff(fil_t[s][2])) / np.maximum(ds, 1e-300)
        w = np.maximum(1.0, np.sqrt(g.module * kappa)) * ds / hf
        meas[s] = np.concatenate([[0.0], np.cumsum(w)])
    n_fil = max(2, max(int(math.ceil(meas[s][-1] - 1e-9)) for s in SIDES))
    fillet_w = {s: np.interp(uniform(n_fil) * meas[s][-1], meas[s], fil_t[s][0]) for s in SIDES}
    for s in SIDES:
        fillet_w[s][0], fillet_w[s][-1] = fil_t[s][0][0], fil_t[s][0][-1]
    short = min(root_t[s][1][-1] for s in SIDES) < 1e-3 * g.module
    if short:
        n_root = 0
    else:
        rf = SizeField(c, hf, 0.0, qs) if loaded else SizeField(c)
        n_root = max(count(root_t[s][1][-1], rf, 1) for s in SIDES)
    root_u = {}
    for s in SIDES:
        if n_root == 0:
            root_u[s] = root_t[s][0][-1:]
        else:
            L = root_t[s][1][-1]
            root_u[s] = _table_param(root_t[s], distribute(L, rf, n_root))
            root_u[s][0], root_u[s][-1] = root_t[s][0][0], root_t[s][0][-1]
    # across the half tooth (mid-surface -> flank), finest at the flank
    half = {}
    for s in SIDES:
        L = base_l[s]
        if loaded:
            if s == focus.side:  # the finer of the Hertz layers under the contact and the layers under the fillet
                hfield = MinField((SizeField(c, sz["contact"], L, qd), SizeField(c, sz["fillet"], L, qs)))
            else:  # under the other flank and fillet: bending only
                hfield = SizeField(c, sz["back"], L, qd)
            half[s] = distribute(L, hfield, nmin=2)
        else:
            half[s] = uniform(count(L, SizeField(c), 2))
    u_tip = {s: flank_t[s][0][-1] for s in SIDES}
    return ToothPlan(flank_u, fillet_w, root_u, half, z_ref, u_tip, label)


def model_teeth(gear: Gear, n: int, centre: int = 0) -> list[int]:
    """Tooth indices (mod N) of an n-tooth model centred on tooth `centre`, counter-clockwise."""
    if not (1 <= n <= gear.teeth):
        raise InputError("mesh.teeth", n, f"an integer in [1, {gear.teeth}] (teeth of {gear.name})")
    first = centre - (n - 1) // 2
    return [int((first + i) % gear.teeth) for i in range(n)]


@dataclass(frozen=True, eq=False)
class MemberPlan:
    """The element distributions of one member before any node is placed: axial levels ``z`` [mm] (member
    frame), the rim fractions, one :class:`ToothPlan` per modelled tooth and the section topology they make."""

    geom: ToothGeometry
    offset: float  # axial offset of the member [mm]
    z: np.ndarray
    rim_frac: np.ndarray
    plans: tuple
    topology: SectionTopology
    info: dict

    @property
    def cells(self) -> int:
        """Hexahedra of the member: one layer of section quads per pair of axial levels."""
        return (len(self.z) - 1) * len(self.topology.quads)

    @property
    def nodes(self) -> int:
        return len(self.z) * self.topology.n_nodes


@dataclass(frozen=True, eq=False)
class GearPlan:
    """Everything :func:`mesh_gear` decides before it places a node (:func:`plan_gear`): the element counts of the
    mesh it will build, exactly, at the cost of the size fields alone."""

    gear: Gear
    body: str
    teeth: list
    centre_index: int  # position of the loaded tooth in ``teeth``
    sizes: dict
    focus: Focus | None
    members: tuple  # MemberPlan of member a (and b)

    @property
    def cells(self) -> int:
        return sum(m.cells for m in self.members)

    @property
    def nodes(self) -> int:
        return sum(m.nodes for m in self.members)


def _member(plan: MemberPlan, teeth: list[int]):
    """Nodes, cells and named face sets of one member (gear frame, axial offset added)."""
    geom, plans, z, rim_frac, offset, topo = plan.geom, plan.plans, plan.z, plan.rim_frac, plan.offset, plan.topology
    g = geom.gear
    closed = len(teeth) == g.teeth
    nz = len(z)
    pos = np.empty((nz, topo.n_nodes, 3))
    blocks_by_plan = {}
    flip = {}
    for t, (j, p) in enumerate(zip(teeth, plans)):
        if id(p) not in blocks_by_plan:
            blocks_by_plan[id(p)] = geom.blocks(p, z, rim_frac)
        blk = blocks_by_plan[id(p)]
        R, tr = g.tooth_transform(j)
        for b in BLOCKS:
            P = blk[b] @ R.T + tr
            pos[:, topo.ids[(t, b)].ravel()] = P.reshape(nz, -1, 3)
            q = topo.quads[topo.quad_block[(t, b)]]
            x, y = pos[0, q, 0], pos[0, q, 1]
            area = 0.5 * np.sum(x * np.roll(y, -1, 1) - y * np.roll(x, -1, 1))
            flip[(t, b)] = area < 0
    quads = topo.quads.copy()
    for key, fl in flip.items():
        if fl:
            sl = topo.quad_block[key]
            quads[sl] = quads[sl][:, [0, 3, 2, 1]]
    nq, ns = len(quads), topo.n_nodes
    k = np.arange(nz - 1)
    bottom = (k[:, None, None] * ns + quads[None]).reshape(-1, 4)
    cells = np.concatenate([bottom, bottom + ns], axis=1)
    pts = pos.reshape(-1, 3).copy()
    pts[:, 2] += offset

    def lateral(key, side, lo=0, hi=None):
        q, e = topo.block_edge(key, side, lo, hi)
        if flip[key]:
            e = 3 - e
        cq = (k[:, None] * nq + q[None, :]).ravel()
        return np.stack([cq, np.tile(2 + e, nz - 1)], -1)

    faces = {}

    def add(name, arr):
        faces[name] = np.concatenate([faces[name], arr]) if name in faces else arr

    for t, (j, p) in enumerate(zip(teeth, plans)):
        for s in SIDES:
            sg, nm = ("+", "pos") if s > 0 else ("-", "neg")
            add(f"tooth{j}/flank_{nm}", lateral((t, "A" + sg), "j1"))
            nf = p.n_fillet(s)
            add(f"tooth{j}/fillet_{nm}", lateral((t, "B" + sg), "j1", 0, nf))
            if p.n_fillet_root > nf:
                add(f"tooth{j}/root_{nm}", lateral((t, "B" + sg), "j1", nf, None))
            add(f"tooth{j}/top_land", lateral((t, "A" + sg), "i1"))
            add("rim_bottom", lateral((t, "C" + sg), "i1"))
    if not closed:
        add("rim_side1", lateral((0, "C-"), "j1"))
        add("rim_side2", lateral((len(teeth) - 1, "C+"), "j1"))
    add("end_zmin", np.stack([np.arange(nq), np.zeros(nq, int)], -1))
    add("end_zmax", np.stack([(nz - 2) * nq + np.arange(nq), np.ones(nq, int)], -1))
    return pts, cells, faces, topo


def plan_gear(gear: Gear, opts: MeshOptions = MeshOptions(), centre: int = 0, focus: Focus | None = None,
              name: str | None = None, member_offset: float | None = None, others: tuple = ()) -> GearPlan:
    """The element distributions of :func:`mesh_gear` with the same arguments, without placing a node: its
    ``cells`` and ``nodes`` are those of the mesh (a resource estimate that is exact)."""
    body = name or gear.name
    sz = opts.sizes(gear)
    teeth = model_teeth(gear, opts.teeth, centre)
    ci = teeth.index(centre % gear.teeth)
    B = gear.face_width
    extra = [(j, f) for j, f in ((int(j) % gear.teeth, f) for j, f in others) if j in teeth and j != teeth[ci]]
    if extra and focus is None:
        raise InputError("others", [j for j, _ in extra], "further foci only with a focus on the centre tooth")
    if opts.gap is None:
        members = [(gear, 0.0, focus, extra)]
    else:
        c = 0.5 * (B + opts.gap) if member_offset is None else member_offset
        mirror = None if focus is None else replace(focus, z=-focus.z)
        members = [(gear, c, focus, extra),
                   (replace(gear, hand=-gear.hand, name=gear.name), -c, mirror, [(j, replace(f, z=-f.z)) for j, f in extra])]
    closed = len(teeth) == gear.teeth
    clamp = lambda z: min(max(z, -0.5 * B), 0.5 * B)  # noqa: E731
    out = []
    for gm, off, fc, ex in members:
        geom = ToothGeometry(gm, sz["rim"])
        z_ref = 0.0 if fc is None else clamp(fc.z)
        if fc is None:
            zf = SizeField(sz["coarse"])
        else:
            ac = sz["axial_coarse"]
            qz = sz["axial_growth"]
            zf = SizeField(ac, sz["axial"], z_ref + 0.5 * B, qz, fc.extent_z)
            if ex:
                zf = MinField((zf,) + tuple(SizeField(ac, sz["axial"], clamp(f.z) + 0.5 * B, qz,
                                                      f.extent_z) for _, f in ex))
        z = -0.5 * B + B * distribute(B, zf, nmin=2, pin=fc is not None)
        pinned = set()
        for _, f in ex:  # each further focus on a level (unless the main one's node is the nearest)
            k = int(np.argmin(np.abs(z - clamp(f.z))))
            if abs(z[k] - z_ref) > 1e-12:
                _pin(z, k, clamp(f.z))
                pinned.add(k)
        kc = -1
        if fc is not None:
            kc = int(np.argmin(np.abs(z - z_ref)))
            _pin(z, kc, z_ref)
        if gm.end_relief is not None:  # a mesh line on each start of the end relief (its ridge, if linear)
            for zs in gm.end_relief.starts(B):
                k = -1 if zs is None else int(np.argmin(np.abs(z - zs)))
                if k != kc and k not in pinned:
                    _pin(z, k, zs)
        rim_frac = uniform(count(sz["rim"], SizeField(sz["coarse"]), 2))
        plain = plan_tooth(geom, sz, z_ref, None, side=None if fc is None else fc.side)
        plans = [plain] * len(teeth)
        if fc is not None:
            plans[ci] = plan_tooth(geom, sz, z_ref, fc, label="loaded")
        for j, f in ex:
            plans[teeth.index(j)] = plan_tooth(geom, sz, clamp(f.z), f, label="loaded")
        topo = SectionTopology.build(plans, len(rim_frac) - 1, closed)
        info = {"offset_mm": off, "hand": gm.hand, "levels": len(z), "section_nodes": topo.n_nodes,
                "loaded_plan": {"flank": plans[ci].n_flank, "fillet_root": plans[ci].n_fillet_root,
                                "half_pos": plans[ci].n_half(1), "half_neg": plans[ci].n_half(-1)},
                "rim": len(rim_frac) - 1}
        out.append(MemberPlan(geom, off, z, rim_frac, tuple(plans), topo, info))
    return GearPlan(gear, body, teeth, ci, sz, focus, tuple(out))


def mesh_gear(gear: Gear, opts: MeshOptions = MeshOptions(), centre: int = 0, focus: Focus | None = None,
              name: str | None = None, member_offset: float | None = None, check: bool = True,
              others: tuple = ()) -> HexMesh:
    """Hexahedral model of `opts.teeth` teeth of a gear centred on tooth `centre`, in the gear frame.

    `focus` (reference-tooth parameters) grades the mesh around the contact point of tooth `centre`.
    `others`: ``(tooth, Focus)`` of further loaded teeth (neighbouring pairs that close under load),
    graded like tooth `centre` around their own contact points; the axial levels, common to all teeth,
    are graded around every focus (the smallest of the size fields, :class:`mesher.grading.MinField`).
    Teeth not in the model are ignored. Needs `focus`.
    With ``opts.gap`` set the gear is double-helical: member a (this gear) at axial offset
    `member_offset` (default +(B + F)/2) and its mirror member b at the opposite offset.
    With `check` (default) an element with det J <= 0 at a Gauss point raises a GeometryError.
    The element distributions are :func:`plan_gear`'s (its counts are this mesh's).
    """
    plan = plan_gear(gear, opts, centre, focus, name, member_offset, others)
    return build_gear(plan, check)


def build_gear(plan: GearPlan, check: bool = True) -> HexMesh:
    """The hexahedral model of a :class:`GearPlan` (:func:`mesh_gear`)."""
    gear, body, teeth, ci, sz, focus = plan.gear, plan.body, plan.teeth, plan.centre_index, plan.sizes, plan.focus
    pts_all, cells_all, faces_all = [], [], {}
    n0 = c0 = 0
    for mp in plan.members:
        pts, cells, faces, _ = _member(mp, teeth)
        pts_all.append(pts)
        cells_all.append(cells + n0)
        for k, v in faces.items():
            v = v + np.array([c0, 0])
            faces_all[k] = np.concatenate([faces_all[k], v]) if k in faces_all else v
        n0 += len(pts)
        c0 += len(cells)
    info = [mp.info for mp in plan.members]
    pts = np.concatenate(pts_all)
    cells = np.concatenate(cells_all)
    fsets = {f"{body}/{k}": v for k, v in faces_all.items()}
    psets = {}
    for k, v in fsets.items():
        psets[k] = np.unique(cells[v[:, 0][:, None], HEX_FACES[v[:, 1]]])
    rim_keys = [f"{body}/{k}" for k in ("rim_side1", "rim_side2", "rim_bottom") if f"{body}/{k}" in fsets]
    fsets[f"{body}/rim"] = np.concatenate([fsets[k] for k in rim_keys])
    psets[f"{body}/rim"] = np.unique(np.concatenate([psets[k] for k in rim_keys]))
    ref = {body: ReferencePoint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))}
    meta = {"bodies": {body: {
        "gear": gear.name, "teeth": teeth, "loaded_tooth": teeth[ci] if focus is not None else None,
        "loaded_side": None if focus is None else focus.side, "rim_radius_mm": ToothGeometry(gear, sz["rim"]).r_rim,
        "sizes_mm": sz, "members": info, "focus": None if focus is None else
        {"side": focus.side, "u_mm": focus.u, "z_mm": focus.z, "extent_u_mm": focus.extent_u,
         "extent_z_mm": focus.extent_z}}}}
    mesh = HexMesh(pts, cells, np.zeros(len(cells), np.int64), (body,), psets, fsets, ref, (), meta)
    if check:
        check_quality(mesh)
    return mesh

