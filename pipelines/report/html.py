"""``report.html``: one self-contained page per load case (``gearfe run``), per comparison (``gearfe compare``,
the designs side by side); the sweep's page is written by :func:`pipelines.render.sweep.plot_cycle`.

A page holds the case file, the position, the key results, per mesh the load share, the FE contact
patch against the TCA and Hertz ellipses (:func:`pipelines.report.figures.design_pictures`
records) and the root stresses, the stage times, and every picture of the run embedded as base64
(:mod:`pipelines.render.html`), so the one file can be mailed or archived on its own.
"""

from __future__ import annotations

from pathlib import Path

from pipelines.render.html import fmt, grid, image, pre, section, table, write_page
from pipelines.report.rating import rating_html

__all__ = ["KEY_RESULTS", "PICTURES", "run_html", "compare_html", "mesh_rows"]

KEY_RESULTS = ("max_von_mises_mpa", "max_von_mises_body", "max_contact_pressure_mpa", "contact_force_n", "contact_area_mm2",
               "max_fillet_stress_mpa", "max_fillet_von_mises_mpa", "max_fillet_set", "torque_balance_error",
               "torque_balance_error_kinematic", "reaction_torque_nm", "expected_reaction_torque_nm", "edge_contact",
               "fe_edge_contact", "dofs", "elements")

# picture kind -> caption (files from design_pictures; zone images from pipelines.report.run.zone_images)
PICTURES = {
    "teeth": "Three-tooth models: along the gear axis cut through the contact point, and the loaded flank along the contact "
             "normal; von Mises on a clipped range (values above it in magenta), the loaded pair marked.",
    "flank": "FE contact pressure on the loaded flank (axial position z, radius) against the TCA: path of contact, TCA "
             "ellipse (elastic approach) and Hertz ellipse under the FE force of the loaded pair; white: the FE patch.",
    "section": "Transverse section through the contact point: both loaded teeth with their fillets (clipped range) and the "
               "subsurface stress under the contact (full range), the depth 0.78 b of the Hertz maximum shear marked.",
    "root": "Largest principal stress along the fillets of the two loaded teeth over the face width.",
    "deformed": "Elastic displacements (rigid-body motion removed), scaled, over the undeformed outline of the cut.",
}


def mesh_rows(s: dict) -> list[dict]:
    """One row per interface member: load share, forces, FE patch vs TCA and Hertz, edge contact, root stress."""
    rows = []
    recs = s.get("pictures", {}).get("records", {})
    for itf, d in s["interfaces"].items():
        for mem, m in d["members"].items():
            r = recs.get(f"{itf}_{mem}", {})
            root = r.get("root_stress_mpa", {})
            rows.append({
                "mesh": f"{itf} {mem}", "load share": s["load_share"][itf]["members"][mem], "force [N]": m["force_n"],
                "peak pressure [MPa]": m["max_contact_pressure_mpa"], "Hertz p0 (FE force) [MPa]": r.get("hertz_p0_mpa"),
                "FE patch length [mm]": r.get("fe_patch_length_mm"), "Hertz 2a [mm]": r.get("hertz_length_mm"),
                "TCA ellipse 2a [mm]": r.get("tca_ellipse_length_mm"), "FE patch width [mm]": r.get("fe_patch_width_mm"),
                "Hertz 2b [mm]": r.get("hertz_width_mm"), "patch centre to TCA point [mm]": r.get("fe_patch_centre_offset_mm"),
                "max root stress [MPa]": max(root.values()) if root else None,
                "max von Mises on the flank [MPa]": m.get("max_von_mises_mpa"), "edge contact (FE)": m["edge_contact"],
                "TCA contact": m["tca_kind"]})
    return rows


def _position(s: dict) -> str:
    pos = s["position"]
    items = [f"φ1 = {pos['phi1_deg']:.6f} deg"]
    for k in ("te_arcsec", "te3_arcsec", "leading_member", "member_phase", "kind", "active_pair"):
        if k in pos:
            items.append(f"{k} = {fmt(pos[k])}")
    return "<p>" + "; ".join(items) + "</p>"


def _pictures(s: dict, folder: Path, prefix: str = "") -> list[str]:
    """Per mesh: the design-review pictures, then the zone images; then the overview and TCA plots."""
    blocks = []
    files = s.get("pictures", {}).get("files", {})
    for stem, f in files.items():
        inner = [image(folder / f[k], PICTURES[k], f"{prefix}{f[k]}") for k in PICTURES if k in f]
        for z, cap in ((f"zone_{stem}.png", "von Mises on the loaded flank (0 to the run's maximum)"),
                       (f"zone_{stem}_pressure.png", "contact pressure on the loaded flank")):
            inner.append(image(folder / z, cap))
        blocks.append(section(f"Mesh {stem.replace('_', ', member ')}", *inner, level=3))
    blocks.append(image(folder / "overview.png", "The whole model cut through the first mesh's contact point (clipped range)."))
    for p in s.get("plots", []):
        blocks.append(image(folder / p, {"tca_te.png": "TCA transmission error and the analysed position",
                                         "tca_paths.png": "TCA paths of contact and contact ellipses"}.get(p, p)))
    return blocks


def _results(s: dict) -> list[str]:
    key = [{"quantity": k, "value": s[k]} for k in KEY_RESULTS if k in s]
    out = [section("Key results", table(key)),
           section("Per mesh: load share, FE contact patch against TCA and Hertz, root stress", table(mesh_rows(s)),
                   '<p class="note">FE patch: nodes of the loaded flank above 1 % of its peak pressure, measured along the '
                   "TCA ellipse's major (length) and minor (width) axes. Hertz: elliptical contact under the FE force of the "
                   "loaded pair (Johnson, Contact Mechanics, eqs. 4.39-4.40).</p>")]
    pic = s.get("pictures", {})
    if pic:
        out.append(f'<p class="note">von Mises colour range of the pictures: {pic["von_mises_range_mpa"][0]:.0f} to '
                   f'{pic["von_mises_range_mpa"][1]:.0f} MPa'
                   + (f' (clipped; largest value shown {pic["von_mises_shown_max_mpa"]:.0f} MPa)' if pic["clipped"] else "")
                   + "</p>")
    if s.get("warnings"):
        out.append("".join(f'<p class="warn">warning: {fmt(w)}</p>' for w in s["warnings"]))
    return out


def _stages(s: dict) -> str:
    return section("Stage times", table([{"stage": k, "wall [s]": v} for k, v in s.get("stages", {}).items()]))


def run_html(s: dict, folder: Path, case_text: str = "", path: Path | None = None) -> Path:
    """``report.html`` of one load case in `folder` (its images are read from there and embedded)."""
    folder = Path(folder)
    title = s.get("title") or s["model"]
    head = (f"<p>Model <b>{fmt(s['model'])}</b>, torque {s['torque_nm']:g} N·m, case <code>{fmt(s.get('case', ''))}</code>, "
            f"{s.get('dofs', 0)} DOF.</p>" + _position(s))
    blocks = [head, *_results(s), rating_html(s.get("rating")), section("Pictures", *_pictures(s, folder)), _stages(s)]
    if case_text:
        blocks.append(section("Case file", pre(case_text)))
    blocks.append(f'<p class="note">Stress recovery: {fmt(s.get("stress_recovery", ""))}. '
                  f'Edge contact rule: {fmt(s.get("edge_contact_rule", ""))}.</p>')
    return write_page(path or folder / "report.html", title, *blocks)


def compare_html(summaries: dict, folders: dict, rows: list[dict], finding: dict, path: Path,
                 case_texts: dict | None = None, images: list | None = None) -> Path:
    """``report.html`` of ``gearfe compare``: the table, the finding, and every picture side by side per design."""
    labels = list(summaries)
    blocks = [table(rows), section("Finding", table([{"check": k, "value": v} for k, v in finding.items()]))]
    for p, cap in images or []:
        blocks.append(image(p, cap))
    blocks.append(section("Per design", grid([f"<h3>{fmt(k)}</h3>" + _position(summaries[k]) + "".join(_results(summaries[k]))
                                              for k in labels])))
    stems = [list(summaries[k].get("pictures", {}).get("files", {})) for k in labels]
    for stem in stems[0]:
        for kind, cap in PICTURES.items():
            cells = []
            for k in labels:
                f = summaries[k].get("pictures", {}).get("files", {}).get(stem, {}).get(kind)
                cells.append(f"<h3>{fmt(k)}</h3>" + (image(Path(folders[k]) / f, cap) if f else "<p>-</p>"))
            blocks.append(section(f"{stem.replace('_', ', member ')}: {kind}", grid(cells), level=3))
    blocks.append(section("Overview", grid([f"<h3>{fmt(k)}</h3>" + image(Path(folders[k]) / "overview.png") for k in labels])))
    if case_texts:
        blocks.append(section("Case files", grid([f"<h3>{fmt(k)}</h3>" + pre(case_texts.get(k, "")) for k in labels])))
    return write_page(path, "Design comparison: " + " vs ".join(labels), *blocks)
