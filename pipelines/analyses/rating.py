"""The ISO 6336 rating of a case, ISO alone and with the load factors gearfe computes (the ``rating`` key of
``summary.json``).

``rating_record(meshes, analysis)`` rates every mesh of a case (:func:`pipelines.cases.rating.rated_meshes`) by
ISO 6336 method B (:func:`tca.rating.rate`) and, where ``analysis`` gives gearfe's own factors for a mesh
(:class:`tca.rating.analysis.AnalysisFactors`: K_Hβ and K_Hα from the loaded TCA, K_γ from a loaded train),
rates it again with them. The record (JSON-ready)::

    rating = {
      "standard": "ISO 6336-1/-2/-3/-5:2006 method B (tca.rating)",
      "gears": {<gear>: {"role", "mesh", "sigma_h0_mpa", "sigma_h_mpa", "sigma_f0_mpa", "sigma_f_mpa",
                         "safety_contact", "safety_bending", "sigma_hp_mpa", "sigma_fp_mpa", "sigma_hg_mpa",
                         "sigma_fg_mpa", "min_safety_contact", "min_safety_bending", "load_cycles",
                         "factors": {<name>: {"value", "source" ("iso" | "gearfe" | "input"), "note"}}}},
      "gearfe": {"gears": {...the same with gearfe's factors...}} or null,
      "compared": {<factor>: {"iso", "gearfe", "note"}},     # each of gearfe's factors beside ISO's
      "meshes": {<mesh>: {"pinion", "wheel", "gears", "gearfe", "pair": {F_t, v, ε_α, ε_β, ...}, "warnings"}},
      "warnings": [...],                                     # failed assumptions of ISO 6336 (code: message)
      "simplified": [...],                                   # factors taken as 1 or simplified, with their notes
    }

``gears`` holds, per gear, the mesh with its lowest safety (a planet meshes with the sun and the ring).
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

from tca.rating.analysis import (AnalysisFactors, face_load_from_slices, transverse_from_shares,
                                 with_analysis)
from tca.rating.factors import Given, Source
from tca.rating.rating import GearRating, PairRating, rate

from pipelines.cases.rating import MeshRating

__all__ = ["STANDARD", "rating_record", "gear_record", "ltca_factors", "SIMPLIFIED_MARKS", "print_rating",
           "ltca_rating"]

STANDARD = "ISO 6336-1/-2/-3/-5 method B (2006 formulas, tca.rating; docs/rating.md)"
SIMPLIFIED_MARKS = ("taken as 1", "simplified", "hardness-only", "solid gear", "no rim thickness")
COMPARED = {"k_h_beta": "K_Hbeta", "k_h_alpha": "K_Halpha", "k_gamma": "K_gamma"}


def gear_record(g: GearRating, role: str, mesh: str, case) -> dict:
    """One gear's stresses, safeties and factors (module docstring)."""
    return {"role": role, "mesh": mesh, "sigma_h0_mpa": g.sigma_h0, "sigma_h_mpa": g.sigma_h, "sigma_f0_mpa": g.sigma_f0,
            "sigma_f_mpa": g.sigma_f, "safety_contact": g.s_h, "safety_bending": g.s_f, "sigma_hp_mpa": g.sigma_hp,
            "sigma_fp_mpa": g.sigma_fp, "sigma_hg_mpa": g.sigma_hg, "sigma_fg_mpa": g.sigma_fg,
            "min_safety_contact": case.min_safety_contact, "min_safety_bending": case.min_safety_bending,
            "load_cycles": g.load_cycles,
            "factors": {k: {"value": f.value, "source": f.source.value, "note": f.note} for k, f in g.factors.items()}}


def _gears(r: PairRating, m: MeshRating, case) -> dict:
    return {m.rated.pinion: gear_record(r.pinion, "pinion", m.label, case),
            m.rated.wheel: gear_record(r.wheel, "wheel", m.label, case)}


def _pair(r: PairRating) -> dict:
    g = r.geometry
    return {"tangential_force_n": r.tangential_force, "circumferential_speed_m_s": r.circumferential_speed,
            "eps_alpha": g.eps_alpha, "eps_beta": g.eps_beta, "centre_distance_mm": g.centre_distance,
            "working_pressure_angle_deg": math.degrees(g.working_pressure_angle), "face_width_mm": g.common_face_width,
            "pinion_torque_nm": r.tangential_force * g.reference_diameter[0] / 2e3}


def _worst(per_mesh: list[dict]) -> dict:
    """Per gear, the record of the mesh with its lowest safety (contact or bending)."""
    out: dict = {}
    for gears in per_mesh:
        for name, rec in gears.items():
            old = out.get(name)
            if old is None or min(rec["safety_contact"], rec["safety_bending"]) < \
                    min(old["safety_contact"], old["safety_bending"]):
                out[name] = rec
    return out


def rating_record(meshes: list[MeshRating], analysis: Mapping[str, AnalysisFactors] | None = None,
                  details: Mapping[str, dict] | None = None) -> dict | None:
    """The ``rating`` record of a case (module docstring); None when the case has no ``[rating]``.

    ``analysis``: gearfe's factors per mesh label; ``details``: what they were computed from, per mesh (shown).
    """
    if not meshes:
        return None
    analysis, details = analysis or {}, details or {}
    per, per_g, warnings, simplified, compared = {}, [], [], [], {}
    gearfe_any = []
    for m in meshes:
        case = m.rated.case
        iso = rate(case)
        rec = {"pinion": m.rated.pinion, "wheel": m.rated.wheel, "gears": _gears(iso, m, case), "pair": _pair(iso),
               "warnings": [str(w) for w in (*m.rated.warnings, *iso.warnings)], "gearfe": None}
        a = analysis.get(m.label)
        if a is not None and a.items():
            both = rate(with_analysis(case, a))
            rec["gearfe"] = {"gears": _gears(both, m, case), "details": details.get(m.label, {})}
            gearfe_any.append(rec["gearfe"]["gears"])
            for key, given in a.items():
                name = COMPARED[key]
                compared[f"{name} ({m.label})" if len(meshes) > 1 else name] = {
                    "iso": iso.factors[name].value, "gearfe": given.value, "iso_note": iso.factors[name].note,
                    "gearfe_note": given.note}
        per[m.label] = rec
        per_g.append(rec["gears"])
        warnings += [f"{m.label}: {w}" if len(meshes) > 1 else w for w in rec["warnings"]]
        for g in (iso.pinion, iso.wheel):
            for k, f in g.factors.items():
                line = f"{k}: {f.note}"
                if any(s in f.note for s in SIMPLIFIED_MARKS) and line not in simplified:
                    simplified.append(line)
    return {"standard": STANDARD, "gears": _worst(per_g), "gearfe": {"gears": _worst(gearfe_any)} if gearfe_any else None,
            "compared": compared, "meshes": per, "warnings": list(dict.fromkeys(warnings)), "simplified": simplified}


def _table(rows: list[dict], key: str) -> np.ndarray:
    return np.array([[r.get(f"{key}.{n}") or 0.0 for n in _pairs(rows)] for r in rows], float)


def _pairs(rows: list[dict]) -> list[str]:
    names: list[str] = []
    for r in rows:
        names += [k.split(".", 1)[1] for k in r if k.startswith("share.") and k.split(".", 1)[1] not in names]
    return names


def _extents(ps: list[dict]) -> np.ndarray:
    """Half the axial length each slice covers [mm]: half the median axial spacing of its contact line's slices."""
    z = np.array([p["z_mm"] for p in ps], float)
    key = [(p["phi1_deg"], p["pair"]) for p in ps]
    groups: dict = {}
    for i, k in enumerate(key):
        groups.setdefault(k, []).append(i)
    steps = {k: float(np.median(np.diff(np.sort(z[idx])))) for k, idx in groups.items() if len(idx) > 1}
    typical = float(np.median(list(steps.values()))) if steps else 1.0
    out = np.empty(len(ps))
    for k, idx in groups.items():
        out[idx] = 0.5 * (steps.get(k) or typical)
    return out


def ltca_factors(rows: list[dict], prows: list[dict], torque_nm: float, face_width: float,
                 bins: int) -> tuple[AnalysisFactors, dict]:
    """K_Hβ (A1) and K_Hα (A2) of :mod:`tca.rating.analysis` from ``gearfe ltca``'s rows at one torque [N m].

    ``rows``/``prows``: the records of results.csv and pressure.csv; ``face_width`` [mm] the common face width;
    ``bins`` the number of face bins (the flank grid's axial cells). Returns the factors and what they rest on.
    """
    rs = [r for r in rows if abs(r["torque_nm"] - torque_nm) <= 1e-9 * torque_nm]
    ps = [p for p in prows if abs(p["torque_nm"] - torque_nm) <= 1e-9 * torque_nm]
    fl = face_load_from_slices(np.array([p["phi1_deg"] for p in ps]), np.array([p["z_mm"] for p in ps]),
                               np.array([p["force_n"] for p in ps]), face_width, bins, _extents(ps))
    tr = transverse_from_shares(_table(rs, "share"), _table(rs, "length_mm"))
    note_b = (f"loaded TCA: cycle-mean load per unit face width, max/mean over {bins} face bins, {fl.positions} "
              f"positions at {torque_nm:g} N m (A1); largest instantaneous {fl.instantaneous:.3f}")
    note_a = (f"loaded TCA: largest load per unit contact length of a tooth pair over that of length-proportional "
              f"sharing, {tr.positions} positions (A2)" + (f"; unlimited {tr.unlimited:.4f}, limited to 1"
                                                            if tr.unlimited < 1 else ""))
    f = AnalysisFactors(k_h_beta=Given(fl.k_h_beta, Source.GEARFE, note_b),
                        k_h_alpha=Given(tr.k_h_alpha, Source.GEARFE, note_a))
    det = {"torque_nm": torque_nm, "face_bins": bins, "positions": fl.positions,
           "line_load_z_mm": fl.z.tolist(), "line_load_n_per_mm": fl.line_load.tolist(),
           "k_h_beta_instantaneous": fl.instantaneous, "k_h_alpha_unlimited": tr.unlimited}
    return f, det


def print_rating(rec: dict, say=print) -> None:
    """A short table of the rating on the terminal."""
    if not rec:
        return
    both = rec.get("gearfe")
    head = f"  {'gear':<10} {'sigma_H0':>9} {'sigma_H':>9} {'S_H':>6} {'sigma_F0':>9} {'sigma_F':>9} {'S_F':>6}"
    say(head + ("   (gearfe factors: S_H, S_F)" if both else ""))
    for name, g in rec["gears"].items():
        line = (f"  {name:<10} {g['sigma_h0_mpa']:9.1f} {g['sigma_h_mpa']:9.1f} {g['safety_contact']:6.3f} "
                f"{g['sigma_f0_mpa']:9.1f} {g['sigma_f_mpa']:9.1f} {g['safety_bending']:6.3f}")
        if both and name in both["gears"]:
            o = both["gears"][name]
            line += f"   {o['safety_contact']:6.3f} {o['safety_bending']:6.3f}"
        say(line)
    for k, v in rec.get("compared", {}).items():
        say(f"  {k}: ISO {v['iso']:.4f}, gearfe {v['gearfe']:.4f}")
    for w in rec.get("warnings", []):
        say(f"  warning: {w}")


def _read_csv(path) -> list[dict]:
    import csv

    with open(path, newline="") as fh:
        return [{k: (float(v) if v not in ("", None) and k != "pair" else (v or None)) for k, v in r.items()}
                for r in csv.DictReader(fh)]


def ltca_rating(case, summary: dict, folder) -> dict | None:
    """The ``rating`` of a ``gearfe ltca`` run: ISO's factors, and K_Hβ, K_Hα of the loaded TCA at the case's
    torque (from ``folder``'s results.csv and pressure.csv); None without ``[rating]``."""
    from pathlib import Path

    from pipelines.cases.rating import rated_meshes

    meshes = rated_meshes(case)
    if not meshes:
        return None
    folder = Path(folder)
    b = min(case.pair.gear1.face_width, case.pair.gear2.face_width)
    bins = max(2, int(round(b / summary["flank_grid_mm"]["axial"])))
    f, det = ltca_factors(_read_csv(folder / "results.csv"), _read_csv(folder / "pressure.csv"), case.torque * 1e-3,
                          b, bins)
    return rating_record(meshes, {"pair": f}, {"pair": det})
