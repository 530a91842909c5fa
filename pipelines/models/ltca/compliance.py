r"""Flank compliance of one gear, condensed once from its hexahedral model (Weber–Banaschek split).

The gear's ``teeth`` modelled teeth are meshed by :func:`mesher.mesh_gear` in the gear frame,
centred on tooth 0, with a uniform flank grid on the loaded side of every tooth (profile size
``h_u``, axial size ``h_z``: the zone of the mesher's focus covers the whole flank), and held on
its rim (Fig. 1.7's sun; the driven gear's rigid rotation is the unknown of the contact problem).

Deflection of a flank point x under a normal load is split as in Weber (1949) and Weber &
Banaschek (1953):

- *global* part: the displacement along the flank normal n of the point P = x - h n on the
  tooth's centre plane (h the distance from x to that plane along -n): tooth bending, shear,
  rim and base rotation; the FE resolves it on a coarse grid;
- *local* part (Hertzian flattening): the approach of x relative to P, which the coarse grid does
  not resolve, from a line-load formula of Weber's form (:func:`flattening`),

      delta = 2 w (1 - nu^2) / (pi E) * (ln(2 h / b) + c),

  w [N/mm] the line load, b its Hertz half-width. Weber (1949) refers x to the point at depth h
  of a half-plane: c = -nu / (2 (1 - nu)) (``local = "weber"``). A tooth is a body of finite
  thickness: the default (``local = "strip"``) refers x to the mid-plane of a plane-strain strip of
  half-thickness h pinched by Hertz line loads on both faces, with c computed once by a fine FE of
  that strip (:func:`strip_constant`: c = 0.148 for steel, independent of h/b to 0.003 for
  h/b = 10..30 and of nu to 1e-4 for nu = 0.25..0.30; Weber's c = -0.204).

Influence coefficients. With N (3n, m) the unit normal loads at the m flank nodes and Q (m, 3n) the
normal displacement at their centre-plane points P_i (inverse-distance interpolation of the
nodal displacements of the 8 nearest nodes), the global compliance is

    C_ij = n_i . u(P_i) under a unit normal load at node j = (Q K_ff^-1 N)_ij      [mm/N],

one factorization and m right-hand sides (:func:`fem.la.condense.influence_matrix`). A load at a
flank point inside a face is shared by the face's nodes with its bilinear shape functions, and
the response there is read with the same weights: w_s^T C w_t between two points s, t.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from fem.assembly import assemble_blocks
from fem.la.condense import influence_matrix
from fem.contact.faces import bilinear, project_to_faces
from fem.elements.hex8 import hex8_matrices
from fem.material import Material
from mesher import Focus, MeshOptions, mesh_gear
from mesher.body import model_teeth
from fem.mesh.hexmesh import HEX_FACES
from tca.errors import GeometryError
from tca.geometry.gear import Gear

__all__ = ["FlankGrid", "FlankCompliance", "flank_compliance", "flattening", "weber_constant", "strip_constant", "FlankPoints"]

SIDE = {1: "pos", -1: "neg"}


@dataclass(frozen=True)
class FlankGrid:
    """The model of one gear whose flanks are condensed: ``teeth`` modelled teeth, a uniform grid on the
    loaded flanks of profile size ``h_u`` and axial size ``h_z`` centred at the profile parameter ``u_mid``
    of the contact, and the body's element size ``coarse`` [mm]."""

    teeth: int
    h_u: float
    h_z: float
    coarse: float
    u_mid: float


@dataclass(frozen=True, eq=False)
class FlankCompliance:
    """Condensed normal compliance of one gear's loaded flanks (gear frame) [mm, mm/N]."""

    gear: Gear
    side: int
    teeth: tuple  # model tooth indices, centred on 0
    points: np.ndarray  # (m, 3) flank nodes
    normals: np.ndarray  # (m, 3) outward unit normals
    depth: np.ndarray  # (m,) distance h to the tooth's centre plane along -n
    faces: np.ndarray  # (f, 4) flank faces as indices into points
    C: np.ndarray  # (m, m) global compliance [mm/N]
    info: dict

    def locate(self, x: np.ndarray, slack: float = 1e-9) -> "FlankPoints":
        """Closest points on the flank faces of points x (p, 3) (gear frame): faces, weights, inside mask.

        ``slack``: a point projecting up to this fraction of a face beyond the grid's border still counts
        as inside (points on a boundary curve of the flank, which the faceted grid approximates)."""
        X = self.points[self.faces]
        centres = X.mean(1)
        k = min(8, len(self.faces))
        _, cand = cKDTree(centres).query(x, k=k)
        cand = cand.reshape(len(x), k)
        xs = np.repeat(x, k, axis=0)
        xi, eta, xp = project_to_faces(xs, X[cand.ravel()])
        inside = (np.abs(xi) <= 1.0 + slack) & (np.abs(eta) <= 1.0 + slack)
        d = np.where(inside, np.linalg.norm(xs - xp, axis=1), np.inf).reshape(len(x), k)
        best = np.argmin(d, axis=1)
        sel = np.arange(len(x)) * k + best
        ok = np.isfinite(d[np.arange(len(x)), best])
        N, _, _ = bilinear(np.clip(xi[sel], -1, 1), np.clip(eta[sel], -1, 1))
        face = cand.ravel()[sel]
        nodes = self.faces[face]
        return FlankPoints(nodes, N, ok, np.einsum("pa,pa->p", N, self.depth[nodes]), d[np.arange(len(x)), best])


@dataclass(frozen=True, eq=False)
class FlankPoints:
    """Points located on a flank grid: face nodes (p, 4), bilinear weights (p, 4), on-flank mask, depth [mm], distance [mm]."""

    nodes: np.ndarray
    weights: np.ndarray
    inside: np.ndarray
    depth: np.ndarray
    distance: np.ndarray

    def matrix(self, m: int) -> sp.csr_matrix:
        """Sparse weights (p, m) of the points over the flank nodes."""
        p = len(self.nodes)
        return sp.csr_matrix((self.weights.ravel(), (np.repeat(np.arange(p), 4), self.nodes.ravel())), shape=(p, m))


def flattening(w: np.ndarray, b: np.ndarray, h: np.ndarray, material: Material, c: float) -> np.ndarray:
    """Hertzian flattening [mm] of one body of ``material`` under a line load w [N/mm] of Hertz half-width b [mm],
    relative to the point at distance h [mm] along the normal (module docstring):

        delta = 2 w (1 - nu^2) / (pi E) * (ln(2 h / b) + c).
    """
    E, nu = material.E, material.nu
    with np.errstate(divide="ignore", invalid="ignore"):
        d = 2.0 * w * (1.0 - nu**2) / (math.pi * E) * (np.log(2.0 * h / b) + c)
    return np.where(w > 0, np.maximum(d, 0.0), 0.0)


def weber_constant(nu: float) -> float:
    """Weber's (1949) constant of the half-plane: c = -nu / (2 (1 - nu))."""
    return -nu / (2.0 * (1.0 - nu))


def strip_constant(material: Material, ratio: float = 10.0, per_b: int = 12, growth: float = 1.15) -> float:
    """Constant c of :func:`flattening` for a plane-strain strip of half-thickness h pinched by Hertz line loads.

    One quarter of the strip (symmetry about its mid-plane and the load line; 12 h long, one element
    thick with the axial displacement held: plane strain), elements b / ``per_b`` under the load
    growing by ``growth``, h / b = ``ratio``; the Hertz pressure p0 (1 - y^2/b^2)^(1/2) is integrated
    on the faces (64 points each). c = delta pi E / (2 w (1 - nu^2)) - ln(2 h / b), delta the approach
    of the load centre to the mid-plane.
    """
    from fem.mesh import primitives as prim

    h, b = 1.0, 1.0 / ratio
    hb = b / per_b
    m = prim.box("strip", prim.graded(0.0, h, hb, at=h, growth=growth),
                 prim.graded(0.0, 12.0 * h, hb, at=0.0, width=b, growth=growth), np.array([0.0, hb]))
    em = hex8_matrices(m.points, m.cells, np.full(m.n_cells, material.lam), np.full(m.n_cells, material.mu), True)
    K = assemble_blocks(em.stiffness, m.cells, m.n_points)
    n3 = 3 * m.n_points
    fixed = np.zeros(n3, bool)
    for name, comp in (("xmin", 0), ("ymin", 1), ("zmin", 2), ("zmax", 2)):
        fixed[3 * m.face_set_points(f"strip/{name}") + comp] = True
    faces = m.face_nodes("strip/xmax")
    X = m.points[faces]
    y0, y1 = X[:, :, 1].min(1), X[:, :, 1].max(1)
    dz = X[:, :, 2].max(1) - X[:, :, 2].min(1)
    s = (np.arange(64) + 0.5) / 64
    yc = y0[:, None] + s[None, :] * (y1 - y0)[:, None]
    p = np.sqrt(np.clip(1.0 - (yc / b) ** 2, 0.0, None))  # p0 = 1 MPa
    dy = ((y1 - y0) / 64)[:, None]
    f = np.zeros(n3)
    for a in range(4):  # linear shape functions along y of the face's nodes, half the face's thickness each
        lo = np.isclose(X[:, a, 1], y0)
        wy = np.where(lo[:, None], 1.0 - s[None, :], s[None, :])
        np.add.at(f, 3 * faces[:, a], -(p * wy * dy).sum(1) * 0.5 * dz)
    w = -2.0 * f.sum() / hb  # [N/mm], both halves of the load (= pi b / 2 for p0 = 1)
    top = np.flatnonzero(np.isclose(m.points[:, 0], h) & np.isclose(m.points[:, 1], 0.0))
    Q = sp.csr_matrix((np.full(len(top), -1.0 / len(top)), (np.zeros(len(top), int), 3 * top)), shape=(1, n3))
    C, _ = influence_matrix(K, fixed, sp.csc_matrix(f[:, None]), Q)
    return float(C[0, 0] * math.pi * material.E / (2.0 * w * (1.0 - material.nu**2)) - math.log(2.0 * h / b))


def _mesh(gear: Gear, side: int, grid: FlankGrid):
    """The gear's model with a uniform grid on the loaded flanks (the focus zone covers the whole flank);
    the fillets at the profile size (a fillet as coarse as the body makes the tooth too stiff in bending)."""
    teeth, h_u, h_z, coarse, u_mid = grid.teeth, grid.h_u, grid.h_z, grid.coarse, grid.u_mid
    B = gear.face_width
    top = max(coarse, h_u, h_z)
    opts = MeshOptions(teeth=teeth, coarse_size=top, contact_size=h_u, axial_contact_size=h_z, fillet_size=min(top, h_u),
                       neighbour_size=h_u, growth=1.3)
    focus = Focus(side, u_mid, 0.0, extent_u=10.0 * gear.module * 3, extent_z=B)
    return mesh_gear(gear, opts, centre=0, focus=focus)


def _normals(points, cells, faces_cf):
    """Outward unit normals at the nodes of a face set (cell, local face) (face normals averaged)."""
    quads = cells[faces_cf[:, 0][:, None], HEX_FACES[faces_cf[:, 1]]]
    X = points[quads]
    nf = np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 1])
    out = X.mean(1) - points[cells[faces_cf[:, 0]]].mean(1)
    nf *= np.sign(np.einsum("ij,ij->i", nf, out))[:, None]
    return quads, nf


def flank_compliance(gear: Gear, side: int, grid: FlankGrid, material: Material, element: str = "hex8i",
                     solver: str = "auto") -> FlankCompliance:
    """Build the condensed flank compliance of ``gear``'s flanks on ``side`` (module docstring)."""
    t0 = time.perf_counter()
    mesh = _mesh(gear, side, grid)
    t_mesh = time.perf_counter() - t0
    name = mesh.bodies[0]
    tlist = model_teeth(gear, grid.teeth, 0)
    quads, nfs, tooth_of_face = [], [], []
    centre_angle = {}
    for j in tlist:
        fs = mesh.face_sets[f"{name}/tooth{j}/flank_{SIDE[side]}"]
        q, nf = _normals(mesh.points, mesh.cells, fs)
        quads.append(q)
        nfs.append(nf)
        tooth_of_face.append(np.full(len(q), j))
        both = np.concatenate([mesh.face_set_points(f"{name}/tooth{j}/flank_{s}") for s in ("pos", "neg")])
        xb = mesh.points[both]
        ang = np.unwrap(np.arctan2(xb[:, 1], xb[:, 0]))
        centre_angle[j] = np.polyfit(xb[:, 2], ang, 1)  # helical teeth: the centre plane turns linearly with z
    quads = np.concatenate(quads)
    nfs = np.concatenate(nfs)
    tof = np.concatenate(tooth_of_face)
    nodes, inv = np.unique(quads, return_inverse=True)
    inv = inv.reshape(quads.shape)
    m = len(nodes)
    nrm = np.zeros((m, 3))
    np.add.at(nrm, inv.ravel(), np.repeat(nfs, 4, axis=0))
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    node_tooth = np.zeros(m, np.int64)
    node_tooth[inv.ravel()] = np.repeat(tof, 4)
    x = mesh.points[nodes]
    # centre plane of each tooth: through the axis at the mean angle of the tooth's flank nodes at that level
    psi = np.array([np.polyval(centre_angle[j], z) for j, z in zip(node_tooth, x[:, 2])])
    e = np.stack([-np.sin(psi), np.cos(psi), np.zeros(m)], 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        h = np.einsum("ij,ij->i", x, e) / np.einsum("ij,ij->i", nrm, e)
    if not np.all(np.isfinite(h) & (h > 0)):
        raise GeometryError(gear.name, "flank normals", "a flank normal does not point away from its tooth's centre plane")
    P = x - h[:, None] * nrm
    # observation: normal displacement at P (inverse-distance weights of the 8 nearest nodes)
    dist, near = cKDTree(mesh.points).query(P, k=8)
    wgt = 1.0 / np.maximum(dist, 1e-9) ** 2
    wgt /= wgt.sum(1, keepdims=True)
    rows = np.repeat(np.arange(m), 24)
    cols = (3 * near[:, :, None] + np.arange(3)).reshape(m, 24).ravel()
    vals = (wgt[:, :, None] * nrm[:, None, :]).reshape(m, 24).ravel()
    n3 = 3 * mesh.n_points
    Q = sp.csr_matrix((vals, (rows, cols)), shape=(m, n3))
    # unit inward normal loads at the flank nodes (compressive contact force)
    Pm = sp.csc_matrix(((-nrm).ravel(), ((3 * nodes[:, None] + np.arange(3)).ravel(), np.repeat(np.arange(m), 3))),
                       shape=(n3, m))
    t1 = time.perf_counter()
    lam = np.full(mesh.n_cells, material.lam)
    mu = np.full(mesh.n_cells, material.mu)
    em = hex8_matrices(mesh.points, mesh.cells, lam, mu, element == "hex8i")
    K = assemble_blocks(em.stiffness, mesh.cells, mesh.n_points)
    fixed = np.zeros(n3, bool)
    rim = mesh.point_sets[f"{name}/rim"]
    fixed[(3 * rim[:, None] + np.arange(3)).ravel()] = True
    t_asm = time.perf_counter() - t1
    # C_ij: inward approach of P_i (along -n_i) per unit compressive load at j
    C, info = influence_matrix(K, fixed, Pm, -Q, solver)
    info.update(mesh_s=t_mesh, assembly_s=t_asm, nodes=mesh.n_points, elements=mesh.n_cells, flank_nodes=m,
                total_s=time.perf_counter() - t0)
    return FlankCompliance(gear, side, tuple(tlist), x, nrm, h, inv, C, info)
