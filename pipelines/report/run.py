"""One load case end to end: TCA → position → mesh → contact FE → images → report (issue 7).

``run_pipeline(case, out, progress)`` runs :func:`pipelines.models.stress.run.run_stress` (TCA, the position —
by default the maximum of the transmission error, as the report does, or the case's ``phi1_deg`` —,
the hexahedral models, the contact solve, ``result.vtu``), then writes into ``out``:

* ``tca_te.png`` — the TE function(s) over the TCA grid with the analysed position marked (for the
  twin drive: members a and b and Eq. (1.15), their maximum); for a pair also ``tca_paths.png``
  (paths of contact and ellipses on both surfaces);
* ``zone_<interface>_<member>.png`` — von Mises stress [MPa] on the loaded flank of the slave body
  (the planet in Part 1) around each mesh's TCA contact point, the other body hidden, the camera on
  the side of the hidden body looking along the contact normal (cells in front of the tangent plane
  at the contact — the neighbouring teeth that would hide the flank — are left out); ``zone_..._pressure.png`` the same
  with the contact pressure [MPa] (edge contact shows as a ridge on the flank's border);
* per mesh the design-review pictures of :func:`pipelines.report.figures.design_pictures`
  (``teeth_``, ``deformed_``, ``flank_``, ``section_``, ``root_<interface>_<member>.png``; their
  numbers under ``pictures`` in the summary; docs/pictures.md);
* ``overview.png`` — the whole model cut through the first mesh's contact point, lit, on the
  pictures' clipped von Mises range (each member's largest von Mises stress on its loaded part, as
  shown in its zone image, is added to the summary: ``interfaces.<i>.members.<m>.max_von_mises_mpa``);
* ``report.md`` — the key numbers, stage times and the images; ``summary.json`` and the
  self-contained ``report.html`` (:mod:`pipelines.report.html`) are written by the command (all keys
  of ``gearfe stress`` plus ``stages`` with the time of every stage [s]).

Colour ranges: every zone image of a run shares one range (0 to the run's largest value on the
shown flanks) unless ``clim`` fixes it (``gearfe compare`` uses one range for both designs).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from tca.pair.analysis import PairTCAResult

from pipelines.analyses.rating import rating_record
from pipelines.cases.rating import rated_meshes
from pipelines.jsonio import plain
from pipelines.models.stress.case import StressCase

from pipelines.models.stress.run import StressRun, run_stress

from pipelines.report.figures import design_pictures, parts_of, share_text

__all__ = ["STAGES", "run_pipeline", "add_images", "zone_images", "zone_limits", "write_report", "zone_name"]

STAGES = ("tca", "mesh", "solve", "results", "images", "report")
EDGES_UP_TO = 6000  # element edges are drawn in zone images of at most this many cells


def zone_name(interface: str, member: str) -> str:
    """File stem of a contact-zone image, e.g. 'zone_sun-planet_a'."""
    return f"zone_{interface}_{member}"


def _zone_radius(m: dict) -> float:
    """View radius [mm] of a contact zone: the whole loaded flank across the face width, at least the ellipse."""
    hz = m["hertz_estimate"]
    return max(0.6 * m["face_width_mm"], 1.5 * hz.get("a_mm", 0.0))


def _view(m: dict) -> np.ndarray:
    """Unit vector from the contact point toward the camera: the hidden (other) body's side of the contact."""
    n = np.asarray(m["tca_normal"], float)
    return n if m["slave_is_driver"] else -n  # the TCA normal points out of the driver's tooth


def _zones(summary: dict, mesh, grid) -> list:
    """(interface, member, summary of the member, sub-grid of its loaded part near the contact, view radius)."""
    out = []
    centres = mesh.points[mesh.cells].mean(axis=1)
    part = parts_of(mesh)
    for itf, d in summary["interfaces"].items():
        for member, m in d["members"].items():
            p = np.asarray(m["tca_contact_point_mm"])
            cells = np.flatnonzero(mesh.cell_body == mesh.bodies.index(m["slave_body"]))
            own = part[cells[np.argmin(np.linalg.norm(centres[cells] - p, axis=1))]]  # the part carrying the contact
            cells = cells[part[cells] == own]
            r = _zone_radius(m)
            off = centres[cells] - p
            # behind the tangent plane only: the convex loaded flank stays, the neighbouring teeth that
            # would hide it from a camera on the contact normal go
            near = cells[(np.linalg.norm(off, axis=1) < 3 * r) & (off @ _view(m) < 0.0)]
            out.append((itf, member, m, grid.extract_cells(near), r))
    return out


def _grid(mesh, result):
    from pipelines.render.images import to_pyvista

    return to_pyvista(mesh, {"von_mises": result.von_mises, "contact_pressure": np.nan_to_num(result.contact_pressure)})


def _maxima(zones) -> dict:
    """Largest von Mises and contact pressure [MPa] over the sub-grids of `zones`."""
    return {f: max((float(np.nanmax(z[3].point_data[f], initial=0.0)) for z in zones), default=0.0)
            for f in ("von_mises", "contact_pressure")}


def zone_limits(summary: dict, mesh, result) -> dict:
    """Largest von Mises and contact pressure [MPa] on the flanks shown in the zone images."""
    return _maxima(_zones(summary, mesh, _grid(mesh, result)))


def zone_images(summary: dict, mesh, result, out: Path, clim: dict | None = None, size=(1200, 900),
                overview_range=None) -> tuple[list, dict]:
    """Contact-zone images of every interface and member, and the overview (module docstring).

    Returns the file names and the largest von Mises stress [MPa] on each zone's loaded part
    ({(interface, member): value}).

    ``clim``: fixed colour ranges {field: max [MPa]} ('von_mises', 'contact_pressure'); a field
    not given gets the largest value over this run's zone images. ``overview_range``: the
    :class:`pipelines.render.views.ColourRange` of ``overview.png`` (default: clipped as the pictures).
    """
    from pipelines.render.images import Scalars, Zone, render_contact_zone, render_overview
    from pipelines.render.views import clip_range

    grid = _grid(mesh, result)
    zones = _zones(summary, mesh, grid)
    lim = {**_maxima(zones), **(clim or {})}
    names, peaks = [], {}
    for itf, member, m, sub, r in zones:
        view = _view(m)
        edge = "edge contact" if m.get("edge_contact") else "no edge contact"
        cap = f"{itf}, member {member} ({m['slave_body']} flank): {share_text(summary, itf, member)}, {edge}"
        stem = zone_name(itf, member)
        vm = peaks[(itf, member)] = float(np.nanmax(sub.point_data["von_mises"], initial=0.0))
        edges = sub.n_cells <= EDGES_UP_TO
        look = np.asarray(sub.center) if sub.n_cells else np.asarray(m["tca_contact_point_mm"])  # frame the whole flank
        zone = Zone(look, view, r)
        render_contact_zone(sub, out / f"{stem}.png", zone, Scalars("von_mises", clim=(0.0, lim["von_mises"] or 1.0)),
                            size=size, show_edges=edges, caption=cap + f"\nmax von Mises {vm:.0f} MPa")
        render_contact_zone(sub, out / f"{stem}_pressure.png", zone,
                            Scalars("contact_pressure", "contact pressure [MPa]", (0.0, lim["contact_pressure"] or 1.0)),
                            size=size, show_edges=edges,
                            caption=cap + f"\nmax contact pressure {m['max_contact_pressure_mpa']:.0f} MPa")
        names += [f"{stem}.png", f"{stem}_pressure.png"]
    cr = overview_range if overview_range is not None else clip_range(result.von_mises, floor=1.1 * (summary.get("max_fillet_von_mises_mpa") or 0.0))
    # cut by the transverse plane (normal z_f, the sun's or driver's axis) through the first mesh's contact point
    cut = (zones[0][2]["tca_contact_point_mm"], (0.0, 0.0, 1.0)) if zones else None
    render_overview(grid, "von_mises", out / "overview.png", size=size, clim=(cr.lo, cr.hi), title=cr.label("von Mises [MPa]"), cut=cut,
                    caption=f"{summary.get('title') or summary.get('model')}: max von Mises {summary['max_von_mises_mpa']:.0f} MPa")
    names.append("overview.png")
    return names, peaks


def peak_images(run: StressRun, out: Path) -> list[tuple[str, str]]:
    """A picture of every flagged peak: (file, caption), :func:`pipelines.render.peaks.plot_peak_map`.

    Edge and corner contact peaks: the contact pressure on the slave flank they were recovered on; contact-induced
    fillet peaks: the largest principal stress on the fillet and the flank above it. Both unrolled onto (axial
    position, radius) in their gear's frame, the peak circled.
    """
    from pipelines.models.stress.headline import gear_coords, gear_frame_part
    from pipelines.render.peaks import plot_peak_map

    summary, mesh, result, scene = run.summary, run.mesh, run.result, run.scene
    p = np.nan_to_num(result.contact_pressure)
    files = []

    def unrolled(part, nodes, at):
        """(z, r) of the nodes within 0.4 m_n of the peak's radius (the whole face width), the peak's (z, r)."""
        g = gear_coords(part, mesh.points[nodes])
        q = gear_coords(part, np.asarray([at], float))[0]
        r, rq = np.hypot(g[:, 0], g[:, 1]), float(np.hypot(q[0], q[1]))
        keep = np.abs(r - rq) <= 0.4 * part.gear.module
        return nodes[keep], g[keep, 2], r[keep], (float(q[2]), rq)

    for k, e in enumerate(summary.get("edge_peaks", [])):
        cp = next((c for c in run_contacts(run) if c[0] == e["pair"]), None)
        if cp is None:
            continue
        part = gear_frame_part(scene, cp[1])
        nodes = mesh.face_set_points(cp[1])
        nodes, z, r, at = unrolled(part, nodes, e["edge_point_mm"])
        f = f"peak_edge_{k}.png"
        cap = (f"{e['edge_kind']} of the {e['edge_of']}, pair {e['pair'].split('/')[-1]}: {e['edge_peak_mpa']:.0f} MPa, "
               f"the pair's smooth peak {e['smooth_peak_mpa']:.0f} MPa; contact pressure on the {part.gear.name} flank")
        plot_peak_map(z, r, p[nodes], at, out / f, cap, "contact pressure [MPa]")
        files.append((f, cap + f"; at ({', '.join(f'{x:.2f}' for x in e['edge_point_mm'])}) mm in the fixed frame"))
    for k, fp in enumerate(summary.get("fillet_peaks", [])):
        part = gear_frame_part(scene, fp["set"])
        sets = [fp["set"], fp["set"].replace("fillet_", "flank_")]
        nodes = np.unique(np.concatenate([mesh.face_set_points(x) for x in sets if x in mesh.face_sets]))
        nodes, z, r, at = unrolled(part, nodes, fp["point_mm"])
        f = f"peak_fillet_{k}.png"
        cap = (f"{fp['cause']} on {fp['set']}: {fp['value_mpa']:.0f} MPa, the fillet away from it "
               f"{fp['clear_max_mpa']:.0f} MPa; largest principal stress on the fillet and its flank")
        plot_peak_map(z, r, result.principal[nodes, 0], at, out / f, cap, "largest principal stress [MPa]")
        files.append((f, cap + f"; at ({', '.join(f'{x:.2f}' for x in fp['point_mm'])}) mm in the fixed frame"))
    return files


def run_contacts(run: StressRun) -> list[tuple[str, str, str]]:
    """(pair name, slave face set, master face set) of the run's contact pairs."""
    return [(c["pair"], c["slave_set"], c["master_set"]) for c in run.summary.get("contact_peaks", []) if "slave_set" in c]


def _fmt(v, nd=4) -> str:
    if isinstance(v, bool) or v is None:
        return str(v)
    if isinstance(v, float):
        return f"{v:.{nd}g}"
    return str(v)


def write_report(summary: dict, path: Path) -> Path:
    """report.md: the case, position, key results, load shares, stage times and images."""
    s = summary
    pos = s["position"]
    lines = [f"# {s.get('title') or s['model']}", "",
             f"Model `{s['model']}`, torque {s['torque_nm']:g} N·m, case `{s.get('case', '')}`.", "",
             "## Position (TCA)", "",
             f"- φ1 = {pos['phi1_deg']:.6f} deg"]
    for k in ("te_arcsec", "te3_arcsec", "leading_member", "member_phase", "kind", "active_pair"):
        if k in pos:
            lines.append(f"- {k} = {_fmt(pos[k])}")
    reg = s.get("tca", {}).get("regulation")
    if reg:
        lines.append("- regulation: " + ", ".join(f"{k} = {_fmt(v)}" for k, v in reg.items()))
    lines += ["", "## Results", "", "| quantity | value |", "|---|---|"]
    for k in ("max_von_mises_mpa", "max_von_mises_body", "max_contact_pressure_mpa", "contact_force_n",
              "contact_area_mm2", "max_fillet_stress_mpa", "max_fillet_set", "torque_balance_error",
              "torque_balance_error_kinematic", "reaction_torque_nm", "expected_reaction_torque_nm", "edge_contact",
              "fe_edge_contact", "dofs", "elements"):
        if k in s:
            lines.append(f"| {k} | {_fmt(s[k])} |")
    lines += ["", "## Load share and edge contact per mesh", "",
              "| interface | member | load share | force [N] | max pressure [MPa] | max von Mises on the loaded part [MPa] | "
              "edge pressure [MPa] | edge contact | TCA contact | Hertz p0 [MPa] |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for itf, d in s["interfaces"].items():
        for mem, m in d["members"].items():
            lines.append(f"| {itf} | {mem} | {s['load_share'][itf]['members'][mem]:.4f} | {m['force_n']:.1f} | "
                         f"{m['max_contact_pressure_mpa']:.1f} | {_fmt(m.get('max_von_mises_mpa'), 5)} | "
                         f"{m['edge_pressure_mpa']:.1f} | {m['edge_contact']} | "
                         f"{m['tca_kind']} | {m['hertz_estimate']['p0_mpa']:.0f} |")
    for itf, d in s["interfaces"].items():  # where the load was shared: every modelled pair of teeth
        shares = s["load_share"][itf].get("teeth", {})
        rows = sorted((t.get("offset", 0), n, shares.get(n, 0.0)) for n, t in d.get("teeth", {}).items())
        if rows:
            lines += ["", f"Load per pair of teeth, {itf} (offset 0: the loaded pair of the TCA): "
                      + ", ".join(f"{n} (offset {q:+d}) {v:.3f}" for q, n, v in rows) + "."]
    iso = s.get("iso6336_sigma_f0_mpa")
    if iso:
        lines += ["", "ISO 6336-3 method B nominal root stress σ_F0 (whole load on one tooth at its HPSTC, no load "
                  "factors): " + ", ".join(f"{g} {_fmt(v)} MPa" for g, v in iso.items())
                  + f"; FE max fillet stress {_fmt(s.get('max_fillet_stress_mpa'))} MPa ({s.get('max_fillet_set', '')})."]
    for g, r in s.get("root_stress", {}).items():
        lines.append(f"- {g}: loaded tooth {r['tooth']} (share {_fmt(r['load_share'])}) at ISO's 30° section "
                     f"{_fmt(r['critical_section_mpa'])} MPa (mid-face {_fmt(r['critical_section_mid_face_mpa'])}), fillet "
                     f"maximum away from contact peaks {_fmt(r['fillet_max_mpa'])} MPa")
    lines.append(f"- smooth contact peak of the loaded pairs {_fmt(s.get('contact_peak_mpa'))} MPa (largest pressure with "
                 f"edge and corner peaks {_fmt(s.get('max_contact_pressure_mpa'))} MPa)")
    for e in s.get("edge_peaks", []):
        lines.append(f"- flagged: {e['edge_kind']} of the {e['edge_of']}, pair {e['pair']}: {_fmt(e['edge_peak_mpa'])} MPa at "
                     + ", ".join(f"{x:.2f}" for x in e["edge_point_mm"]) + " mm")
    for p in s.get("fillet_peaks", []):
        lines.append(f"- flagged: {p['cause']} on {p['set']}: {_fmt(p['value_mpa'])} MPa at "
                     + ", ".join(f"{x:.2f}" for x in p["point_mm"]) + " mm")
    if s.get("rating"):
        from pipelines.report.rating import rating_markdown

        lines += ["", rating_markdown(s["rating"]).replace("# ISO 6336 rating", "## ISO 6336 rating", 1).rstrip()]
    lines += ["", "## Stage times [s]", "", "| stage | wall [s] |", "|---|---|"]
    for k, v in s["stages"].items():
        lines.append(f"| {k} | {v:.2f} |")
    lines += ["", f"Stress recovery: {s.get('stress_recovery', '')}.", f"Edge contact rule: {s.get('edge_contact_rule', '')}.",
              "", "## Images", ""]
    for f in s.get("images", []) + s.get("plots", []):
        lines.append(f"![{f}]({f})")
    path.write_text("\n".join(lines) + "\n")
    return path


def _say(progress):
    n = len(STAGES)

    def say(msg: str) -> None:
        if progress is not None:
            stage = msg.split(":", 1)[0]
            i = STAGES.index(stage) + 1 if stage in STAGES else 0
            progress(f"[{i}/{n}] {msg}" if i else msg)
    return say


def add_images(run: StressRun, out: Path, clim: dict | None = None, progress=None,
               top: float | None = None, show_edges: bool = False) -> StressRun:
    """Render the images of a computed run into ``out`` and rewrite its reports; the run with its updated summary.

    ``clim``: colour ranges of the zone images (:func:`zone_images`); ``top`` [MPa]: the top of the
    von Mises range of the design-review pictures (:func:`pipelines.report.figures.design_pictures`;
    default: clipped per run); ``show_edges``: element edges on the teeth views.
    """
    say = _say(progress)
    t1 = time.perf_counter()
    say("images: rendering off screen (pyvista)")
    summary = run.summary
    pics = design_pictures(run, Path(out), top=top, show_edges=show_edges)
    names, peaks = zone_images(summary, run.mesh, run.result, Path(out), clim, overview_range=pics.colour)
    flagged = peak_images(run, Path(out))
    names += [f for f, _ in flagged]
    for f in pics.files.values():
        names += list(f.values())
    dt = time.perf_counter() - t1
    say(f"images: {len(names)} images in {dt:.1f} s")
    interfaces = {itf: {**d, "members": {k: {**m, "max_von_mises_mpa": peaks[(itf, k)]} for k, m in d["members"].items()}}
                  for itf, d in summary["interfaces"].items()}
    c = pics.colour
    pictures = {"files": pics.files, "records": pics.records, "von_mises_range_mpa": [c.lo, c.hi], "von_mises_shown_max_mpa": c.max,
                "clipped": c.clipped, "clip_percentile": c.percentile}
    pictures["peaks"] = [{"file": f, "caption": c} for f, c in flagged]
    s = {**summary, "interfaces": interfaces, "images": names, "pictures": pictures, "files": [*summary["files"], *names]}
    s["stages"] = {**summary["stages"], "images": summary["stages"].get("images", 0.0) + dt}
    return replace(run, summary=_report(s, Path(out), say))


def _report(s: dict, out: Path, say) -> dict:
    t = time.perf_counter()
    write_report(s, out / "report.md")
    s["stages"]["report"] = time.perf_counter() - t
    s["total_s"] = sum(s["stages"].values())
    say("report: report.md written")
    return s


def run_pipeline(case: StressCase, out: Path, progress=None, clim: dict | None = None, images: bool = True,
                 show_edges: bool = False) -> StressRun:
    """Run a load case into ``out`` (module docstring); the summary (JSON-ready) and the objects behind it.

    ``show_edges`` draws the element edges on the teeth views. ``images=False`` skips the rendering (``add_images`` does it later, e.g. with a colour range
    common to several runs).
    """
    out = Path(out)
    say = _say(progress)
    run = run_stress(case, out, progress=say)
    s = run.summary
    stages = {k: s[f"{k}_s"] for k in ("tca", "mesh", "solve", "results")}
    t1 = time.perf_counter()
    from pipelines.render.plots import plot_contact_paths, plot_position_te

    plots = [plot_position_te(run.tca, math.radians(s["position"]["phi1_deg"]), out / "tca_te.png").name]
    if isinstance(run.tca, PairTCAResult):
        g = case.pair
        plots.append(plot_contact_paths(run.tca, out / "tca_paths.png", (g.gear1.name, g.gear2.name)).name)
    stages["images"] = time.perf_counter() - t1
    s = {**s, "images": [], "plots": plots, "files": ["result.vtu", "report.md", "summary.json", *plots], "stages": stages,
         "rating": plain(rating_record(rated_meshes(case)))}
    if images:
        return add_images(replace(run, summary=s), out, clim, progress, show_edges=show_edges)
    return replace(run, summary=_report(s, out, say))
