r"""Design-review pictures of a computed load case (issue 17): what is drawn where, from the run (:class:`pipelines.models.stress.run.StressRun`).

Inputs are the objects returned by :func:`pipelines.models.stress.run.run_stress` (``tca``, ``scene``, ``mesh``,
``result``). Every interface member of the scene (a pair's mesh; the twin drive's sun–planet and
planet–ring meshes of members a and b) gives:

* ``teeth_<interface>_<member>.png`` — :func:`pipelines.render.views.render_teeth`: the driver and
  driven parts (three teeth each) along the gear axis, and the loaded flank's part along the
  contact normal; von Mises [MPa] on one colour range per run (:func:`colour_top`: the 99.5th
  percentile of the shown nodes, at least 1.1 × the largest fillet von Mises stress; labelled as
  clipped), the loaded pair marked by an arrow at the TCA contact point;
* ``deformed_<interface>_<member>.png`` — the same axial view, displacements scaled;
* ``flank_<interface>_<member>.png`` — the FE contact pressure on the loaded (slave) flank in the
  flank's own coordinates (axial position :math:`z` and radius :math:`\rho = \sqrt{x^2+y^2}` in the
  gear frame :math:`x_g = R^T(x_f - t)`, invariant to the tooth index), with the TCA's path of
  contact on that tooth surface (``point1``/``point2`` of the pair TCA over its grid), the TCA's
  contact ellipse at the analysed position (semi-axes :math:`\sqrt{2\delta/\lambda_i}`, δ the TCA's
  elastic approach, :mod:`tca.contact.ellipse`) and the Hertz ellipse under the FE force of the loaded pair
  (:func:`pipelines.models.stress.sizing.hertz_contact`); FE patch against TCA prediction (no ellipse at an
  edge or corner contact);
* ``section_<interface>_<member>.png`` — the transverse plane through the TCA contact point
  (normal: the slave gear's axis): von Mises of both loaded teeth with their fillets, and a zoom
  under the contact with the depth of the Hertz maximum shear (0.78 b for a line contact,
  Johnson, Contact Mechanics, §4.2) marked;
* ``root_<interface>_<member>.png`` — the largest principal stress along the fillets of the two
  loaded teeth (driving and coast sides) over the face width.

The ellipse axes on the tangent plane: :math:`e_1` the driver's axis projected on the plane,
:math:`e_2 = n \times e_1`, the major axis at the TCA angle from :math:`e_1` (:mod:`tca.contact.ellipse`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tca.pair.analysis import ContactKind, PairTCAResult
from pipelines.models.stress.run import StressRun
from pipelines.models.stress.sizing import HertzContact

__all__ = ["parts_of", "elastic_displacement", "InterfaceView", "interface_views", "ellipse_outline", "ellipse_axes",
           "to_gear", "flank_zr", "surface_contact", "cut_point", "flank_set", "tca_semi_axes", "patch_extent", "flank_map",
           "section", "root_curves", "loaded_pair_force", "fe_hertz", "colour_top", "picture_range", "Pictures",
           "design_pictures"]


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
    interface: object  # pipelines.models.stress.scene.Interface
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
    A, B = ellipse_axes(v)
    t = np.linspace(0.0, 2 * math.pi, npts)
    return v.point + a * np.cos(t)[:, None] * A + b * np.sin(t)[:, None] * B


def _side_name(part, itf) -> str:
    side = itf.side1 if part is itf.driver else itf.side2
    return "pos" if side > 0 else "neg"


def surface_contact(v: InterfaceView) -> bool:
    """The TCA contact is inside both surfaces (not at an edge or corner): its ellipse and Hertz apply."""
    return int(v.interface.contact.kind) == int(ContactKind.SURFACE)


def cut_point(v: InterfaceView, inset: float = 0.5) -> tuple[np.ndarray, float]:
    """Point [mm] of the transverse cut through the contact, and its shift along the axis [mm].

    An edge contact at an end face would be cut in the face itself: the plane is moved
    max(`inset`, 2 % of the face width) inside the slave's face width there (shift 0 elsewhere).
    """
    g = to_gear(v.slave, v.point)
    half = 0.5 * v.slave.gear.face_width
    room = max(inset, 0.02 * 2 * half)
    z = float(np.clip(g[2], -half + room, half - room))
    shift = z - float(g[2])
    return v.point + shift * v.axis, shift


def flank_set(v: InterfaceView) -> str:
    """Face set of the loaded (slave) flank of the loaded tooth."""
    return v.slave.set(f"tooth{v.slave.centre}/flank_{_side_name(v.slave, v.interface)}")


def ellipse_axes(v: InterfaceView) -> tuple[np.ndarray, np.ndarray]:
    """Unit major and minor axes of the TCA contact ellipse on the tangent plane (S_f)."""
    itf = v.interface
    n = _unit(itf.normal)
    d_axis = _unit(itf.driver.R[:, 2])
    e1 = _unit(d_axis - (d_axis @ n) * n)
    e2 = np.cross(n, e1)
    A = math.cos(itf.contact.angle) * e1 + math.sin(itf.contact.angle) * e2
    return A, np.cross(n, A)


def tca_semi_axes(v: InterfaceView, delta: float) -> tuple[float, float]:
    """TCA ellipse semi-axes sqrt(2 δ / λ_i) [mm] at the analysed position (inf: line contact)."""
    lam = v.interface.contact.curvature
    return tuple(math.sqrt(2 * delta / x) if x > 1e-9 else math.inf for x in lam)


def patch_extent(v: InterfaceView, mesh, pressure: np.ndarray) -> dict:
    """FE contact patch on the loaded flank (p > PATCH_FRACTION x peak): its lengths [mm] along the TCA
    ellipse's major and minor axes and its centre's offset from the TCA point [mm]."""
    from pipelines.render.maps import PATCH_FRACTION

    nodes = mesh.face_set_points(flank_set(v))
    p = np.nan_to_num(pressure[nodes])
    peak = float(p.max(initial=0.0))
    if peak <= 0:
        return {"length_mm": 0.0, "width_mm": 0.0, "offset_mm": float("nan"), "peak_mpa": 0.0}
    on = nodes[p > PATCH_FRACTION * peak]
    A, B = ellipse_axes(v)
    d = mesh.points[on] - v.point
    sa, sb = d @ A, d @ B
    w = np.nan_to_num(pressure[on])
    c = (w[:, None] * mesh.points[on]).sum(0) / w.sum()
    return {"length_mm": float(np.ptp(sa)), "width_mm": float(np.ptp(sb)), "offset_mm": float(np.linalg.norm(c - v.point)),
            "peak_mpa": peak}


def flank_map(v: InterfaceView, mesh, result, path: Path, delta: float, hertz: dict | None = None, title: str = "") -> Path:
    """``flank_<interface>_<member>.png``: FE pressure on the loaded flank with the TCA's path and ellipses (module docstring)."""
    from pipelines.render.maps import Curve, TriField, plot_flank_pressure, quads_to_triangles

    q = mesh.face_nodes(flank_set(v))
    nodes, inv = np.unique(q, return_inverse=True)
    tri = quads_to_triangles(inv.reshape(q.shape))
    zr = flank_zr(v.slave, mesh.points[nodes])
    curves = []
    r = v.tca
    if r is not None:
        pts = r.point1 if v.which == 1 else r.point2
        ok = np.all(np.isfinite(pts), axis=1)
        if ok.any():
            curves.append(Curve(pts[ok, 2], np.hypot(pts[ok, 0], pts[ok, 1]), "TCA path of contact", ".", "k"))
    hz = hertz or v.interface.hertz
    if surface_contact(v):  # at an edge or corner the TCA has no ellipse and Hertz does not apply
        a, b = tca_semi_axes(v, delta)
        if math.isfinite(a) and math.isfinite(b):
            e = flank_zr(v.slave, ellipse_outline(v, a, b))
            curves.append(Curve(e[:, 0], e[:, 1], f"TCA ellipse (δ = {delta * 1e3:g} µm): {2 * a:.2f} x {2 * b:.2f} mm",
                                "--", "k"))
        e = flank_zr(v.slave, ellipse_outline(v, hz.a, hz.b))
        curves.append(Curve(e[:, 0], e[:, 1], f"Hertz ellipse (P = {hz.load:.0f} N): {2 * hz.a:.2f} x "
                            f"{2 * hz.b:.2f} mm", "-", "m"))
    ar = v.slave.gear.area(1 if _side_name(v.slave, v.interface) == "pos" else -1)
    pt = flank_zr(v.slave, v.point[None, :])[0]
    zoom = min(max(3.0 * hz.b, 1.2 * hz.a, 1.0), 0.3 * (ar.z_max - ar.z_min))
    if not surface_contact(v):
        title = (title + " (TCA: " if title else "(TCA: ") + f"{ContactKind.names.get(int(v.interface.contact.kind), '?')} contact, no ellipse)"
    return plot_flank_pressure(TriField(zr, tri, np.nan_to_num(result.contact_pressure[nodes])), path, curves=curves,
                               point=pt, area=(ar.z_min, ar.z_max, ar.r_form, ar.r_tip), title=title, zoom=zoom)


def section(v: InterfaceView, grid, path: Path, vmax: float, hertz: dict | None = None, title: str = "") -> Path:
    """``section_<interface>_<member>.png``: von Mises on the transverse plane through the contact point."""
    from pipelines.render.maps import DepthMark, TriField, plot_section

    origin, shift = cut_point(v)
    sl = grid.extract_cells(v.cells).slice(normal=v.axis, origin=origin).triangulate()
    faces = np.asarray(sl.faces).reshape(-1, 4)[:, 1:]
    ex = _unit(np.cross(v.up, v.axis))
    x = np.asarray(sl.points) - origin
    if shift:
        title = f"{title} (plane {abs(shift):.2f} mm inside the face width from the edge contact)"
    xy = np.stack([x @ ex, x @ v.up], -1)
    down3 = -v.view - (-v.view @ v.axis) * v.axis
    down = np.array([_unit(down3) @ ex, _unit(down3) @ v.up])
    b = (hertz or v.interface.hertz).b
    zoom = max(6.0 * b, 1.0) if surface_contact(v) else 1.5
    if not surface_contact(v):
        b = None
    return plot_section(TriField(xy, faces, sl.point_data["von_mises"]), path, vmax=vmax, point=(0.0, 0.0),
                        depth=None if b is None else DepthMark(0.78 * b, down), zoom=zoom, title=title)


def root_curves(v: InterfaceView, mesh, result) -> list:
    """Largest principal stress [MPa] at each axial level of the two fillets of both loaded teeth.

    Axial position [mm]: from the TCA contact point along the slave gear's axis, common to both gears
    (their own frames may run opposite ways: the planet's is turned over in Part 1).
    """
    from pipelines.render.maps import Curve

    out = []
    for part, colors in ((v.slave, ("C3", "C1")), (v.master, ("C0", "C2"))):
        loaded = _side_name(part, v.interface)
        for side, style, color in ((loaded, "-", colors[0]), ("neg" if loaded == "pos" else "pos", "--", colors[1])):
            name = part.set(f"tooth{part.centre}/fillet_{side}")
            if name not in mesh.point_sets:
                continue
            nodes = mesh.point_sets[name]
            # the mesh's axial levels are planes of the gear's own frame; plotted at their mean position
            # along the slave's axis from the contact point (one coordinate for both gears)
            _, inv = np.unique(np.round(to_gear(part, mesh.points[nodes])[:, 2], 6), return_inverse=True)
            n = inv.max() + 1
            levels = np.bincount(inv, (mesh.points[nodes] - v.point) @ v.axis, n) / np.bincount(inv, None, n)
            top = np.full(n, -np.inf)
            np.maximum.at(top, inv, result.principal[nodes, 0])
            order = np.argsort(levels)
            levels, top = levels[order], top[order]
            which = "loaded flank's side (tension)" if side == loaded else "other side"
            out.append(Curve(levels, top, f"{part.body} tooth {part.centre}: fillet on the {which}", style, color))
    return out


def loaded_pair_force(v: InterfaceView, summary: dict) -> float:
    """FE normal force [N] on the loaded tooth pair of an interface member (offset 0)."""
    teeth = summary["interfaces"][v.name]["teeth"]
    return float(sum(t["force_n"] for k, t in teeth.items() if k.startswith(f"{v.member}/") and t["offset"] == 0))


def fe_hertz(v: InterfaceView, result, force: float) -> HertzContact:
    """Hertz contact (pipelines.models.stress.sizing.hertz_contact) under the FE force of the loaded pair [N]."""
    from pipelines.models.stress.sizing import hertz_contact

    mat = result.model.bodies[0].material
    width = min(v.slave.gear.face_width, v.master.gear.face_width)
    return hertz_contact(v.interface.contact.curvature, max(force, 1e-9), mat, width)


def colour_top(summary: dict, mesh, result, views) -> "object":
    """The run's von Mises colour range for the pictures: P99.5 of the shown parts' nodes, at least 1.1 x the
    largest fillet von Mises stress (pipelines.render.views.clip_range)."""
    from pipelines.render.views import clip_range

    cells = np.unique(np.concatenate([v.cells for v in views])) if views else np.arange(mesh.n_cells)
    fil = summary.get("max_fillet_von_mises_mpa") or 0.0
    return clip_range(result.von_mises[np.unique(mesh.cells[cells])], floor=1.1 * fil)


def picture_range(run: StressRun):
    """:func:`colour_top` of a computed run (before its pictures are drawn; ``gearfe compare`` shares the top)."""
    return colour_top(run.summary, run.mesh, run.result, interface_views(run.scene, run.mesh, run.tca))


@dataclass(frozen=True)
class Pictures:
    """File names written per interface member and the numbers behind them (JSON-ready records)."""

    files: dict  # stem -> {kind: file name}
    records: dict  # stem -> {quantity: value}
    colour: object  # the ColourRange of the von Mises pictures


def share_text(summary: dict, interface: str, member: str) -> str:
    """'member share 1.000, loaded pair sun0-planet0 0.612' (the loaded pair's share where several pairs carry load)."""
    share = summary["load_share"][interface]["members"][member]
    teeth = {n: t for n, t in summary["interfaces"][interface].get("teeth", {}).items() if n.startswith(f"{member}/")}
    loaded = next((n for n, t in teeth.items() if t.get("offset") == 0), None)
    pair = ""
    if loaded is not None and len(teeth) > 1:
        pair = f", loaded pair {loaded.split('/')[-1]} {summary['load_share'][interface]['teeth'][loaded]:.3f}"
    return f"member share {share:.3f}{pair}"


def design_pictures(run: StressRun, out: Path, *, top: float | None = None, show_edges: bool = False,
                    size=(1300, 600)) -> Pictures:
    """All pictures of the module docstring for every interface member, into ``out``.

    ``top`` [MPa] fixes the top of the von Mises range (``gearfe compare``: one range for both
    designs); by default :func:`colour_top`.
    """
    from pipelines.render.images import to_pyvista
    from pipelines.render.maps import plot_root_stress
    from pipelines.render.views import Colouring, Frame, Mark, clip_range, deformation_scale, render_deformed, render_teeth

    summary, mesh, result, scene, tca = run.summary, run.mesh, run.result, run.scene, run.tca
    out = Path(out)
    views = interface_views(scene, mesh, tca)
    cr = colour_top(summary, mesh, result, views)
    if top is not None:
        cells = np.unique(np.concatenate([v.cells for v in views]))
        cr = clip_range(result.von_mises[np.unique(mesh.cells[cells])], fixed=top)
    grid = to_pyvista(mesh, {"von_mises": result.von_mises, "displacement": elastic_displacement(mesh, result)})
    delta = tca.options.elastic_approach if isinstance(tca, PairTCAResult) else (
        views[0].tca.options.elastic_approach if views and views[0].tca is not None else 0.0065)
    files, records = {}, {}
    for v in views:
        f = {}
        head = f"{v.name}, member {v.member}: " + share_text(summary, v.name, v.member)
        parts = grid.extract_cells(v.cells)
        force = loaded_pair_force(v, summary)
        mark = Mark(tuple(v.point), tuple(v.view), ("loaded pair" if force > 0 else "TCA pair, no load") +
                    f": {v.slave.body} {v.slave.centre} / {v.master.body} {v.master.centre}")
        frame = Frame(v.axis, v.up, v.view, cut_point(v)[0])
        f["teeth"] = render_teeth(parts, grid.extract_cells(v.flank_cells), out / f"teeth_{v.stem}.png", frame,
                                  Colouring(cr, show_edges=show_edges), marks=[mark], caption=head, size=size).name
        scale = deformation_scale(parts.point_data["displacement"], float(np.linalg.norm(np.ptp(parts.points, axis=0))))
        f["deformed"] = render_deformed(parts, out / f"deformed_{v.stem}.png", frame, Colouring(cr),
                                        factor=scale, size=(int(0.7 * size[0]), int(1.1 * size[1])),
                                        caption=f"{head}\nelastic displacements x {scale:.3g} (rigid-body motion removed)").name
        hz = fe_hertz(v, result, force)
        f["flank"] = flank_map(v, mesh, result, out / f"flank_{v.stem}.png", delta, hertz=hz,
                               title=f"{head}: FE contact pressure on the loaded {v.slave.body} flank against the TCA").name
        f["section"] = section(v, grid, out / f"section_{v.stem}.png", cr.hi, hertz=hz,
                               title=f"{head}: von Mises [MPa] on the transverse section through the contact point").name
        curves = root_curves(v, mesh, result)
        f["root"] = plot_root_stress([(head, curves)], out / f"root_{v.stem}.png",
                                     xlabel=f"axial position from the contact point along the {v.slave.body} axis [mm]").name
        files[v.stem] = f
        a, b = tca_semi_axes(v, delta)
        patch = patch_extent(v, mesh, result.contact_pressure)
        ok = surface_contact(v)  # else no ellipse: None in the records
        records[v.stem] = {
            "interface": v.name, "member": v.member, "load_share": summary["load_share"][v.name]["members"][v.member], "loaded_pair_force_n": force,
            "tca_kind": ContactKind.names.get(int(v.interface.contact.kind), str(v.interface.contact.kind)),
            "fe_peak_pressure_mpa": patch["peak_mpa"], "hertz_p0_mpa": float(hz.p0) if ok else None,
            "fe_patch_length_mm": patch["length_mm"], "hertz_length_mm": 2 * float(hz.a) if ok else None,
            "tca_ellipse_length_mm": 2 * a if ok else None, "fe_patch_width_mm": patch["width_mm"],
            "hertz_width_mm": 2 * float(hz.b) if ok else None, "tca_ellipse_width_mm": 2 * b if ok else None,
            "fe_patch_centre_offset_mm": patch["offset_mm"],
            "root_stress_mpa": {c.label: float(np.max(c.y)) for c in curves},
            "deformation_scale": scale,
        }
    return Pictures(files, records, cr)
