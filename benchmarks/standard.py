"""Standard gears benchmark: the aligned spur pair (pipelines/cases/stress_spur_pair.toml) end to end.

1. Three-tooth model at the pitch point, default accuracy: wall time (goal <= 30 s) and the Hertz
   line-contact check (nodal peak in the middle half of the face against p0 = sqrt(w E* / (pi rho))).
2. ISO 6336-3 method B: fillet maximum principal stress of each gear with the whole load at its own
   HPSTC (one tooth per gear; the wheel's HPSTC is the pinion's LPSTC) against sigma_F0.
3. One mesh cycle of the unmodified pair (three teeth, ``--positions`` angles): load share per pair of
   teeth (two pairs in the double-contact zones, one at the pitch point) and the loaded TE.
4. The helical pair (pipelines/cases/stress_helical_pair.toml) as shipped: time, force balance and the
   load shared by the pairs of teeth on their inclined contact lines.
5. ISO 6336-3 for an internal pair (pipelines/cases/stress_internal_pair.toml, 24/72, one tooth per gear):
   the ring's fillet maximum principal stress at its HPSTC (the pinion's LPSTC) at refine 0.5, 1, 2 with
   Richardson's extrapolation, against the substitute-rack sigma_F0; the pinion's at its own HPSTC.

Run: ``.venv/bin/python -m benchmarks.standard --out out/bench/standard``.
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from tca.rating.root_stress import root_factors, tooth_root
from tca.pair.te import path_of_contact

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress
from pipelines.models.stress.results import loaded_te

__all__ = ["main"]

CASE = CASES_DIR / "stress_spur_pair.toml"


def _case(**kw):
    c = read_stress_case(load_case(CASE))
    mesh = {k: kw.pop(k) for k in ("teeth", "refine", "contact") if k in kw}
    return replace(c, mesh=replace(c.mesh, **mesh), **kw)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True)
    ap.add_argument("--positions", type=int, default=12)
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    L = ["# Standard gears: aligned spur pair 19/24, m 4.5 mm, b 14 mm, T2 = 120 N m", ""]
    # 1. speed and Hertz
    c = _case(position="pitch")
    art: dict = {}
    t0 = time.perf_counter()
    run = run_stress(c, out / "pitch")
    s, art = run.summary, {"result": run.result, "mesh": run.mesh}
    wall = time.perf_counter() - t0
    g1, g2 = c.pair.gear1, c.pair.gear2
    al = path_of_contact(c.pair).alpha_wt
    rho = 1.0 / (1.0 / (g1.r_b * math.tan(al)) + 1.0 / (g2.r_b * math.tan(al)))
    w = c.torque / g2.r_b / g1.face_width
    p0 = math.sqrt(w * c.fe.material.E / (2 * (1 - c.fe.material.nu ** 2)) / (math.pi * rho))
    p = np.nan_to_num(art["result"].contact_pressure)
    mid = (p > 0) & (np.abs(art["mesh"].points[:, 2]) <= 0.25 * g1.face_width)
    L += ["## 1. Three-tooth model at the pitch point (default accuracy)", "",
          f"- wall time end to end {wall:.1f} s (goal <= 30 s); {s['dofs']} DOF; tca {s['tca_s']:.1f} s, mesh {s['mesh_s']:.1f} s, "
          f"solve {s['solve_s']:.1f} s",
          f"- peak pressure, middle half of the face: {p[mid].max():.1f} MPa against Hertz p0 = {p0:.1f} MPa "
          f"({p[mid].max() / p0 - 1:+.1%}); whole face (ends included) {s['max_contact_pressure_mpa']:.1f} MPa",
          f"- total normal force {s['contact_force_n']:.1f} N against T2/r_b2 = {c.torque / g2.r_b:.1f} N", ""]
    # 2. ISO 6336-3
    L += ["## 2. Root stress against ISO 6336-3 method B (one tooth per gear, load at each gear's HPSTC)", "",
          "| gear | position | FE max principal [MPa] | sigma_F0 [MPa] | FE / ISO - 1 | Y_F | Y_S |", "|---|---|---|---|---|---|---|"]
    eps = path_of_contact(c.pair).contact_ratio
    for gear, pos, fset, torque in ((g1, "hpstc", "pinion/tooth0/fillet_pos", c.torque * g1.teeth / g2.teeth),
                                    (g2, "lpstc", "wheel/tooth0/fillet_neg", c.torque)):
        run = run_stress(_case(position=pos, teeth=1, contact=0.2), out / pos)
        s = run.summary
        fe = run.result.fillet_stress()[fset]["max_principal_mpa"]
        rf = root_factors(gear, eps)
        sig = torque / gear.r_p / (gear.face_width * gear.module) * rf.y_f * rf.y_s
        L.append(f"| {gear.name} | {pos} | {fe:.1f} | {sig:.1f} | {fe / sig - 1:+.1%} | {rf.y_f:.3f} | {rf.y_s:.3f} |")
    # 3. a mesh cycle
    path = path_of_contact(c.pair)
    L += ["", f"## 3. One mesh cycle, three teeth, refine 0.5 (eps_alpha = {eps:.3f})", "",
          "| roll [deg] | phi1 [deg] | zone (TCA) | load shares (pairs -1, 0, +1) | loaded TE [arcsec] |", "|---|---|---|---|---|"]
    for t in np.linspace(path.t_c - 0.5 * path.p_bt, path.t_c + 0.5 * path.p_bt, a.positions, endpoint=False):
        cc = _case(roll=t / path.r_b1, position="max_te", refine=0.5)
        s = run_stress(cc, out / "cycle").summary
        sh = s["load_share"]["pinion-wheel"]["teeth"]
        off = {n: d["offset"] for n, d in s["interfaces"]["pinion-wheel"]["teeth"].items()}
        zone = "single" if path.t_b < t < path.t_d else "double"
        lt = loaded_te(cc, s)
        L.append(f"| {math.degrees(t / path.r_b1):.3f} | {s['position']['phi1_deg']:.3f} | {zone} | "
                 + ", ".join(f"{v:.3f}" for _, v in sorted((off[n], v) for n, v in sh.items())) + f" | {lt['loaded_te_arcsec']:.2f} |")
    # 4. the helical pair as shipped
    hc = read_stress_case(load_case(CASES_DIR / "stress_helical_pair.toml"))
    t0 = time.perf_counter()
    s = run_stress(hc, out / "helical").summary
    g = hc.pair.gear2
    beta_b = math.atan(math.tan(g.helix) * g.r_b / g.r_p)
    off = {n: d["offset"] for n, d in s["interfaces"]["sun-planet"]["teeth"].items()}
    sh = sorted((off[n], v) for n, v in s["load_share"]["sun-planet"]["teeth"].items())
    L += ["", "## 4. Helical pair as shipped (stress_helical_pair.toml, pitch point)", "",
          f"- wall time {time.perf_counter() - t0:.1f} s, {s['dofs']} DOF",
          f"- total normal force {s['contact_force_n']:.1f} N against T2 / (r_b2 cos β_b) = {hc.torque / g.r_b / math.cos(beta_b):.1f} N",
          "- load shares by pair offset: " + ", ".join(f"{q:+d}: {v:.3f}" for q, v in sh),
          f"- peak contact pressure {s['max_contact_pressure_mpa']:.0f} MPa (FE edge contact: {s['fe_edge_contact']})"]
    L += _internal(out)
    (out / "standard.md").write_text("\n".join(L) + "\n")
    print("\n".join(L))
    return 0


def _internal(out: Path) -> list[str]:
    """Section 5: the internal pair's root stresses against ISO 6336-3 (substitute rack for the ring)."""
    base = read_stress_case(load_case(CASES_DIR / "stress_internal_pair.toml"))
    pinion, ring = base.pair.gear1, base.pair.gear2
    eps = path_of_contact(base.pair).contact_ratio
    L = ["", f"## 5. Internal pair 24/72 (stress_internal_pair.toml), one tooth per gear, eps_alpha = {eps:.3f}", "",
         "| gear | position | refine | DOF | FE max principal [MPa] | sigma_F0 [MPa] | FE / ISO - 1 |", "|---|---|---|---|---|---|---|"]
    rows = []
    for gear, pos, fset, refine in [(ring, "lpstc", "ring/tooth0/fillet_neg", r) for r in (0.5, 1.0, 2.0)] + \
                                    [(pinion, "hpstc", "pinion/tooth0/fillet_pos", 1.0)]:
        c = replace(base, position=pos, mesh=replace(base.mesh, teeth=1, refine=refine))
        run = run_stress(c, out / f"internal_{pos}_{refine:g}")
        fe = run.result.fillet_stress()[fset]["max_principal_mpa"]
        sig = run.summary["iso6336_sigma_f0_mpa"][gear.name]
        rows.append(fe)
        L.append(f"| {gear.name} | {pos} | {refine:g} | {run.summary['dofs']} | {fe:.1f} | {sig:.1f} | {fe / sig - 1:+.1%} |")
    f1, f2, f3 = rows[:3]
    sig_ring = tooth_root(base.pair, base.torque)[ring.name]["sigma_f0_mpa"]
    if (f2 - f1) * (f3 - f2) > 0 and abs(f3 - f2) < abs(f2 - f1):
        q = (f2 - f1) / (f3 - f2)
        rich = f3 + (f3 - f2) / (q - 1)
        L += ["", f"- ring, Richardson (refinement ratio 2, observed order {math.log2(q):.2f}): {rich:.1f} MPa, "
                  f"{rich / sig_ring - 1:+.1%} against sigma_F0 = {sig_ring:.1f} MPa"]
    else:
        L += ["", "- ring: the three levels are not monotonically convergent; no extrapolation"]
    return L


if __name__ == "__main__":
    raise SystemExit(main())
