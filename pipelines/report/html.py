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

KEY_RESULTS = ("max_von_mises_mpa", "max_von_mises_body", "contact_peak_mpa", "max_contact_pressure_mpa", "contact_force_n",
               "contact_area_mm2", "max_fillet_stress_mpa", "max_fillet_set", "max_fillet_stress_raw_mpa",
               "max_fillet_von_mises_mpa", "torque_balance_error", "torque_balance_error_kinematic", "reaction_torque_nm",
               "expected_reaction_torque_nm", "edge_contact", "fe_edge_contact", "dofs", "elements")

MEANING = {
    "contact_peak_mpa": "largest smooth contact peak of a loaded tooth pair (edge and corner peaks apart)",
    "max_contact_pressure_mpa": "largest nodal contact pressure anywhere, edge and corner peaks included",
    "max_fillet_stress_mpa": "largest principal stress on the fillets away from contact-induced local peaks",
    "max_fillet_stress_raw_mpa": "largest principal stress on the fillets, contact-induced peaks included",
    "max_von_mises_mpa": "largest von Mises stress anywhere (contact zones included)",
}

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


def iso_rows(s: dict) -> list[dict]:
    """Per gear: the FE bending stress of the loaded tooth at ISO's 30° section and its fillet maximum beside σ_F0."""
    rows = []
    iso = s.get("iso6336_sigma_f0_mpa") or {}
    for key, g in s.get("root_stress", {}).items():
        f0 = iso.get(g["gear"])
        rows.append({"gear": key, "loaded tooth": g.get("tooth"), "its share": g.get("load_share"),
                     "FE at the 30° section, max over the face [MPa]": g.get("critical_section_mpa"),
                     "FE at the 30° section, mid-face [MPa]": g.get("critical_section_mid_face_mpa"),
                     "FE fillet max, away from contact peaks [MPa]": g.get("fillet_max_mpa"),
                     "ISO σ_F0, whole load [MPa]": f0, "ISO σ_F0 × share [MPa]":
                         None if f0 is None or g.get("load_share") is None else f0 * g["load_share"]})
    return rows


def pair_rows(s: dict) -> list[dict]:
    """Per tooth pair: offset, load share, force, smooth contact peak, edge/corner peak and where."""
    peaks = {c["pair"]: c for c in s.get("contact_peaks", [])}
    rows = []
    for itf, d in s["interfaces"].items():
        for name, t in d.get("teeth", {}).items():
            c = peaks.get(f"{itf}/{name}", {})
            where = (f"{c['edge_kind']} of the {c['edge_of']}" if c.get("edge_kind") else "-")
            rows.append({"mesh": itf, "tooth pair": name, "offset": t.get("offset"),
                         "load share": s["load_share"][itf]["teeth"].get(name), "force [N]": t["force_n"],
                         "smooth peak [MPa]": c.get("smooth_peak_mpa"), "edge/corner peak [MPa]": c.get("edge_peak_mpa"),
                         "edge/corner": where, "flagged": c.get("edge_flagged")})
    return rows


def _contact_iso(s: dict) -> str:
    c = (s.get("iso6336") or {}).get("contact") or {}
    if "sigma_h0" not in c:
        return ""
    return (f'<p class="note">ISO 6336-2 nominal contact stress (no load factors) under the whole load: σ_H0 = '
            f'{c["sigma_h0"]:.1f} MPa at the pitch point (Z_ε = {c["z_eps"]:.4f}, ISO\'s allowance for sharing); one pair '
            f'carrying the whole load: σ_H0·Z_B/Z_ε = {c["at_inner_point_pinion"]:.1f} MPa at the {c["pinion"]}\'s inner '
            f'point of single contact (Z_B = {c["z_b"]:.4f}), σ_H0·Z_D/Z_ε = {c["at_inner_point_wheel"]:.1f} MPa at the '
            f'{c["wheel"]}\'s (Z_D = {c["z_d"]:.4f}). FE smooth peak of the loaded pairs: '
            f'{fmt(s.get("contact_peak_mpa"))} MPa.</p>')


def _flagged(s: dict, folder: Path) -> list[str]:
    rows = [{"peak": f"{e['edge_kind']} of the {e['edge_of']}", "pair": e["pair"], "value [MPa]": e["edge_peak_mpa"],
             "smooth peak of the pair [MPa]": e["smooth_peak_mpa"],
             "at [mm]": ", ".join(f"{x:.2f}" for x in e["edge_point_mm"])} for e in s.get("edge_peaks", [])]
    rows += [{"peak": p["cause"], "pair": p["set"], "value [MPa]": p["value_mpa"],
              "smooth peak of the pair [MPa]": p["clear_max_mpa"],
              "at [mm]": ", ".join(f"{x:.2f}" for x in p["point_mm"])} for p in s.get("fillet_peaks", [])]
    if not rows:
        return [section("Flagged peaks", '<p class="note">none: no edge or corner contact peak above its pair\'s smooth '
                        "peak, no contact-induced fillet peak.</p>")]
    imgs = [image(folder / p["file"], p["caption"]) for p in s.get("pictures", {}).get("peaks", [])]
    return [section("Flagged peaks (reported apart from the headline numbers)", table(rows),
                    grid(imgs, 2) if imgs else "")]


def _results(s: dict, folder: Path | None = None) -> list[str]:
    key = [{"quantity": k, "value": s[k], "meaning": MEANING.get(k, "")} for k in KEY_RESULTS if k in s]
    out = [section("Key results", table(key))]
    if s.get("root_stress"):
        out.append(section("FE beside ISO 6336: root stress of the loaded teeth", table(iso_rows(s)),
                           '<p class="note">ISO 6336-3 method B σ_F0: the whole load on one tooth at its outer point of '
                           "single contact, no load factors; the FE: the loaded tooth at the analysed position, carrying "
                           "its share.</p>"))
    out.append(section("Load per pair of teeth and contact peaks", table(pair_rows(s)), _contact_iso(s)))
    if folder is not None:
        out += _flagged(s, folder)
    out += [
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
    blocks = [head, *_results(s, folder), rating_html(s.get("rating")), section("Pictures", *_pictures(s, folder)), _stages(s)]
    if case_text:
        blocks.append(section("Case file", pre(case_text)))
    blocks.append(f'<p class="note">Stress recovery: {fmt(s.get("stress_recovery", ""))}. '
                  f'Edge contact rule: {fmt(s.get("edge_contact_rule", ""))}.</p>')
    return write_page(path or folder / "report.html", title, *blocks)


def compare_html(summaries: dict, folders: dict, rows: list[dict], finding: dict, path: Path,
                 case_texts: dict | None = None, images: list | None = None) -> Path:
    """``report.html`` of ``gearfe compare``: the table, the finding, and every picture side by side per design."""
    labels = list(summaries)
    head = ("Finding (Part 1, Numerical Example 1.3: the twin drives)" if "reproduced" in finding
            else "What the two cases share")
    keys = list(dict.fromkeys(k for r in rows for k in r))
    blocks = [table(rows, headers={k: k.replace("_", " ") for k in keys}),
              section(head, table([{"check": k, "value": v} for k, v in finding.items()]))]
    for p, cap in images or []:
        blocks.append(image(p, cap))
    for k in labels:  # one design after the other: their tables are too wide to stand side by side at 1400 px
        blocks.append(section(f"Design: {k}", _position(summaries[k]), *_results(summaries[k], Path(folders[k])),
                              rating_html(summaries[k].get("rating"))))
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
