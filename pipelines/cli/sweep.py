"""Sweep a grid of load cases (positions, torques, misalignments, designs) as independent Dask tasks.

``gearfe sweep SWEEP.toml --out DIR [--scheduler ADDRESS]``. The sweep file names a base case and
the axes of the grid (dotted keys of the base case and their values)::

    task = "tca"                          # what each grid point runs: "tca" (gearfe tca), "stress", or
                                          # "train_tolerance" (below)
    base = "part1_sun_planet.toml"        # relative to the sweep file
    [[axes]]
    key = "misalignment.d_gamma_arcmin"
    values = [-3.0, 0.0, 3.0]
    [[axes]]
    key = "gears.planet.plunge.parabola_per_mm"
    values = [0.001, 0.002]

Designs: an axis with ``key = "base"`` and a list of case files (relative to the sweep file) sweeps
the base case itself (then no top-level ``base``); the other axes apply to each design. A dotted
key may create a table the base case lacks (the case reader then checks it like any other key).

Stress sweeps (``task = "stress"``, :mod:`pipelines.sweep.points`): each point runs
:func:`pipelines.models.stress.run.run_stress` and writes ``result.vtu`` and ``summary.json`` in its case
folder; typical axes are ``torque_nm``, ``phi1_deg``, ``position``, ``misalignment.d_gamma_arcmin``,
``shaft.d_gamma_arcmin``, ``mesh.refine``. An axis over ``position`` or ``phi1_deg`` replaces the
base case's choice of position. Positions through a mesh cycle::

    [positions]
    steps = 12        # 12 positions over one angular pitch of the driving gear, on the TCA grid:
    start = 0         # position = start + i * steps_per_cycle / steps (steps must divide
                      # tca.steps_per_cycle); column "positions.step" = i
    # or: phi1_deg = [-6.0, -5.5, ...]   plain driving-gear angles (column "phi1_deg")

The positions are the innermost axis; a ``[positions]`` table alone (no ``[[axes]]``) is a grid too. A stress sweep over two or more positions also writes
``DIR/te_loaded.png`` (unloaded TCA TE and loaded TE = TCA TE + FE elastic rotation of the driven
body, vs φ1) and ``DIR/load_share.png`` (share of the contact force of each modelled tooth pair vs
φ1), one curve per combination of the other axes.

Tolerance studies of a train (``task = "train_tolerance"``, :mod:`pipelines.sweep.trains`): a train case (kind
``isostatic`` or ``planetary``) as ``base``, an optional ``set = { "train.sun_axis" = "fixed" }`` of its keys, and a
``[samples]`` table (``count``, ``seed``, ``tangential_um``, ``radial_um``, ``distribution``) instead of axes: each
point is one seeded random sample of every planet's pin errors from the band, solved by the train's loaded TCA
with the model built once per worker; ``DIR/summary.json`` carries the K_γ distribution (``k_gamma``: samples,
mean, std, min, max, p95; ``k_gamma_members`` for twins) and ``DIR/k_gamma_distribution.png`` its histogram and
CDF. Example: ``pipelines/cases/sweep_part3_pin_errors.toml``; docs/trains.md, "Tolerance studies".

Every grid point is validated before anything runs, and grid points are distinct cases (a value listed twice
in an axis, or two combinations of the axes giving the same case, are refused: they would share a folder) (a bad key or value: exit status 2, no files,
the error names the grid point); a grid has at most ``MAX_GRID_POINTS`` (10^5) points, and
``--scheduler`` is probed (TCP, 3 s) before anything else.
Each point runs in ``DIR/cases/<id>/`` (written under a temporary name and renamed when finished),
so an interrupted sweep resumes where it stopped and never leaves a half-written case; finished
points are not recomputed (they are read in this process; a cluster is started only for unfinished
points). ``DIR/results.csv`` gathers the axes and the scalar results of all
points (with ``status``; stress: ``phi1_deg``, ``te_unloaded_arcsec``, ``elastic_rotation_arcsec``,
``te_loaded_arcsec``, ``tca_second_pair_gap_arcsec``, maximum stresses, contact force, torque
balance errors, ``dofs``, stage times and ``share.<interface>.member.<m>`` /
``share.<interface>.teeth.<pair>`` load shares); ``DIR/sweep.json`` records the grid. Runs on a
local Dask cluster (processes, one thread each) or on the scheduler at ``--scheduler``.
"""

from __future__ import annotations

import argparse
import copy
import csv
import hashlib
import io
import itertools
import json
import math
import socket
import urllib.parse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from tca.errors import InputError
from pipelines.errors import INPUT_ERRORS, USER_ERRORS

from pipelines.cli.interrupt import check_interrupted
from pipelines.cases.reader import load_case
from pipelines.cases.validate import validate_case
from pipelines.cli.outdir import atomic_write_text
from pipelines.cases.schema import Table
from pipelines.render.sweep import plot_cycle
from pipelines.sweep.points import POSITION_KEYS, STEP_KEY, apply_position, expand_positions, stress_scalars
from pipelines.sweep.points import run_point_stress, validate_stress
from pipelines.sweep.trains import read_tolerance_sweep, run_sample, sample_scalars, tolerance_points, tolerance_summary

__all__ = ["add_args", "handle", "build_grid", "run_point", "check_scheduler", "TASKS", "MAX_GRID_POINTS"]

TASKS = ("tca", "stress", "train_tolerance")
MAX_GRID_POINTS = 100_000  # grid points of one sweep (each is validated before any runs)


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("sweep", help="sweep file (TOML)")
    p.add_argument("--out", required=True, help="output folder (resumable)")
    p.add_argument("--scheduler", default=None, help="address of an existing Dask scheduler (default: local cluster)")
    p.add_argument("--workers", type=int, default=None,
                   help="local cluster size (default: CPU count); 0 runs the points one after the other in this process")


def _set(d: dict, dotted: str, value, where: str):
    keys = dotted.split(".")
    cur = d
    for k in keys[:-1]:
        cur.setdefault(k, {})  # a missing table is created: the case reader checks its keys
        if not isinstance(cur[k], dict):
            raise InputError(where, dotted, f"a key of the base case ({k!r} is a value, not a table)")
        cur = cur[k]
    cur[keys[-1]] = value


def build_grid(sweep_path: str | Path) -> tuple[str, list[dict], list[str]]:
    """(task, points, axis keys): each point {'id', 'values', 'case'} with the patched base case."""
    return _grid(sweep_path)[:3]


def _grid(sweep_path: str | Path) -> tuple:
    """(task, points, keys, the ToleranceSweep of a train tolerance sweep or None)."""
    sweep_path = Path(sweep_path)
    t = load_case(sweep_path)
    task = t.get("task", str, "tca", choices=TASKS)
    if task == "train_tolerance":  # samples of pin errors, not a grid (pipelines.sweep.trains)
        tol = read_tolerance_sweep(t, sweep_path)
        return (task, *tolerance_points(tol), tol)
    axes = t.tables("axes", required=False) or []  # a stress sweep may have only a [positions] table
    keys, values = [], []
    for a in axes:
        k = a.get("key", str)
        v = a.get("values", list)
        if not v:
            raise InputError(f"{a.path}.values", v, "a non-empty list")

        if k in keys:
            raise InputError(f"{a.path}.key", k, "a key not already swept by another axis")
        a.done()
        keys.append(k)
        values.append(v)
    if "base" in keys:
        if t.has("base"):
            raise InputError("base", t.data["base"], "no top-level base when an axis sweeps key = 'base'")
        bases = values[keys.index("base")]
        if any(not isinstance(b, str) for b in bases):
            raise InputError("axes.values", bases, "case file names (strings) for key = 'base'")
    else:
        bases = [t.get("base", str)]
    cases = {b: load_case((sweep_path.parent / b).resolve()).data for b in bases}
    positions = expand_positions(t.table("positions", required=False))
    if positions is not None:
        if task != "stress":
            raise InputError("positions", t.data["positions"], "a [positions] table only with task = 'stress'")
        if any(k in POSITION_KEYS or k == STEP_KEY for k in keys):
            raise InputError("positions", t.data["positions"], "either [positions] or an axis over position/phi1_deg")
        keys.append(positions[0])
        values.append(positions[1])
    if not keys:
        raise InputError("axes", [], "at least one [[axes]] table or a [positions] table")
    t.done()
    size = math.prod(len(v) for v in values)
    if size > MAX_GRID_POINTS:
        raise InputError("axes", " x ".join(str(len(v)) for v in values),
                         f"a grid of at most {MAX_GRID_POINTS} points (the product of the axes' lengths is {size})")
    for i, v in enumerate(values[:len(axes)]):
        seen = set()
        for x in v:
            tag = json.dumps(x, sort_keys=True, default=str)
            if tag in seen:  # the same point twice would race for its folder on a cluster
                raise InputError(f"axes[{i}].values", x, "distinct values in an axis", "listed twice: two grid points "
                                 "would be the same case")
            seen.add(tag)
    points, ids = [], {}
    for combo in itertools.product(*values):
        named = dict(zip(keys, combo))
        case = copy.deepcopy(cases[named.get("base", bases[0])])
        shown = {}
        for k, v in named.items():
            if k == "base":
                shown[k] = v
            elif task == "stress" and (k in POSITION_KEYS or k == STEP_KEY):
                shown[k] = apply_position(case, k, v, "axes.key")
            else:
                _set(case, k, v, "axes.key")
                shown[k] = v
        ident = hashlib.sha1(json.dumps(case, sort_keys=True, default=str).encode()).hexdigest()[:12]
        if ident in ids:  # two combinations of the axes give the same case (e.g. a value equal to the base's)
            where = lambda vals: ", ".join(f"{k} = {v!r}" for k, v in vals.items())  # noqa: E731
            raise InputError("axes", where(shown), "axes whose grid points are distinct cases",
                             f"the same case as grid point {where(ids[ident])}")
        ids[ident] = shown
        points.append({"id": ident, "values": shown, "case": case})
    return task, points, keys, None


def _validate(task: str, point: dict) -> None:
    """Parse a grid point fully (readers only, no solve), raising InputError/GeometryError early."""
    try:
        if task == "tca":
            validate_case(Table(point["case"], ""))
        elif task == "stress":
            validate_stress(point["case"])
    except INPUT_ERRORS as e:  # name the grid point the error belongs to
        where = ", ".join(f"{k} = {v!r}" for k, v in point["values"].items())
        raise InputError(e.field, e.value, e.valid, "; ".join(filter(None, (e.why, f"grid point {where}")))) from None
    except USER_ERRORS as e:
        where = ", ".join(f"{k} = {v!r}" for k, v in point["values"].items())
        raise InputError("axes", where, "a valid case at every grid point", str(e)) from None


def run_point(task: str, point: dict, out_dir: str) -> dict:
    """Run one grid point into out_dir/cases/<id> (atomically); returns its row for results.csv."""
    from pipelines.cli.tca import run_case
    from pipelines.jsonio import to_json

    final = Path(out_dir) / "cases" / point["id"]
    row = {"id": point["id"], **point["values"]}
    scalars = {"stress": stress_scalars, "train_tolerance": sample_scalars}.get(task, _scalars)
    if (final / "summary.json").is_file():
        summary = json.loads((final / "summary.json").read_text())
        return {**row, **scalars(summary), "status": "ok"}
    final.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{point['id']}.tmp-", dir=final.parent))
    try:
        (tmp / "case.json").write_text(json.dumps(point["case"], indent=2))
        if task == "stress":
            summary = run_point_stress(point["case"], tmp)
        elif task == "train_tolerance":
            summary = run_sample(point, tmp)
        else:
            summary = run_case(Table(copy.deepcopy(point["case"]), ""), tmp, label=point["id"])
        (tmp / "summary.json").write_text(json.dumps(summary, indent=2, default=to_json))
        os.replace(tmp, final)
        return {**row, **scalars(summary), "status": "ok"}
    except USER_ERRORS as e:
        shutil.rmtree(tmp, ignore_errors=True)
        return {**row, "status": f"error: {e}"}
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def _scalars(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if isinstance(v, (int, float, bool, str)) and k not in ("case",)}


def _progress(done: int, total: int, t0: float) -> None:
    check_interrupted()
    width = 30
    fill = int(width * done / total)
    rate = done / max(time.perf_counter() - t0, 1e-9)
    sys.stderr.write(f"\r[{'#' * fill}{'.' * (width - fill)}] {done}/{total} points  {rate:.2f}/s ")
    sys.stderr.flush()


SCHEDULER_TIMEOUT_S = 3.0  # connection probe of --scheduler before any work


def check_scheduler(address: str) -> None:
    """Fail fast (InputError on --scheduler) when the Dask scheduler's TCP address cannot be reached."""
    url = urllib.parse.urlparse(address if "://" in address else f"tcp://{address}")
    try:
        host, port = url.hostname, url.port
    except ValueError:
        host, port = None, None
    if url.scheme not in ("tcp", "tls") or not host or not port:
        raise InputError("--scheduler", address, "a Dask scheduler address tcp://HOST:PORT")
    try:
        with socket.create_connection((host, port), timeout=SCHEDULER_TIMEOUT_S):
            pass
    except OSError as e:
        raise InputError("--scheduler", address, "a reachable Dask scheduler",
                         f"{e.strerror or type(e).__name__} within {SCHEDULER_TIMEOUT_S:g} s") from None


def _run_dask(task: str, points: list[dict], out: Path, args, t0: float) -> list[dict]:
    """Run the points as Dask tasks (local cluster or --scheduler); rows in completion order."""
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if args.scheduler:
        try:  # a port that answers but is not a Dask scheduler: fail after 30 s, in one line
            client = Client(args.scheduler, timeout=f"{10 * SCHEDULER_TIMEOUT_S:g}s")
        except (OSError, TimeoutError) as e:
            raise InputError("--scheduler", args.scheduler, "a Dask scheduler", f"{type(e).__name__}: {e}") from None
    else:
        n = args.workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    rows = []
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
    return rows


def handle(args) -> int:
    if args.workers is not None and args.workers < 0:
        raise InputError("--workers", args.workers, "an integer >= 0 (0: in this process)")
    if args.scheduler:
        check_scheduler(args.scheduler)
    task, points, keys, tol = _grid(args.sweep)
    t0 = time.perf_counter()
    for i, p in enumerate(points, 1):  # all inputs checked before any work
        if tol is None:  # a tolerance sweep's base case was read with its samples
            _validate(task, p)
        if len(points) >= 200 and (i % 100 == 0 or i == len(points)):
            sys.stderr.write(f"\rvalidating grid points: {i}/{len(points)} ")
            sys.stderr.flush()
    if len(points) >= 200:
        sys.stderr.write(f"({time.perf_counter() - t0:.1f} s)\n")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for stale in (out / "cases").glob(".*.tmp-*"):  # left by a killed run: never a result
        shutil.rmtree(stale, ignore_errors=True)
    atomic_write_text(out / "sweep.json", json.dumps(
        {"task": task, "axes": keys, "points": [{"id": p["id"], **p["values"]} for p in points]}, indent=2))
    # points finished by an earlier run are read here; only the others are computed (no cluster is started when
    # every point is finished)
    finished = {p["id"] for p in points if (out / "cases" / p["id"] / "summary.json").is_file()}
    rows = [run_point(task, p, str(out.resolve())) for p in points if p["id"] in finished]
    todo = [p for p in points if p["id"] not in finished]
    t0 = time.perf_counter()
    if todo and args.workers == 0 and not args.scheduler:  # in-process, no Dask (tests, debugging)
        _progress(0, len(todo), t0)
        for i, p in enumerate(todo, 1):
            rows.append(run_point(task, p, str(out.resolve())))
            _progress(i, len(todo), t0)
        sys.stderr.write("\n")
    elif todo:
        rows += _run_dask(task, todo, out, args, t0)
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
    if tol is not None:
        from pipelines.jsonio import plain

        summary = tolerance_summary(tol, rows, out, time.perf_counter() - t0)
        atomic_write_text(out / "summary.json", json.dumps(plain(summary), indent=2) + "\n")
        if "k_gamma" in summary:
            k = summary["k_gamma"]
            print(f"K_gamma over {k['samples']} samples: mean {k['mean']:.4f}, 95th percentile {k['p95']:.4f}, "
                  f"min {k['min']:.4f}, max {k['max']:.4f}; summary in {out / 'summary.json'}")
    pos_key = next((k for k in keys if k in POSITION_KEYS or k == STEP_KEY), None)
    if task == "stress" and pos_key is not None:
        for path in plot_cycle(rows, keys, pos_key, out):
            print(f"plot: {path}")
    for r in failed:
        print(f"  {r['id']}: {r['status']}", file=sys.stderr)
    return 1 if failed else 0
