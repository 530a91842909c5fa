"""Sweep a grid of load cases (positions, torques, misalignments, designs) as independent Dask tasks.

``gearfe sweep SWEEP.toml --out DIR [--scheduler ADDRESS]``. The sweep file names a base case and
the axes of the grid (dotted keys of the base case and their values)::

    task = "tca"                          # what each grid point runs (gearfe tca)
    base = "part1_sun_planet.toml"        # relative to the sweep file
    [[axes]]
    key = "misalignment.d_gamma_arcmin"
    values = [-3.0, 0.0, 3.0]
    [[axes]]
    key = "gears.planet.plunge.parabola_per_mm"
    values = [0.001, 0.002]

Every grid point is validated before anything runs (a bad key or value: exit status 2, no files).
Each point runs in ``DIR/cases/<id>/`` (written under a temporary name and renamed when finished),
so an interrupted sweep resumes where it stopped and never leaves a half-written case; finished
points are not recomputed. ``DIR/results.csv`` gathers the axes and the scalar results of all
points (with ``status``); ``DIR/sweep.json`` records the grid. Runs on a local Dask cluster
(processes, one thread each) or on the scheduler at ``--scheduler``.
"""

from __future__ import annotations

import argparse
import copy
import csv
import hashlib
import io
import itertools
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from tca.errors import GearfeError, InputError

from .cases import load_case
from .outdir import atomic_write_text
from .schema import Table

__all__ = ["add_args", "handle", "build_grid", "run_point", "TASKS"]

TASKS = ("tca",)


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("sweep", help="sweep file (TOML)")
    p.add_argument("--out", required=True, help="output folder (resumable)")
    p.add_argument("--scheduler", default=None, help="address of an existing Dask scheduler (default: local cluster)")
    p.add_argument("--workers", type=int, default=None, help="local cluster size (default: CPU count)")


def _set(d: dict, dotted: str, value, where: str):
    keys = dotted.split(".")
    cur = d
    for k in keys[:-1]:
        if not isinstance(cur.get(k), dict):
            raise InputError(where, dotted, f"a key of the base case (no table {k!r})")
        cur = cur[k]
    cur[keys[-1]] = value


def build_grid(sweep_path: str | Path) -> tuple[str, list[dict], list[str]]:
    """(task, points, axis keys): each point {'id', 'values', 'case'} with the patched base case."""
    sweep_path = Path(sweep_path)
    t = load_case(sweep_path)
    task = t.get("task", str, "tca", choices=TASKS)
    base_name = t.get("base", str)
    base_path = (sweep_path.parent / base_name).resolve()
    base = load_case(base_path).data
    axes = t.tables("axes")
    if not axes:
        raise InputError("axes", [], "at least one [[axes]] table")
    keys, values = [], []
    for a in axes:
        k = a.get("key", str)
        v = a.get("values", list)
        if not v:
            raise InputError(f"{a.path}.values", v, "a non-empty list")
        a.done()
        keys.append(k)
        values.append(v)
    t.done()
    points = []
    for combo in itertools.product(*values):
        case = copy.deepcopy(base)
        for k, v in zip(keys, combo):
            _set(case, k, v, "axes.key")
        ident = hashlib.sha1(json.dumps(case, sort_keys=True, default=str).encode()).hexdigest()[:12]
        points.append({"id": ident, "values": dict(zip(keys, combo)), "case": case})
    return task, points, keys


def _validate(task: str, point: dict) -> None:
    """Parse a grid point fully (readers only, no solve), raising InputError/GeometryError early."""
    from .cases import read_gears, read_misalignment, read_tca_options

    tab = Table(copy.deepcopy(point["case"]), "")
    if task == "tca":
        read_gears(tab)
        read_misalignment(tab.table("misalignment", required=False))
        read_tca_options(tab.table("tca", required=False))


def run_point(task: str, point: dict, out_dir: str) -> dict:
    """Run one grid point into out_dir/cases/<id> (atomically); returns its row for results.csv."""
    from .cmd_tca import run_case, to_json

    final = Path(out_dir) / "cases" / point["id"]
    row = {"id": point["id"], **point["values"]}
    if (final / "summary.json").is_file():
        summary = json.loads((final / "summary.json").read_text())
        return {**row, **_scalars(summary), "status": "ok"}
    final.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{point['id']}.tmp-", dir=final.parent))
    try:
        (tmp / "case.json").write_text(json.dumps(point["case"], indent=2))
        summary = run_case(Table(copy.deepcopy(point["case"]), ""), tmp, label=point["id"])
        (tmp / "summary.json").write_text(json.dumps(summary, indent=2, default=to_json))
        os.replace(tmp, final)
        return {**row, **_scalars(summary), "status": "ok"}
    except GearfeError as e:
        shutil.rmtree(tmp, ignore_errors=True)
        return {**row, "status": f"error: {e}"}
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def _scalars(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if isinstance(v, (int, float, bool, str)) and k not in ("case",)}


def _progress(done: int, total: int, t0: float) -> None:
    width = 30
    fill = int(width * done / total)
    rate = done / max(time.perf_counter() - t0, 1e-9)
    sys.stderr.write(f"\r[{'#' * fill}{'.' * (width - fill)}] {done}/{total} points  {rate:.2f}/s ")
    sys.stderr.flush()


def handle(args) -> int:
    task, points, keys = build_grid(args.sweep)
    for p in points:  # all inputs checked before any work
        _validate(task, p)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for stale in (out / "cases").glob(".*.tmp-*"):  # left by a killed run: never a result
        shutil.rmtree(stale, ignore_errors=True)
    atomic_write_text(out / "sweep.json", json.dumps(
        {"task": task, "axes": keys, "points": [{"id": p["id"], **p["values"]} for p in points]}, indent=2))
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        n = args.workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    rows = []
    t0 = time.perf_counter()
    try:
        futures = [client.submit(run_point, task, p, str(out.resolve()), pure=False) for p in points]
        _progress(0, len(points), t0)
        for i, fut in enumerate(as_completed(futures), 1):
            rows.append(fut.result())
            _progress(i, len(points), t0)
        sys.stderr.write("\n")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    order = {p["id"]: i for i, p in enumerate(points)}
    rows.sort(key=lambda r: order[r["id"]])
    cols = ["id", *keys]
    for r in rows:
        for k in r:
            if k not in cols and k != "status":
                cols.append(k)
    cols.append("status")
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=cols, extrasaction="ignore")
    w.writeheader()
    w.writerows(rows)
    atomic_write_text(out / "results.csv", buf.getvalue())
    failed = [r for r in rows if r["status"] != "ok"]
    print(f"{len(rows) - len(failed)}/{len(rows)} points ok; results in {out / 'results.csv'}")
    for r in failed:
        print(f"  {r['id']}: {r['status']}", file=sys.stderr)
    return 1 if failed else 0
