"""What two load cases share, compared (``gearfe compare`` of cases that are not Part 1's twin drive).

Part 1's finding (the new design shares the load between its members without edge contact, the conventional one
does not: :func:`pipelines.cli.compare.finding`) is stated only for two twin-drive cases. Other pairs of cases are
compared on the numbers both have: the headline stresses (smooth contact peak, largest pressure with edge peaks,
fillet maximum away from contact-induced peaks, the loaded teeth's bending stress at ISO's 30° section per gear),
the flagged peaks, the torque balance and, where both were rated, the safety factors.
"""

from __future__ import annotations

__all__ = ["shared_comparison", "SHARED_KEYS"]

SHARED_KEYS = ("contact_peak_mpa", "max_contact_pressure_mpa", "max_fillet_stress_mpa", "max_von_mises_mpa",
               "torque_balance_error")


def _ratio(a, b):
    return b / a if isinstance(a, (int, float)) and isinstance(b, (int, float)) and a else None


def shared_comparison(summaries: dict) -> dict:
    """{quantity: "value A | value B | B/A"} for the numbers both summaries have (module docstring)."""
    (la, a), (lb, b) = list(summaries.items())[:2]
    out: dict = {"compared": f"{la} against {lb}: the numbers both cases have (Part 1's finding applies to twin drives only)"}

    def put(name, x, y):
        if x is None or y is None:
            return
        r = _ratio(x, y)
        fx = f"{x:.4g}" if isinstance(x, float) else str(x)
        fy = f"{y:.4g}" if isinstance(y, float) else str(y)
        out[name] = f"{la} {fx} | {lb} {fy}" + (f" | ratio {r:.3f}" if r is not None else "")

    for k in SHARED_KEYS:
        put(k, a.get(k), b.get(k))
    for g in set(a.get("root_stress", {})) & set(b.get("root_stress", {})):
        put(f"{g}: FE bending at the 30° section [MPa]", a["root_stress"][g].get("critical_section_mpa"),
            b["root_stress"][g].get("critical_section_mpa"))
    put("flagged edge/corner peaks", len(a.get("edge_peaks", [])), len(b.get("edge_peaks", [])))
    put("contact-induced fillet peaks", len(a.get("fillet_peaks", [])), len(b.get("fillet_peaks", [])))
    ra, rb = (a.get("rating") or {}).get("gears", {}), (b.get("rating") or {}).get("gears", {})
    for g in set(ra) & set(rb):
        put(f"{g}: S_H (ISO)", ra[g]["safety_contact"], rb[g]["safety_contact"])
        put(f"{g}: S_F (ISO)", ra[g]["safety_bending"], rb[g]["safety_bending"])
    return out
