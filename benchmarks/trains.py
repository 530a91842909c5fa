"""`make bench` area ``trains``: the report's load-sharing findings under load and the speed of the train LTCA.

1. Findings (docs/workflows.md, "Planetary trains under load"):
   - Part 1, Table 1.1 train with the Table 1.2 errors (``part1_planetary_regulation.toml``): K_γ without
     regulation, with ΔZ^(1) and with ΔZ^(2);
   - Part 1, Example 1.2 (``part1_twin_dgamma.toml``, Δγ = 3′ on shaft 2): the shares of members a and b before
     and after regulation;
   - Part 3: the five error cases with the floating sun, and the same trains with the sun held on its axis.
   Errors that do not vary with the carrier angle (installment, pin errors) repeat every mesh cycle: one
   mesh cycle is run; run-outs and centre errors over one carrier revolution.
2. Speed: the Part 1 train (five twin shafts, 20 meshes) and the Part 3 train over one carrier revolution at
   ``--per-cycle`` positions per mesh cycle (default 10: 1,090 and 1,510 positions); build, solve, cost of a
   further position and a further torque.
3. Tolerance (``--only tolerance``): ``gearfe sweep`` (``task = "train_tolerance"``, a local Dask cluster of
   ``--workers`` processes) of ``--samples`` random samples of the planets' pin errors (tangential and radial,
   uniform within +-10 um, seed 1) for the Part 3 train with the sun held (the shipped
   ``sweep_part3_pin_errors.toml``) and for the Part 1 twin train (``part1_twin_dgamma.toml``): the K_γ
   distribution and the wall time (the models built once per worker).

Writes ``<out>/trains.md`` and ``summary.json``.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from pipelines.cases.kinds import read_checked, kind_of
from pipelines.cases.schema import Table
from pipelines.jsonio import plain
from pipelines.models.trains.ltca import train_layout
from pipelines.models.trains.model import build_train_model
from pipelines.models.trains.run import solve_run, train_positions

from pipelines.cases.reader import CASES_DIR, load_case

__all__ = ["main", "read_train_case", "PART3"]

PART3 = ("part3_ideal", "part3_indexing", "part3_carrier_center", "part3_sun_runout", "part3_planet_runout",
         "part3_double_crowned")
STATIONARY = {"part3_ideal", "part3_indexing", "part3_double_crowned", "part1_planetary_regulation",
              "part1_twin_dgamma"}


def read_train_case(name: str, ltca: dict, train: dict | None = None):
    """A shipped train case with an ``[ltca]`` table (and ``[train]`` overrides): its TrainCase."""
    t = load_case(CASES_DIR / f"{name}.toml")
    t.data["ltca"] = dict(ltca)
    if train:
        t.data.setdefault("train", {}).update(train)
    return read_checked(Table(t.data, t.path), kind_of(t, "ltca"), "ltca")


def _teeth_ring(name: str) -> int:
    return int(load_case(CASES_DIR / f"{name}.toml").data["gears"]["ring"]["teeth"])


def _span(name: str, per_cycle: int) -> dict:
    rev = 1.0 / _teeth_ring(name) if name in STATIONARY else 1.0
    return {"positions_per_cycle": per_cycle, "carrier_revolutions": rev}


def finding(name: str, ltca: dict, train: dict | None = None, say=print) -> dict:
    """K_γ, planet and member shares of one case (one torque)."""
    c = read_train_case(name, ltca, train)
    t0 = time.perf_counter()
    layout, dz = train_layout(c)
    m = build_train_model(layout, c.opts)
    r = solve_run(m, c.errors, c.opts.torques[0])
    out = {"case": name, "ltca": ltca, "train": train or {}, "k_gamma": r.k_gamma, "planet_shares": r.shares_summary(),
           "positions": len(r.psi1), "torque_nm": r.torque * 1e-3, "dz_mm": [list(d) for d in dz],
           "unloaded": r.unloaded, "elapsed_s": time.perf_counter() - t0}
    if len(layout.members) > 1:
        out["k_gamma_members"] = r.k_gamma_members
        out["member_shares"] = {f"p{i + 1}{k}": [float(r.member_share[:, i, j].min()),
                                                 float(r.member_share[:, i, j].mean()),
                                                 float(r.member_share[:, i, j].max())]
                                for i in range(r.planets) for j, k in enumerate(layout.members)}
    if r.sun_center.any():
        out["sun_offset_max_um"] = float((r.sun_center ** 2).sum(1).max() ** 0.5 * 1e3)
    say(f"{name} {train or ''} {ltca.get('regulation', '')}: K_gamma {r.k_gamma:.4f} ({len(r.psi1)} positions, "
        f"{out['elapsed_s']:.0f} s)")
    return out


def speed(name: str, per_cycle: int, grid: dict, say=print) -> dict:
    """Build and solve one carrier revolution; the cost of a further position and torque."""
    c = read_train_case(name, {**grid, "positions_per_cycle": per_cycle, "carrier_revolutions": 1.0,
                               **({"regulation": "first_order"} if name.startswith("part1") else {})})
    t0 = time.perf_counter()
    layout, _ = train_layout(c)
    m = build_train_model(layout, c.opts)
    m.build_phases()  # one-off: the slices of every mesh phase (the run's positions reuse them)
    t_build = time.perf_counter() - t0
    psi = train_positions(m)
    T = c.opts.torques[0]
    t1 = time.perf_counter()
    r = solve_run(m, c.errors, T, psi)
    t_solve = time.perf_counter() - t1
    t2 = time.perf_counter()
    r2 = solve_run(m, c.errors, 1.5 * T, psi)
    t_torque = time.perf_counter() - t2
    out = {"case": name, "positions": len(psi), "meshes": len(layout.sites), "build_s": t_build, "solve_s": t_solve,
           "slices_s": r.build_slices_s, "coupled_solve_s": r.solve_s, "per_position_s": t_solve / len(psi),
           "further_torque_s": t_torque, "per_torque_per_position_s": t_torque / len(psi),
           "distinct_mesh_phases": m.cached_phases, "k_gamma": r.k_gamma, "k_gamma_1.5T": r2.k_gamma,
           "build": m.build}
    say(f"speed {name}: build {t_build:.1f} s, {len(psi)} positions in {t_solve:.1f} s, further torque "
        f"{t_torque:.1f} s")
    return out


PART1_TOLERANCE = """task = "train_tolerance"
base = "{base}"
[samples]
count = {samples}
seed = 1
tangential_um = 10.0
radial_um = 10.0
"""


def tolerance(out: Path, samples: int, workers: int, say=print) -> dict:
    """Tolerance sweeps of the Part 3 train (sun held) and the Part 1 twin train, ``samples`` each, on a local Dask
    cluster: K_γ distribution, wall time, model builds."""
    from pipelines.cli import main as gearfe

    res = {}
    p3 = (CASES_DIR / "sweep_part3_pin_errors.toml").read_text().replace("count = 200", f"count = {samples}")
    p3 = p3.replace('base = "part3_ideal.toml"', f'base = "{CASES_DIR / "part3_ideal.toml"}"')
    files = {"part3_held": p3,
             "part1_twin": PART1_TOLERANCE.format(base=CASES_DIR / "part1_twin_dgamma.toml", samples=samples)}
    for name, text in files.items():
        folder = out / f"tolerance_{name}"
        if folder.exists():  # a fresh run: the time of every sample, none resumed
            import shutil

            shutil.rmtree(folder)
        sweep = out / f"tolerance_{name}.toml"
        sweep.write_text(text)
        t0 = time.perf_counter()
        rc = gearfe(["sweep", str(sweep), "--out", str(folder), "--workers", str(workers)])
        wall = time.perf_counter() - t0
        s = json.loads((folder / "summary.json").read_text())
        res[name] = {"exit": rc, "wall_s": wall, "samples": s["samples_ok"], "k_gamma": s.get("k_gamma"),
                     "k_gamma_members": s.get("k_gamma_members"), "timing": s.get("timing"),
                     "positions_per_sample": s.get("positions_per_sample")}
        say(f"tolerance {name}: {s['samples_ok']} samples in {wall:.1f} s on {workers} workers, K_gamma "
            f"{json.dumps(s.get('k_gamma'))}")
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default="out/bench/trains")
    ap.add_argument("--per-cycle", type=int, default=10)
    ap.add_argument("--quick", action="store_true", help="coarse flank grids, 4 positions per cycle")
    ap.add_argument("--only", choices=("findings", "speed", "tolerance"), default=None)
    ap.add_argument("--samples", type=int, default=200, help="samples of each tolerance sweep")
    ap.add_argument("--workers", type=int, default=2, help="local Dask workers of the tolerance sweeps")
    ap.add_argument("--train", choices=("part1", "part3"), default=None, help="speed of one train only")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    g1 = {"profile_size_mm": 0.6, "axial_size_mm": 2.0, "slice_mm": 1.0} if a.quick else {}
    g3 = {"profile_size_mm": 1.2, "axial_size_mm": 4.0, "slice_mm": 2.0} if a.quick else {}
    P = 4 if a.quick else a.per_cycle
    res = {"findings": {}, "speed": {}, "tolerance": {}}
    if a.only in (None, "findings"):
        f = res["findings"]
        f["part1"] = [finding("part1_planetary_regulation", {**g1, **_span("part1_planetary_regulation", P),
                                                             "regulation": mode})
                      for mode in ("none", "first_order", "tca")]
        f["example12"] = [finding("part1_twin_dgamma", {**g1, **_span("part1_twin_dgamma", P), "regulation": mode})
                          for mode in ("none", "tca")]
        f["part3"] = [finding(n, {**g3, **_span(n, P if n in STATIONARY else max(2, P // 5))}, {"sun_axis": axis})
                      for n in PART3 for axis in ("floating", "fixed")]
    if a.only in (None, "speed"):
        if a.train in (None, "part1"):
            res["speed"]["part1"] = speed("part1_planetary_regulation", a.per_cycle, g1)
        if a.train in (None, "part3"):
            res["speed"]["part3"] = speed("part3_indexing", a.per_cycle, g3)
    if a.only in (None, "tolerance"):
        res["tolerance"] = tolerance(out, a.samples, a.workers)
    (out / "summary.json").write_text(json.dumps(plain(res), indent=2) + "\n")
    (out / "trains.md").write_text(_markdown(res))
    return 0


def _markdown(res: dict) -> str:
    lines = ["# Train LTCA: findings and speed", ""]
    f = res["findings"]
    if f:
        lines += ["| case | sun axis | regulation | positions | K_gamma | K_gamma members | min share | max share |",
                  "|---|---|---|---|---|---|---|---|"]
        for k in ("part1", "example12", "part3"):
            for r in f.get(k, []):
                sh = [p["sun_min"] for p in r["planet_shares"]] + [p["sun_max"] for p in r["planet_shares"]]
                lines.append(f"| {r['case']} | {r['train'].get('sun_axis', '')} | {r['ltca'].get('regulation', '')} | "
                             f"{r['positions']} | {r['k_gamma']:.4f} | {r.get('k_gamma_members', float('nan')):.4f} | "
                             f"{min(sh):.4f} | {max(sh):.4f} |")
    for k, s in res["speed"].items():
        lines += ["", f"speed {k}: " + json.dumps(plain({x: s[x] for x in s if x != 'build'}))]
    for k, s in res.get("tolerance", {}).items():
        lines += ["", f"tolerance {k}: " + json.dumps(plain(s))]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    raise SystemExit(main())
