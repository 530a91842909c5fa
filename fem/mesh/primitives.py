"""Simple structured hexahedral meshes for tests and benchmarks of the FE solver.

A structured block maps a grid of parameters (i, j, k) to points X[i, j, k]; cell (i, j, k) has
VTK nodes (i,j,k), (i+1,j,k), (i+1,j+1,k), (i,j+1,k) and the same at k+1, so its local faces
(``HEX_FACES``) 5/3 lie on i-min/i-max, 2/4 on j-min/j-max, 0/1 on k-min/k-max. The mapping must
be orientation preserving (X_i x X_j . X_k > 0), which is checked. Cells may be masked out (teeth
cut from a polar block); unused nodes are dropped.

One-dimensional spacings ``graded`` are uniform (size h) over a fine zone and grow geometrically
away from it, so that contact zones are resolved by a stated number of elements.

Bodies built here:

- ``box``: a graded rectangular block; sides ``xmin`` ... ``zmax``.
- ``cylinder_segment``: an annular sector about the z axis; sides ``rmin, rmax, tmin, tmax, zmin, zmax``.
- ``cylinder_on_block``: a plane-strain slice (one element thick) of half a cylinder on a block,
  for Hertz line contact.
- ``sphere_on_block``: a quarter of a spherical cap on a block, for Hertz point contact.
- ``spline_coupling``: a synthetic gear-like pair: a hub with teeth, double-crowned drive flanks,
  tied to a reference node on its axis, in contact with the teeth of a fixed sleeve (geometry
  :class:`SplineCoupling`, element sizes :class:`SplineMesh`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from fem.errors import FEInputError

from fem.mesh.hexmesh import HEX_FACES, HexMesh, ReferencePoint

__all__ = [
    "graded",
    "block",
    "box",
    "cylinder_segment",
    "combine",
    "with_reference",
    "with_face_sets",
    "boundary_faces",
    "cylinder_on_block",
    "sphere_on_block",
    "SplineCoupling",
    "SplineMesh",
    "spline_coupling",
]

_SIDE_FACE = {"imin": 5, "imax": 3, "jmin": 2, "jmax": 4, "kmin": 0, "kmax": 1}


def graded(a: float, b: float, h: float, *, at: float | None = None, width: float = 0.0, growth: float = 1.2,
           h_max: float | None = None) -> np.ndarray:
    """Node coordinates on [a, b]: size h [mm] within `width` of `at` (default a), then growing by `growth`."""
    if not (b > a and h > 0.0 and growth >= 1.0):
        raise FEInputError("graded", (a, b, h, growth), "a < b, h > 0, growth >= 1")
    at = a if at is None else float(np.clip(at, a, b))
    # a fine point within h/2 of an end moves to that end: no sliver element there
    at = a if at - a < 0.5 * h else (b if b - at < 0.5 * h else at)
    h_max = (b - a) if h_max is None else h_max

    def side(length: float) -> np.ndarray:
        """Offsets 0 .. length: fine sizes over `width`, then geometric; scaled by the factor nearest 1."""
        if length <= 1e-12 * (b - a):
            return np.zeros(1)
        sizes = [h] * max(1, int(np.ceil(min(width, length) / h - 1e-9)))
        while sum(sizes) < length:
            sizes.append(min(sizes[-1] * growth, max(h_max, h)))
        sizes = np.asarray(sizes)
        # end exactly at `length`: shrink all N sizes, or drop the last and stretch the others
        options = [sizes] + ([sizes[:-1]] if len(sizes) > 1 else [])
        best = min(options, key=lambda s_: abs(np.log(length / s_.sum())))
        return np.concatenate([[0.0], np.cumsum(best * (length / best.sum()))])

    left = at - side(at - a)[::-1]
    right = at + side(b - at)
    x = np.concatenate([left, right[1:]])
    x[0], x[-1] = a, b
    return x


def block(body: str, X: np.ndarray, mask: np.ndarray | None = None, names: dict[str, str] | None = None) -> HexMesh:
    """Structured body from node coordinates X (ni+1, nj+1, nk+1, 3); side face sets named by `names`."""
    X = np.asarray(X, float)
    ni, nj, nk = (s - 1 for s in X.shape[:3])
    idx = np.arange((ni + 1) * (nj + 1) * (nk + 1)).reshape(ni + 1, nj + 1, nk + 1)
    c = idx[:-1, :-1, :-1]
    cells = np.stack(
        [c, idx[1:, :-1, :-1], idx[1:, 1:, :-1], idx[:-1, 1:, :-1],
         idx[:-1, :-1, 1:], idx[1:, :-1, 1:], idx[1:, 1:, 1:], idx[:-1, 1:, 1:]], axis=-1
    )
    keep = np.ones((ni, nj, nk), bool) if mask is None else np.asarray(mask, bool)
    cell_id = -np.ones((ni, nj, nk), np.int64)
    cell_id[keep] = np.arange(keep.sum())
    cells = cells[keep]
    pts = X.reshape(-1, 3)
    # orientation: the triple product of the cell's edge vectors at node 0 must be positive
    e = pts[cells[:, [1, 3, 4]]] - pts[cells[:, [0]]]
    vol = np.einsum("ij,ij->i", np.cross(e[:, 0], e[:, 1]), e[:, 2])
    if np.any(vol <= 0.0):
        raise FEInputError(f"{body}: block mapping", int(np.argmin(vol)), "an orientation-preserving mapping (X_i x X_j . X_k > 0)")
    face_sets = {}
    names = names or {}
    sel = {"imin": (0, slice(None), slice(None)), "imax": (ni - 1, slice(None), slice(None)),
           "jmin": (slice(None), 0, slice(None)), "jmax": (slice(None), nj - 1, slice(None)),
           "kmin": (slice(None), slice(None), 0), "kmax": (slice(None), slice(None), nk - 1)}
    for side, name in names.items():
        ids = cell_id[sel[side]].ravel()
        ids = ids[ids >= 0]
        face_sets[f"{body}/{name}"] = np.stack([ids, np.full_like(ids, _SIDE_FACE[side])], axis=1)
    used, cells = np.unique(cells, return_inverse=True)
    cells = cells.reshape(-1, 8)
    return HexMesh(points=pts[used], cells=cells, cell_body=np.zeros(len(cells), np.int64), bodies=(body,), face_sets=face_sets)


def box(body: str, x, y, z) -> HexMesh:
    """Rectangular block on coordinate lines x, y, z [mm]; face sets xmin, xmax, ymin, ymax, zmin, zmax."""
    X = np.stack(np.meshgrid(x, y, z, indexing="ij"), axis=-1)
    return block(body, X, names={"imin": "xmin", "imax": "xmax", "jmin": "ymin", "jmax": "ymax", "kmin": "zmin", "kmax": "zmax"})


def cylinder_segment(body: str, r, theta, z, center=(0.0, 0.0)) -> HexMesh:
    """Annular sector on lines r [mm], theta [rad], z [mm] about an axis || z through `center`."""
    R, T, Z = np.meshgrid(r, theta, z, indexing="ij")
    X = np.stack([center[0] + R * np.cos(T), center[1] + R * np.sin(T), Z], axis=-1)
    return block(body, X, names={"imin": "rmin", "imax": "rmax", "jmin": "tmin", "jmax": "tmax", "kmin": "zmin", "kmax": "zmax"})


def combine(*meshes: HexMesh) -> HexMesh:
    """Several meshes as one (bodies, sets and reference points kept; names must be distinct)."""
    pts, cells, cbody, bodies, psets, fsets, refs = [], [], [], [], {}, {}, {}
    n0 = c0 = 0
    for m in meshes:
        pts.append(m.points)
        cells.append(m.cells + n0)
        cbody.append(m.cell_body + len(bodies))
        bodies.extend(m.bodies)
        for k, v in m.point_sets.items():
            psets[k] = v + n0
        for k, v in m.face_sets.items():
            fsets[k] = v + np.array([c0, 0])
        refs.update(m.reference_points)
        n0 += m.n_points
        c0 += m.n_cells
    if len(set(bodies)) != len(bodies):
        raise FEInputError("combine.bodies", bodies, "distinct body names")
    return HexMesh(np.concatenate(pts), np.concatenate(cells), np.concatenate(cbody), tuple(bodies), psets, fsets, refs)


def with_reference(mesh: HexMesh, name: str, point, axis=(0.0, 0.0, 1.0)) -> HexMesh:
    """A copy of the mesh with a reference point added."""
    refs = dict(mesh.reference_points)
    refs[name] = ReferencePoint(tuple(float(v) for v in point), tuple(float(v) for v in axis))
    return dataclasses.replace(mesh, reference_points=refs)


def with_face_sets(mesh: HexMesh, sets: dict[str, np.ndarray]) -> HexMesh:
    """A copy of the mesh with face sets added or replaced."""
    fs = dict(mesh.face_sets)
    fs.update(sets)
    return dataclasses.replace(mesh, face_sets=fs)


def boundary_faces(mesh: HexMesh) -> np.ndarray:
    """All exterior faces (k, 2) as (cell, local face): faces that belong to one cell only."""
    fn = mesh.cells[:, HEX_FACES].reshape(-1, 4)
    key = np.sort(fn, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    ext = np.flatnonzero(cnt[inv.ravel()] == 1)
    return np.stack([ext // 6, ext % 6], axis=1)


def _face_centres_normals(mesh: HexMesh, faces: np.ndarray):
    X = mesh.points[mesh.cells[faces[:, 0][:, None], HEX_FACES[faces[:, 1]]]]
    n = np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 1])
    return X.mean(axis=1), n / np.linalg.norm(n, axis=1, keepdims=True)


# ---------------------------------------------------------------------------------------------
# Hertz contact specimens


def cylinder_on_block(radius: float, h: float, fine_width: float, *, growth: float = 1.2, thickness: float | None = None,
                      inner: float = 0.5, block_size: float | None = None, block_h: float | None = None) -> HexMesh:
    """Plane-strain slice of half a cylinder (x >= 0) resting on a block, touching at the origin.

    Bodies ``roller`` (annular sector, radius [mm], inner radius ``inner * radius``) and ``block``
    (x in [0, L], y in [-L, 0]); both graded to size h [mm] over ``fine_width`` [mm] from the
    contact line x = 0, and in depth (the block to ``block_h``, default h: the two surfaces' nodes
    do not coincide unless block_h = h). One element through the thickness (z). Reference point
    ``roller`` at the cylinder centre. Face sets: ``roller/surface`` (r = R), ``roller/inner``,
    ``roller/sym`` (x = 0), ``roller/front``/``back`` (z faces); ``block/top``, ``block/bottom``,
    ``block/sym``, ``block/front``/``back``.
    """
    t = h if thickness is None else thickness
    L = radius if block_size is None else block_size
    z = np.array([0.0, t])
    # arc length from the contact point, mapped to the angle measured from -90 deg
    s = graded(0.0, 0.5 * np.pi * radius, h, width=fine_width, growth=growth)
    r = graded(inner * radius, radius, h, at=radius, width=fine_width, growth=growth)
    theta = -0.5 * np.pi + s / radius
    roller = cylinder_segment("roller", r, theta, z, center=(0.0, radius))
    roller = _rename(roller, {"rmax": "surface", "rmin": "inner", "tmin": "sym", "zmin": "back", "zmax": "front", "tmax": "side"})
    hb = h if block_h is None else block_h
    x = graded(0.0, L, hb, width=fine_width, growth=growth)
    y = -graded(0.0, L, hb, width=fine_width, growth=growth)[::-1]
    blk = box("block", x, y, z)
    blk = _rename(blk, {"ymax": "top", "ymin": "bottom", "xmin": "sym", "zmin": "back", "zmax": "front", "xmax": "side"})
    return with_reference(combine(roller, blk), "roller", (0.0, radius, 0.0))


def sphere_on_block(radius: float, h: float, fine_width: float, *, growth: float = 1.3, size: float | None = None,
                    block_h: float | None = None) -> HexMesh:
    """Quarter (x, y >= 0) of a spherical cap resting on a block, touching at the origin.

    ``cap``: x, y in [0, L], z from the sphere z = R - sqrt(R^2 - x^2 - y^2) to L; ``block``:
    x, y in [0, L], z in [-L, 0]; graded to size h [mm] over ``fine_width`` [mm] from the contact
    point in x, y and z (the block to ``block_h``, default h). Reference point ``cap`` at (0, 0, L). Face sets ``cap/surface``,
    ``cap/top``, ``cap/symx`` (x = 0), ``cap/symy`` (y = 0); ``block/top``, ``block/bottom``,
    ``block/symx``, ``block/symy``.
    """
    L = 0.4 * radius if size is None else size
    x = graded(0.0, L, h, width=fine_width, growth=growth)
    zc = graded(0.0, 1.0, h / L, width=fine_width / L, growth=growth)  # fraction of the cap height
    Xg, Yg, S = np.meshgrid(x, x, zc, indexing="ij")
    zs = radius - np.sqrt(radius**2 - Xg**2 - Yg**2)
    cap = block("cap", np.stack([Xg, Yg, zs + S * (L - zs)], axis=-1),
                names={"kmin": "surface", "kmax": "top", "imin": "symx", "jmin": "symy"})
    hb = h if block_h is None else block_h
    xb = graded(0.0, L, hb, width=fine_width, growth=growth)
    zb = -graded(0.0, L, hb, width=fine_width, growth=growth)[::-1]
    blk = box("block", xb, xb, zb)
    blk = _rename(blk, {"zmax": "top", "zmin": "bottom", "xmin": "symx", "ymin": "symy"}, keep_only=True)
    return with_reference(combine(cap, blk), "cap", (0.0, 0.0, L))


def _rename(mesh: HexMesh, names: dict[str, str], keep_only: bool = False) -> HexMesh:
    body = mesh.bodies[0]
    fs = {}
    for k, v in mesh.face_sets.items():
        short = k.split("/", 1)[1]
        if short in names:
            fs[f"{body}/{names[short]}"] = v
        elif not keep_only:
            fs[k] = v
    return dataclasses.replace(mesh, face_sets=fs)


# ---------------------------------------------------------------------------------------------
# Synthetic gear-like model


@dataclass(frozen=True)
class SplineCoupling:
    """Geometry of :func:`spline_coupling`: hub with external teeth driving the internal teeth of a sleeve.

    ``teeth`` teeth at ``pitch_deg``, each ``tooth_deg`` wide, the sleeve flanks ``gap_deg`` beyond
    the hub's drive flanks [deg]; radii = (hub bore R0, hub root R1, hub tip R2, sleeve tip Rt,
    contact radius rc, sleeve outer R4) [mm]; face ``width`` [mm]; the drive flanks crowned with
    radii ``crown_profile`` and ``crown_lead`` [mm] and receded by ``backlash`` [mm], one per tooth.
    """

    teeth: int = 3
    pitch_deg: float = 30.0
    tooth_deg: float = 12.0
    gap_deg: float = 0.0
    radii: tuple = (40.0, 46.0, 56.0, 48.0, 52.0, 64.0)
    width: float = 20.0
    crown_profile: float = 20.0
    crown_lead: float = 400.0
    backlash: tuple = (0.0, 0.002, 0.005)

    def __post_init__(self):
        object.__setattr__(self, "radii", tuple(self.radii))
        object.__setattr__(self, "backlash", tuple(self.backlash))
        R0, R1, R2, Rt, rc, R4 = self.radii
        R3 = R2 + (Rt - R1)  # sleeve root: the same radial clearance as at the hub root
        if not (R0 < R1 < Rt < rc < R2 < R3 < R4):
            raise FEInputError("spline_coupling.radii", self.radii, "R0 < R1 < Rt < rc < R2 and R3 = R2 + Rt - R1 < R4")
        if len(self.backlash) != self.teeth:
            raise FEInputError("spline_coupling.backlash", self.backlash, f"{self.teeth} values [mm], one per tooth")


@dataclass(frozen=True)
class SplineMesh:
    """Element sizes of :func:`spline_coupling` [mm]: h over ``fine_width`` around the contact in the profile (r)
    and depth (theta) directions, hz over ``z_fine_width`` along the face width, growing by ``growth`` up
    to h_max elsewhere."""

    h: float = 0.1
    fine_width: float = 1.0
    hz: float = 0.4
    z_fine_width: float = 3.0
    growth: float = 1.35
    h_max: float = 2.5


def spline_coupling(coupling: SplineCoupling = SplineCoupling(), sizes: SplineMesh = SplineMesh()) -> HexMesh:
    """Hub with external teeth driving the internal teeth of a sleeve about the z axis (gear-like).

    Sleeve teeth span r in [Rt, R3], R3 = R2 + (Rt - R1) (same root clearance as the hub). Hub
    tooth k spans theta in theta_k +- tooth/2; its drive flank (theta_k + tooth/2) is
    double-crowned: it recedes by (r - rc)^2 / (2 crown_profile) + (z - width/2)^2 / (2 crown_lead)
    [mm] plus backlash[k] [mm]. The facing sleeve flank is the radial plane theta_k + tooth/2 +
    gap. Contact starts at (rc, width/2) of tooth 0 and closes under a positive torque about +z.
    Geometry and names: :class:`SplineCoupling`; element sizes: :class:`SplineMesh`.

    Face sets: ``hub/bore``, ``hub/tooth<k>/flank`` (drive flanks), ``hub/tooth<k>/fillet``
    (faces of the tooth root region on the loaded side); ``sleeve/outer``,
    ``sleeve/tooth<k>/flank``, ``sleeve/tooth<k>/fillet``. Point set ``hub/tooth<k>/contact_point``:
    the flank node at (rc, width/2). Reference point ``hub`` at the origin, axis z.
    """
    teeth, width, crown_profile, crown_lead, backlash = (coupling.teeth, coupling.width, coupling.crown_profile,
                                                         coupling.crown_lead, coupling.backlash)
    h, fine_width, hz, z_fine_width, growth, h_max = (sizes.h, sizes.fine_width, sizes.hz, sizes.z_fine_width,
                                                      sizes.growth, sizes.h_max)
    R0, R1, R2, Rt, rc, R4 = coupling.radii
    R3 = R2 + (Rt - R1)
    pitch, tw, gap = np.radians([coupling.pitch_deg, coupling.tooth_deg, coupling.gap_deg])
    centres = (np.arange(teeth) - (teeth - 1) / 2.0) * pitch
    flanks = centres + tw / 2  # hub drive flanks; sleeve flanks at + gap
    hs = h / rc  # angular size of the fine elements at the contact radius
    z = graded(0.0, width, hz, at=width / 2, width=z_fine_width, growth=growth, h_max=h_max)

    def angular_lines(lo, hi, marks, fine_at):
        """Theta lines on [lo, hi] through `marks`, fine near `fine_at`."""
        pts = np.unique(np.concatenate([[lo, hi], marks]))
        out = [np.array([lo])]
        for a, b in zip(pts[:-1], pts[1:]):
            near = [f for f in fine_at if a - 1e-12 <= f <= b + 1e-12]
            if near:
                seg = graded(a, b, hs, at=near[0], width=fine_width / rc, growth=growth, h_max=h_max / rc)
            else:
                n = max(2, int(np.ceil((b - a) * rc / h_max)))
                seg = np.linspace(a, b, n + 1)
            out.append(seg[1:])
        return np.concatenate(out)

    # --- hub: polar block r in [R0, R2], teeth where r > R1
    th_lo, th_hi = centres[0] - pitch / 2, centres[-1] + pitch / 2
    marks = np.concatenate([centres - tw / 2, flanks, centres])
    th = angular_lines(th_lo, th_hi, marks, flanks)
    r = np.concatenate([
        graded(R0, R1, h_max, growth=1.0)[:-1],
        graded(R1, R2, h, at=rc, width=fine_width, growth=growth, h_max=h_max),
    ])
    Rg, Tg, Zg = np.meshgrid(r, th, z, indexing="ij")
    # crown: the drive flank recedes; the shift fades to zero at the tooth centre and into the rim
    shift = np.zeros_like(Rg)
    mask = np.zeros((len(r) - 1, len(th) - 1, len(z) - 1), bool)
    rmid = 0.5 * (r[:-1] + r[1:])
    tmid = 0.5 * (th[:-1] + th[1:])
    mask[rmid < R1] = True
    for k, (c, f) in enumerate(zip(centres, flanks)):
        mask[np.ix_(rmid > R1, (tmid > c - tw / 2) & (tmid < f), np.ones(len(z) - 1, bool))] = True
        w = np.clip((Tg - c) / (f - c), 0.0, 1.0) * ((Tg >= c - 1e-12) & (Tg <= f + 1e-12))
        radial = np.where(Rg >= R1, 1.0, np.clip((Rg - R0) / (R1 - R0), 0.0, 1.0))
        crown = (np.maximum(Rg, R1) - rc) ** 2 / (2 * crown_profile) + (Zg - width / 2) ** 2 / (2 * crown_lead) + backlash[k]
        shift += w * radial * crown / Rg
    Tg = Tg - shift
    hub = block("hub", np.stack([Rg * np.cos(Tg), Rg * np.sin(Tg), Zg], axis=-1), mask=mask, names={"imin": "bore"})

    # --- sleeve: polar block r in [Rt, R4], teeth where r < R3, beside the hub drive flanks
    s_lo = flanks + gap
    s_hi = s_lo + (pitch - tw) * 0.6
    th_s = angular_lines(s_lo[0] - (pitch - tw) * 0.1, s_hi[-1] + (pitch - tw) * 0.1, np.concatenate([s_lo, s_hi]), s_lo)
    r_s = np.concatenate([
        graded(Rt, R3, h, at=rc, width=fine_width, growth=growth, h_max=h_max)[:-1],
        graded(R3, R4, h_max, growth=1.0),
    ])
    Rs, Ts, Zs = np.meshgrid(r_s, th_s, z, indexing="ij")
    mask_s = np.zeros((len(r_s) - 1, len(th_s) - 1, len(z) - 1), bool)
    rmid_s = 0.5 * (r_s[:-1] + r_s[1:])
    tmid_s = 0.5 * (th_s[:-1] + th_s[1:])
    mask_s[rmid_s > R3] = True
    for a, b in zip(s_lo, s_hi):
        mask_s[np.ix_(rmid_s < R3, (tmid_s > a) & (tmid_s < b), np.ones(len(z) - 1, bool))] = True
    sleeve = block("sleeve", np.stack([Rs * np.cos(Ts), Rs * np.sin(Ts), Zs], axis=-1), mask=mask_s, names={"imax": "outer"})

    # --- flank and fillet face sets from the exterior faces
    sets = {}
    for m, name, lo_edges, rad_lo, rad_hi, fil in ((hub, "hub", flanks, R1, R2, R1), (sleeve, "sleeve", s_lo, Rt, R3, R3)):
        bf = boundary_faces(m)
        ctr, nrm = _face_centres_normals(m, bf)
        rr = np.hypot(ctr[:, 0], ctr[:, 1])
        tt = np.arctan2(ctr[:, 1], ctr[:, 0])
        e_t = np.stack([-np.sin(tt), np.cos(tt), np.zeros_like(tt)], axis=1)
        nt = np.einsum("ij,ij->i", nrm, e_t)
        sign = 1.0 if name == "hub" else -1.0  # hub flanks face +theta, sleeve flanks face -theta
        for k, f in enumerate(lo_edges):
            near = np.abs(tt - f) < (0.45 * tw)
            flank = near & (sign * nt > 0.9) & (rr > rad_lo + 1e-9) & (rr < rad_hi - 1e-9)
            sets[f"{name}/tooth{k}/flank"] = bf[flank]
            root = near & (np.abs(rr - fil) < 0.25 * (R2 - R1)) & (np.abs(nt) < 0.999)
            sets[f"{name}/tooth{k}/fillet"] = bf[root & ~flank]
    hub = with_face_sets(hub, {k: v for k, v in sets.items() if k.startswith("hub/")})
    sleeve = with_face_sets(sleeve, {k: v for k, v in sets.items() if k.startswith("sleeve/")})
    # the nominal contact point of each tooth (flank node nearest to r = rc, z = width / 2), as TCA gives it
    nominal = {}
    for k in range(teeth):
        nodes = hub.face_set_points(f"hub/tooth{k}/flank")
        p = hub.points[nodes]
        nominal[f"hub/tooth{k}/contact_point"] = nodes[[np.argmin(np.abs(np.hypot(p[:, 0], p[:, 1]) - rc) + np.abs(p[:, 2] - width / 2))]]
    hub = dataclasses.replace(hub, point_sets=nominal)
    return with_reference(combine(hub, sleeve), "hub", (0.0, 0.0, 0.0))
