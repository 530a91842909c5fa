"""Part 1 benchmark: regulation of the planetary train on the report's data, measured against Table 1.2.

Run:  .venv/bin/python -m benchmarks.part1 --out DIR   (writes DIR/bench_part1.md and bench_part1.json)

Studies: Numerical Example 1.1 (Table 1.2) at full resolution with timing; the report's ΔZ^(2) evaluated in
our TCA; finite-difference sensitivities of the TE maximum to ΔE_x and ΔZ against the first-order values of
Eq. (1.16); convergence of ΔZ^(2) with the TCA grid; Numerical Example 1.2 (Δγ = 3 arcmin, members a/b).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path

import numpy as np

from tca.pair.analysis import ARCSEC, TCAOptions
from tca.planetary.train import ShaftErrors
from tca.planetary.regulation import nominal_peak, periodic_peak, regulate_member, regulate_train, twin_te

from pipelines.cases.reader import CASES_DIR, load_case, read_tca_options
from pipelines.cases.planetary import read_installment, read_train

__all__ = ["main", "REPORT_TABLE_1_2"]

# Table 1.2 of the report: Delta E_x [um], Delta Z^(1) [mm] (Eq. 16), Delta Z^(2) [mm] (TCA)
REPORT_TABLE_1_2 = [(0, 0.0, 0.0), (20, -4.44, -4.6), (-20, 4.44, 4.6), (5, -1.11, -1.15), (-5, 1.11, 1.15)]


def _case(name):
    case = load_case(CASES_DIR / name)
    train = read_train(case)
    errors = read_installment(case.table("installment"), train.planets)
    opts = read_tca_options(case.table("tca", required=False))
    return train, errors, opts


def _load() -> str:
    try:
        return " / ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def example_1_1(lines: list, out: dict) -> None:
    train, errors, opts = _case("part1_planetary_regulation.toml")
    load0 = _load()
    reg = regulate_train(train, errors, opts)
    lines += ["## Numerical Example 1.1 (Table 1.2), `part1_planetary_regulation.toml`", "",
              f"TCA grid: {opts.steps_per_cycle} steps per sun pitch, {opts.cycles} cycles; secant tolerance 1e-3 arcsec "
              "on the TE maximum.", "",
              "| planet | ΔE_x [μm] | ΔZ^(1) ours [mm] | ΔZ^(1) report | ΔZ^(2) ours [mm] | ΔZ^(2) report | ours/report "
              "| TCA runs | max before [\"] | max after [\"] |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    rows = []
    for (ra, _), (dex, z1, z2), e in zip(reg.members, REPORT_TABLE_1_2, errors):
        ratio = ra.dz2 / z2 if z2 else float("nan")
        i = ra.shaft
        lines.append(f"| 2^({i + 1}) | {e.d_ex * 1e3:g} | {ra.dz1:.4f} | {z1:g} | {ra.dz2:.4f} | {z2:g} | "
                     f"{ratio:.4f} | {ra.iterations} | {reg.before.twins[i].peak / ARCSEC:.3f} | "
                     f"{reg.after.twins[i].peak / ARCSEC:.4f} |")
        rows.append({"planet": i + 1, "dEx_um": e.d_ex * 1e3, "dz1_mm": ra.dz1, "dz2_mm": ra.dz2, "report_dz1_mm": z1,
                     "report_dz2_mm": z2})
    b, f, a = reg.before.summary(), reg.first_order.summary(), reg.after.summary()
    lines += ["", "| | before | with ΔZ^(1) | with ΔZ^(2) |", "|---|---|---|---|",
              f"| spread of the maxima [\"] | {b['spread_arcsec']:.4g} | {f['spread_arcsec']:.4g} | {a['spread_arcsec']:.4g} |",
              f"| planets in mesh | {b['planets_in_mesh']} | {f['planets_in_mesh']} | {a['planets_in_mesh']} |",
              f"| smallest margin of the planet in mesh [\"] | {b['min_margin_to_next_planet_arcsec']:.3f} | "
              f"{f['min_margin_to_next_planet_arcsec']:.3f} | {a['min_margin_to_next_planet_arcsec']:.3f} |",
              f"| largest backlash \\|M_j M_i\\| [\"] | {b['max_backlash_arcsec']:.2f} | {f['max_backlash_arcsec']:.2f} | "
              f"{a['max_backlash_arcsec']:.2f} |",
              f"| integrated TE peak-to-peak [\"] | {b['integrated_peak_to_peak_arcsec']:.3f} | "
              f"{f['integrated_peak_to_peak_arcsec']:.3f} | {a['integrated_peak_to_peak_arcsec']:.3f} |", "",
              f"Regulation of 5 planets (10 members, b mirrored): **wall {reg.elapsed:.1f} s, CPU {reg.cpu:.1f} s**, "
              f"{reg.tca_runs} member evaluations (two pair TCAs each); load average before: {load0}.", ""]
    out["example_1_1"] = {"rows": rows, "before": b, "first_order": f, "after": a, "wall_s": reg.elapsed,
                          "cpu_s": reg.cpu, "load": load0}

    # the report's Delta Z^(2) in our TCA
    cache: dict = {}
    target = reg.target
    lines += ["### The report's ΔZ^(2) in our TCA", "",
              "| planet | ΔZ = report's ΔZ^(2) [mm] | max Δφ3 - target [\"] | equivalent ΔZ error [mm] |", "|---|---|---|---|"]
    slope = (math.tan(train.sun.helix) - math.tan(train.ring.helix)) / train.ring.r_p
    rep = []
    for (dex, _, z2), e in list(zip(REPORT_TABLE_1_2, errors))[1:]:
        i = REPORT_TABLE_1_2.index((dex, _, z2))
        t = twin_te(train, i, e, (z2, z2), opts, cache)
        g = (t.peak - target) / ARCSEC
        lines.append(f"| 2^({i + 1}) | {z2:g} | {g:+.3f} | {g * ARCSEC / slope:+.4f} |")
        rep.append({"planet": i + 1, "dz_mm": z2, "peak_minus_target_arcsec": g})
    out["report_dz2_in_our_tca"] = rep

    # sensitivities by finite differences
    p0 = nominal_peak(train, opts, cache)
    pz = twin_te(train, 0, ShaftErrors(), (1.0, 1.0), opts, cache).peak
    px = twin_te(train, 0, ShaftErrors(d_ex=0.01), (0.0, 0.0), opts, cache).peak
    sz, sx = (pz - p0) / ARCSEC, (px - p0) / 0.01 / ARCSEC
    sz1, sx1 = slope / ARCSEC, 2 / train.ring.r_p / ARCSEC
    lines += ["", "### Sensitivities of the TE maximum (finite differences on the TCA)", "",
              "| | TCA | first order | ratio |", "|---|---|---|---|",
              f"| dP/dΔZ [\"/mm] (ΔZ = 1 mm) | {sz:.4f} | (tan β1 - tan β3)/r3 = {sz1:.4f} | {sz / sz1:.5f} |",
              f"| dP/dΔE_x [\"/mm] (ΔE_x = 10 μm) | {sx:.3f} | 2/r3 = {sx1:.3f} | {sx / sx1:.5f} |",
              f"| ΔZ balancing 20 μm [mm] | {-0.02 * sx / sz:.4f} | Eq. (1.16): {-0.02 * sx1 / sz1:.4f} | |", ""]
    out["sensitivities"] = {"dP_dZ_arcsec_per_mm": sz, "first_order_dP_dZ": sz1, "dP_dEx_arcsec_per_mm": sx,
                            "first_order_dP_dEx": sx1}

    # grid convergence of Delta Z^(2) (planet 2^(2))
    lines += ["### ΔZ^(2) of planet 2^(2) against the TCA grid", "", "| steps per cycle | ΔZ^(2) [mm] | wall [s] |",
              "|---|---|---|"]
    conv = []
    for s in (20, 40, 80):
        o = TCAOptions(cycles=1, steps_per_cycle=s)
        c: dict = {}
        t0 = time.perf_counter()
        tgt = nominal_peak(train, o, c)
        r = regulate_member(train, 1, "a", errors[1], tgt, o, cache=c)
        dt = time.perf_counter() - t0
        lines.append(f"| {s} | {r.dz2:.5f} | {dt:.1f} |")
        conv.append({"steps_per_cycle": s, "dz2_mm": r.dz2, "wall_s": dt})
    out["grid_convergence"] = conv
    lines.append("")


def example_1_2(lines: list, out: dict) -> None:
    train, errors, opts = _case("part1_twin_dgamma.toml")
    reg = regulate_train(train, errors, opts)
    ra, rb = reg.members[0]
    lines += ["## Numerical Example 1.2 (Δγ = 3 arcmin on planet 2^(1)), `part1_twin_dgamma.toml`", ""]
    lines += ["| | ΔZ_a [mm] | ΔZ_b [mm] | max a [\"] | max b [\"] | max a - max b [\"] | max\\|a - b\\| over φ1 [\"] "
              "| φ1 of max a - φ1 of max b [deg] |", "|---|---|---|---|---|---|---|---|"]
    res = {}
    for which, lab in (("before", "before"), ("first_order", "ΔZ^(1)"), ("after", "ΔZ^(2)")):
        a, b = getattr(ra, which), getattr(rb, which)
        pa, pb = periodic_peak(a.te3) / ARCSEC, periodic_peak(b.te3) / ARCSEC
        dmax = float(np.abs(a.te3 - b.te3).max() / ARCSEC)
        pitch = 360 / train.sun.teeth
        dphi = (math.degrees(a.phi1[np.argmax(a.te3)] - b.phi1[np.argmax(b.te3)]) + pitch / 2) % pitch - pitch / 2
        lines.append(f"| {lab} | {a.dz:.4f} | {b.dz:.4f} | {pa:.3f} | {pb:.3f} | {pa - pb:+.4f} | {dmax:.3f} | {dphi:+.2f} |")
        res[which] = {"dz_a_mm": a.dz, "dz_b_mm": b.dz, "peak_a_arcsec": pa, "peak_b_arcsec": pb,
                      "max_abs_diff_arcsec": dmax, "peak_phase_diff_deg": dphi}
    lines += ["", f"Spread of the planets' maxima: before {reg.before.spread / ARCSEC:.3f}\", after "
              f"{reg.after.spread / ARCSEC:.2e}\"; wall {reg.elapsed:.1f} s, CPU {reg.cpu:.1f} s.", ""]
    out["example_1_2"] = res | {"wall_s": reg.elapsed, "cpu_s": reg.cpu}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    outdir = Path(args.out)
    outdir.mkdir(parents=True, exist_ok=True)
    t0, c0 = time.perf_counter(), time.process_time()
    lines = ["# Part 1 benchmark: planetary train, regulation of backlash", "",
             f"Load average at start: {_load()} (2 cores, shared machine: wall times are noisy).", ""]
    out: dict = {}
    example_1_1(lines, out)
    example_1_2(lines, out)
    lines.append(f"Total: wall {time.perf_counter() - t0:.1f} s, CPU {time.process_time() - c0:.1f} s; "
                 f"load average at end: {_load()}.")
    (outdir / "bench_part1.md").write_text("\n".join(lines) + "\n")
    (outdir / "bench_part1.json").write_text(json.dumps(out, indent=2) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
