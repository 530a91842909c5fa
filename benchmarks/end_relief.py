"""End relief benchmark: the TCA of a misaligned spur pair and the stress of the aligned pair, with and without.

1. TCA, the 19/24 spur pair of pipelines/cases/stress_spur_pair.toml with Δγ = 3' and 10': TE and
   axial position of the contact without relief (edge contact at the face end), with a linear relief
   (15 um over 4 mm: the ridge z_s = 3 mm touches, checked against the same pair cut to b = 6 mm) and
   with a parabolic one (a point of tangency in the relieved zone, against the closed form
   z* = z_s + a r_b2 L² / (4 C_I), a the TE per mm of axial position of the cut pair).
2. Stress, default accuracy (three teeth, refine 1): pipelines/cases/stress_spur_pair.toml,
   stress_spur_pair_end_relief.toml (linear, 15 um over 3 mm) and the same with a parabolic relief:
   contact pressure at the face-end nodes, the peak in the middle half of the face, the peak anywhere,
   the axial pressure profile (largest nodal pressure per axial level), fe_edge_contact, force.

Run: ``.venv/bin/python -m benchmarks.end_relief --out out/bench/end_relief``.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from tca.geometry.modifications.end_relief import EndRelief
from tca.pair.gear_pair import GearPair, Misalignment
from tca.pair.analysis import TCAOptions, run_pair_tca
from tca.units import ARCMIN, ARCSEC

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress

__all__ = ["main"]


def _tca_section(lines: list[str]) -> None:
    base = read_stress_case(load_case(CASES_DIR / "stress_spur_pair.toml")).pair
    opts = TCAOptions(cycles=1, steps_per_cycle=20)
    lines += ["## 1. TCA of the misaligned spur pair", "",
              "| Δγ | flanks | TE [arcsec] | contact z on the pinion [mm] | check | time [s] |", "|---|---|---|---|---|---|"]
    for dg in (3.0, 10.0):
        mis = Misalignment(d_gamma=dg * ARCMIN)

        def run(relief=None, face=14.0):
            g1, g2 = (replace(g, face_width=face, end_relief=relief) for g in (base.gear1, base.gear2))
            t0 = time.perf_counter()
            r = run_pair_tca(GearPair(g1, g2, misalignment=mis), opts)
            return r, time.perf_counter() - t0

        cut, _ = run(face=6.0)
        a = cut.te / 3.0
        for label, rel in (("unmodified", None), ("linear 15 um / 4 mm", EndRelief(0.015, 4.0, 1)),
                           ("parabolic 15 um / 4 mm", EndRelief(0.015, 4.0, 2))):
            r, dt = run(rel)
            z = np.abs(r.point1[:, 2])
            if rel is None:
                check = "edge contact at the face end" if np.allclose(z, 7.0, atol=0.02) else "-"
            elif rel.power == 1:
                check = f"max |TE - TE(cut pair, b = 6 mm)| = {np.abs(r.te - cut.te).max() / ARCSEC:.1e} arcsec"
            else:
                zs = 3.0 + a * base.gear2.r_b * 16.0 / (4 * 0.015)
                te = a * zs - 2 * 0.015 * ((zs - 3.0) / 4.0) ** 2 / base.gear2.r_b
                check = (f"z* closed form {zs.min():.3f}..{zs.max():.3f} mm, max TE error "
                         f"{np.abs(r.te / te - 1).max() * 100:.3f} %")
            lines.append(f"| {dg:g}' | {label} | {r.te.min() / ARCSEC:.3f} .. {r.te.max() / ARCSEC:.3f} | "
                         f"{z.min():.3f} .. {z.max():.3f} | {check} | {dt:.1f} |")
    lines.append("")


def _stress_section(out: Path, lines: list[str]) -> None:
    lines += ["## 2. Stress of the aligned spur pair at the pitch point (three teeth, refine 1)", "",
              "| case | DOF | face ends [MPa] | middle half peak [MPa] | peak [MPa] | fe_edge_contact | force [N] | "
              "fillet [MPa] | time [s] |", "|---|---|---|---|---|---|---|---|---|"]
    src = CASES_DIR / "stress_spur_pair_end_relief.toml"
    linear = read_stress_case(load_case(src))
    parab_case = out / "stress_spur_pair_end_relief_parabolic.toml"  # the shipped case, shape = "parabolic"
    parab_case.write_text(src.read_text().replace('shape = "linear"', 'shape = "parabolic"'))
    parab = read_stress_case(load_case(parab_case))
    profiles = []
    for label, c in (("unmodified", read_stress_case(load_case(CASES_DIR / "stress_spur_pair.toml"))),
                     ("linear 15 um / 3 mm", linear), ("parabolic 15 um / 3 mm", parab)):
        t0 = time.perf_counter()
        run = run_stress(c, out / label.split()[0])
        dt = time.perf_counter() - t0
        s = run.summary
        p = np.nan_to_num(run.result.contact_pressure)
        z = run.mesh.points[:, 2]
        b = c.pair.gear1.face_width
        mid = p[(p > 0) & (np.abs(z) <= 0.25 * b)].max()
        ends = p[np.abs(np.abs(z) - 0.5 * b) < 1e-9].max()
        levels = np.unique(np.round(z[p > 0], 3))
        prof = [p[np.abs(z - zz) < 1e-3].max() for zz in levels]
        profiles.append(f"- {label}: " + ", ".join(f"{zz:+.2f}: {pp:.0f}" for zz, pp in zip(levels, prof)))
        lines.append(f"| {label} | {s['dofs']} | {ends:.1f} | {mid:.1f} | {s['max_contact_pressure_mpa']:.1f} | "
                     f"{s['fe_edge_contact']} | {s['contact_force_n']:.1f} | {s['max_fillet_stress_mpa']:.1f} | {dt:.1f} |")
    lines += ["", "Axial profile (z [mm]: largest nodal pressure at that level [MPa]):", ""] + profiles + [""]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = ["# End relief: spur pair 19/24, m 4.5 mm, b 14 mm", ""]
    _tca_section(lines)
    _stress_section(out, lines)
    (out / "end_relief.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
