r"""Design-review pictures of a computed load case (issue 17): what is drawn where, from the run's artefacts.

Inputs are the artefacts of :func:`pipelines.stress.run.run_stress` (``tca``, ``scene``, ``mesh``,
``result``). Every interface member of the scene (a pair's mesh; the twin drive's sun–planet and
planet–ring meshes of members a and b) gives:

* ``teeth_<interface>_<member>.png`` — :func:`pipelines.render.views.render_teeth`: the driver and
  driven parts (three teeth each) along the gear axis, and the loaded flank's part along the
  contact normal; von Mises [MPa] on one colour range per run clipped at the
  99.5th percentile (labelled), the loaded pair marked by an arrow at the TCA contact point;
* ``deformed_<interface>_<member>.png`` — the same axial view, displacements scaled;
* ``flank_<interface>_<member>.png`` — the FE contact pressure on the loaded (slave) flank in the
  flank's own coordinates (axial position :math:`z` and radius :math:`\rho = \sqrt{x^2+y^2}` in the
  gear frame :math:`x_g = R^T(x_f - t)`, invariant to the tooth index), with the TCA's path of
  contact on that tooth surface (``point1``/``point2`` of the pair TCA over its grid), the TCA's
  contact ellipse at the analysed position (semi-axes :math:`\sqrt{2\delta/\lambda_i}`, δ the TCA's
  elastic approach, Eq. of :mod:`tca.ellipse`) and the Hertz ellipse under the FE load
  (:func:`pipelines.stress.sizing.hertz_contact`); FE patch against TCA prediction;
* ``section_<interface>_<member>.png`` — the transverse plane through the TCA contact point
  (normal: the slave gear's axis): von Mises of both loaded teeth with their fillets, and a zoom
  under the contact with the depth of the Hertz maximum shear (0.78 b for a line contact,
  Johnson, Contact Mechanics, §4.2) marked;
* ``root_<interface>_<member>.png`` — the largest principal stress along the fillets of the two
  loaded teeth (driving and coast sides) over the face width.

The ellipse axes on the tangent plane: :math:`e_1` the driver's axis projected on the plane,
:math:`e_2 = n \times e_1`, the major axis at the TCA angle from :math:`e_1` (:mod:`tca.ellipse`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tca.pair_tca import PairTCAResult

__all__ = ["parts_of", "elastic_displacement", "InterfaceView", "interface_views", "ellipse_outline", "to_gear", "flank_zr"]


def parts_of(mesh) -> np.ndarray:
    """Connected part of every cell (parts of one body share no nodes: Fig. 1.7's members)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    nc, k = mesh.cells.shape
    a = coo_matrix((np.ones(nc * k), (np.repeat(np.arange(nc), k), mesh.cells.ravel())), shape=(nc, mesh.n_points)).tocsr()
    _, lab = connected_components(a @ a.T, directed=False)
    return lab


def elastic_displacement(mesh, result) -> np.ndarray:
    """Nodal displacements [mm] without the rigid bodies' motion: u - (t + w x (x - x_ref)) on each rigid body.

    The driven gear turns as a rigid body by the elastic approach over its radius; removing that
    leaves the deformation of the teeth (bending, Hertz flattening) for a scaled deformed view.
    """
    u = np.array(result.displacement, float)
    for body, (t, w) in result.rigid_motion.items():
        ref = mesh.reference_points.get(body)
        if ref is None or body not in mesh.bodies:
            continue
        nodes = np.unique(mesh.cells[mesh.body_cells(body)])
        x = mesh.points[nodes] - np.asarray(ref.point, float)
        u[nodes] -= np.asarray(t, float) + np.cross(np.asarray(w, float), x)
    return u


@dataclass(frozen=True, eq=False)
class InterfaceView:
    """One interface member's geometry for the pictures (all in S_f, [mm])."""

    name: str  # interface, e.g. 'sun-planet'
    member: str
    interface: object  # pipelines.stress.scene.Interface
    slave: object  # the slave Part (its flank carries the pressure)
    master: object  # the other Part
    which: int  # 1: the slave is the pair's gear 1 (driver), 2: gear 2
    cells: np.ndarray  # cells of both parts
    slave_cells: np.ndarray
    flank_cells: np.ndarray  # slave cells behind the tangent plane (seen along the normal)
    axis: np.ndarray  # slave gear axis (unit)
    up: np.ndarray  # radial direction of the slave gear at the contact point (unit, ⟂ axis)
    view: np.ndarray  # unit normal toward the camera: the master's side of the contact
    point: np.ndarray  # TCA contact point
    tca: PairTCAResult | None  # the pair TCA of this mesh

    @property
    def stem(self) -> str:
        return f"{self.name}_{self.member}"


def _pair_result(tca, itf) -> PairTCAResult | None:
    if isinstance(tca, PairTCAResult):
        return tca
    members = getattr(tca, "members", None)
    if not members or itf.member not in members:
        return None
    sub = members[itf.member]
    return (sub.mesh12 if itf.name == "sun-planet" else sub.mesh23).result


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def interface_views(scene, mesh, tca) -> list[InterfaceView]:
    """The parts, flank cells and directions of every interface member of a solved scene."""
    centres = mesh.points[mesh.cells].mean(axis=1)
    lab = parts_of(mesh)
    out = []
    for itf in scene.interfaces:
        slave, master = (itf.driven, itf.driver) if itf.slave == "driven" else (itf.driver, itf.driven)
        p = np.asarray(itf.point, float)

        def part_cells(part):
            cells = np.flatnonzero(mesh.cell_body == mesh.bodies.index(part.body))
            own = lab[cells[np.argmin(np.linalg.norm(centres[cells] - p, axis=1))]]
            return cells[lab[cells] == own]

        sc, mc = part_cells(slave), part_cells(master)
        n = _unit(itf.normal)
        view = -n if itf.slave == "driven" else n  # the TCA normal points out of the driver's tooth
        flank = sc[(centres[sc] - p) @ view < 0.0]
        axis = _unit(slave.R[:, 2])
        r = p - np.asarray(slave.t, float)
        up = _unit(r - (r @ axis) * axis)
        out.append(InterfaceView(itf.name, itf.member, itf, slave, master, 2 if itf.slave == "driven" else 1,
                                 np.union1d(sc, mc), sc, flank, axis, up, view, p, _pair_result(tca, itf)))
    return out


def to_gear(part, x) -> np.ndarray:
    """Points of S_f [mm] in the part's gear frame: x_g = R^T (x_f - t)."""
    return (np.asarray(x, float) - np.asarray(part.t, float)) @ np.asarray(part.R, float)


def flank_zr(part, x) -> np.ndarray:
    """(z, radius) [mm] of S_f points in the part's gear frame (the flank's own coordinates)."""
    g = to_gear(part, x)
    return np.stack([g[..., 2], np.hypot(g[..., 0], g[..., 1])], -1)


def ellipse_outline(v: InterfaceView, a: float, b: float, npts: int = 73) -> np.ndarray:
    """Ellipse of semi-axes a, b [mm] on the tangent plane at the contact point, major axis at the TCA angle (S_f)."""
    itf = v.interface
    n = _unit(itf.normal)
    d_axis = _unit(itf.driver.R[:, 2])
    e1 = _unit(d_axis - (d_axis @ n) * n)
    e2 = np.cross(n, e1)
    ang = itf.contact.angle
    A = math.cos(ang) * e1 + math.sin(ang) * e2
    B = np.cross(n, A)
    t = np.linspace(0.0, 2 * math.pi, npts)
    return v.point + a * np.cos(t)[:, None] * A + b * np.sin(t)[:, None] * B
