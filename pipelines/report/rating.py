"""The rating in reports: ``rating.md`` (``gearfe rate``) and the rating section of ``report.html``.

Both show per gear σ_H0, σ_H, σ_HP, S_H, σ_F0, σ_F, σ_FP, S_F (ISO's factors, and beside them the same with
gearfe's factors where the run computed them), the factors with their sources and notes, gearfe's factors beside
ISO's, the failed assumptions and the factors taken as 1 or simplified.
"""

from __future__ import annotations

from pipelines.render.html import section, table

__all__ = ["rating_rows", "factor_rows", "rating_markdown", "rating_html"]

_COLS = (("sigma_h0_mpa", "σ_H0 [MPa]"), ("sigma_h_mpa", "σ_H [MPa]"), ("sigma_hp_mpa", "σ_HP [MPa]"),
         ("safety_contact", "S_H"), ("sigma_f0_mpa", "σ_F0 [MPa]"), ("sigma_f_mpa", "σ_F [MPa]"),
         ("sigma_fp_mpa", "σ_FP [MPa]"), ("safety_bending", "S_F"))


def rating_rows(rec: dict) -> list[dict]:
    """One row per gear and way (ISO's factors; gearfe's factors where computed)."""
    rows = []
    ways = [("ISO", rec["gears"])] + ([("gearfe factors", rec["gearfe"]["gears"])] if rec.get("gearfe") else [])
    for way, gears in ways:
        for name, g in gears.items():
            row = {"gear": name, "factors": way, "mesh": g["mesh"]}
            row.update({label: g[k] for k, label in _COLS})
            rows.append(row)
    return rows


def factor_rows(rec: dict) -> list[dict]:
    """The factors of each gear (ISO's way) with source and note; pair factors once."""
    rows, seen = [], set()
    for name, g in rec["gears"].items():
        for k, f in g["factors"].items():
            shared = not k.startswith(("Z_NT", "Y_", "sigma_", "Z_B", "Z_D", "Z_W"))
            key = (g["mesh"], k) if shared else (name, k)
            if key in seen:
                continue
            seen.add(key)
            rows.append({"factor": k, "gear": "pair" if shared else name, "mesh": g["mesh"], "value": f["value"],
                         "source": f["source"], "note": f["note"]})
    return rows


def _compared(rec: dict) -> list[dict]:
    return [{"factor": k, "ISO": v["iso"], "gearfe": v["gearfe"], "gearfe from": v["gearfe_note"]}
            for k, v in rec.get("compared", {}).items()]


def _md_table(rows: list[dict]) -> list[str]:
    if not rows:
        return []
    keys = list(rows[0])
    out = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    for r in rows:
        out.append("| " + " | ".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in r.values()) + " |")
    return out


def rating_markdown(rec: dict, title: str = "") -> str:
    """``rating.md``: the tables of the module docstring."""
    lines = [f"# ISO 6336 rating{': ' + title if title else ''}", "", rec["standard"], ""]
    lines += _md_table(rating_rows(rec))
    if rec.get("compared"):
        lines += ["", "## gearfe's factors beside ISO's", ""] + _md_table(_compared(rec))
    lines += ["", "## Factors (ISO's way)", ""] + _md_table(factor_rows(rec))
    if rec.get("warnings"):
        lines += ["", "## Assumptions of ISO 6336 that fail", ""] + [f"- {w}" for w in rec["warnings"]]
    if rec.get("simplified"):
        lines += ["", "## Taken as 1 or simplified", ""] + [f"- {w}" for w in rec["simplified"]]
    return "\n".join(lines) + "\n"


def rating_html(rec: dict | None) -> str:
    """The rating section of ``report.html`` ('' without a rating)."""
    if not rec:
        return ""
    blocks = [f'<p class="note">{rec["standard"]}. S_H = σ_HG/σ_H, S_F = σ_FG/σ_F; σ_HP, σ_FP with S_min.</p>',
              table(rating_rows(rec))]
    if rec.get("compared"):
        blocks.append(section("gearfe's factors beside ISO's", table(_compared(rec)), level=3))
    if rec.get("warnings"):
        blocks.append("".join(f'<p class="warn">ISO assumption: {w}</p>' for w in rec["warnings"]))
    if rec.get("simplified"):
        blocks.append('<p class="note">Taken as 1 or simplified: ' + "; ".join(rec["simplified"]) + "</p>")
    blocks.append(f'<details><summary>All factors</summary>{table(factor_rows(rec))}</details>')
    return section("ISO 6336 rating", *blocks)
