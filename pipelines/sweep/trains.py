r"""Tolerance studies of a planetary train: K_γ over random samples of the planets' pin errors from a band.

Used by ``gearfe sweep`` with ``task = "train_tolerance"`` (:mod:`pipelines.cli.sweep`). The sweep file names a
train case (kind ``isostatic`` or ``planetary``, with its optional ``[ltca]`` table) and a band::

    task = "train_tolerance"
    base = "part3_ideal.toml"
    set = { "train.sun_axis" = "fixed" }   # optional: keys of the base case set for this sweep
    [samples]
    count = 200               # samples (1 ... 100000)
    seed = 1                  # sample k is drawn from the generator seeded with (seed, k)
    tangential_um = 10.0      # band: every planet's tangential pin error within +-10 um
    radial_um = 10.0          # and its radial pin error within +-10 um
    distribution = "uniform"  # or "normal": sigma = band / 3, truncated at the band

Samples. Sample k draws, for every planet i, the pin error :math:`(\Delta r_{c,i}, \Delta E_{t,i})` (radial
outwards, tangential along the carrier's rotation, Part 3 Eq. 3.12) from ``numpy.random.default_rng((seed, k))``:
uniform in :math:`[-b_r, b_r] \times [-b_t, b_t]`, or normal with :math:`\sigma = b/3` redrawn until inside the
band. A sample depends on (seed, k) only: raising ``count`` keeps the first samples (and their results). The
sampled errors are added to the base case's own pin errors (an isostatic case's ``[[train.planet_errors]]``; a
Part 1 case's installment errors and regulation stay built into its meshes) and entered as prescribed translations
of the planets' teeth, exactly as the train LTCA enters pin errors (:mod:`pipelines.models.trains.geometry`).

Each sample is the train LTCA (:func:`pipelines.models.trains.run.solve_run`) at every torque of the base case;
its K_γ is Eq. (T5) over the positions and the torques (the maximum), ``k_gamma_members`` for twins. Positions:
pin errors (and Part 1's installment errors) do not vary with the carrier angle, so the loads repeat every mesh
cycle and one mesh cycle (``positions_per_cycle`` positions) gives the whole revolution's K_γ
(docs/trains.md, "Reuse"); a base case with run-outs or centre errors runs its full ``[ltca]`` span.

Reuse. The model (the meshes' TCAs, the condensed flank compliances, the slices of every mesh phase) does not
depend on the pin errors: it is built once per worker process (:func:`sample_model`, keyed by the base case) and
every sample on that worker reuses it; a sample's summary records ``model_build_s`` (0 when reused) and the
worker's process id.

Statistics over the samples (``summary.json`` of the sweep, :func:`distribution`): mean, standard deviation,
minimum, maximum and the 95th percentile (``numpy.percentile``, linear interpolation between order statistics).
For a sun held on its axis and every planet in contact, Eq. (T6) of docs/trains.md gives each sample's
:math:`K_\gamma - 1 = n k r_{b1} \max_i(\bar a - a_i)/T`, :math:`a_i = 2\Delta E_{t,i}\cos\alpha_{wt}`: linear in
the tangential errors, so for a band :math:`b_t` the mean grows as :math:`b_t` (radial pin errors do not open a
spur planet's path to first order); a floating sun with three planets shares the load equally (K_γ = 1) whatever
the pin errors.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tca.errors import InputError

from pipelines.cases.schema import Table
from pipelines.models.trains.case import TrainCase
from pipelines.models.trains.depth import check_pin_errors, depth_range
from pipelines.models.trains.geometry import TrainErrors
from pipelines.models.trains.run import solve_run, train_positions

__all__ = ["ToleranceBand", "ToleranceSweep", "SampleResult", "DISTRIBUTIONS", "MAX_SAMPLES", "read_tolerance_sweep",
           "read_train_case", "set_keys", "sample_pins", "sample_errors", "tolerance_points", "sample_model", "run_sample",
           "solve_sample", "sample_scalars", "distribution", "tolerance_summary"]

DISTRIBUTIONS = ("uniform", "normal")
MAX_SAMPLES = 100_000
MAX_BAND_UM = 1000.0  # a pin error band beyond 1 mm is not a tolerance


@dataclass(frozen=True)
class ToleranceBand:
    """Half-widths of the pin error band [mm] (radial, tangential) and the distribution inside it."""

    radial: float
    tangential: float
    distribution: str = "uniform"

    def __post_init__(self):
        for key, v in (("samples.radial_um", self.radial), ("samples.tangential_um", self.tangential)):
            if not (math.isfinite(v) and 0.0 <= v <= MAX_BAND_UM * 1e-3):
                raise InputError(key, v * 1e3, f"a band half-width in [0, {MAX_BAND_UM:g}] um")
        if self.radial == 0.0 and self.tangential == 0.0:
            raise InputError("samples.tangential_um", 0.0, "> 0 um (or radial_um > 0): a band of zero width has "
                             "one sample")
        if self.distribution not in DISTRIBUTIONS:
            raise InputError("samples.distribution", self.distribution,
                             "one of " + ", ".join(repr(d) for d in DISTRIBUTIONS))

    @property
    def half_widths(self) -> np.ndarray:
        """(radial, tangential) [mm]."""
        return np.array([self.radial, self.tangential])


@dataclass(frozen=True, eq=False)
class ToleranceSweep:
    """A tolerance sweep file: the base train case (its dict and record), the band, the samples and the seed."""

    base: str  # the base case file as written in the sweep file
    case: dict  # the base case's TOML data
    train: TrainCase
    band: ToleranceBand
    count: int
    seed: int


@dataclass(frozen=True)
class SampleResult:
    """One sample's loaded TCA: K_γ (max over positions and torques), per torque, the planets' share extremes."""

    k_gamma: float
    k_gamma_by_torque: tuple  # per torque of the base case
    k_gamma_members: float | None  # twins
    share_min: float  # smallest planet share of the sun mesh over the run
    share_max: float
    unloaded: tuple  # (planet 1-based, positions) of planets without load at some positions
    positions: int
    solve_s: float


def read_train_case(data: dict, where: str = "base"):
    """A train case's TrainCase from its TOML data (kind isostatic or planetary, read for gearfe ltca)."""
    from pipelines.cases.kinds import kind_of, read_checked

    t = Table(copy.deepcopy(data), "")
    kind = kind_of(t, "ltca")
    if kind.name not in ("isostatic", "planetary"):
        raise InputError(where, kind.name, "a train case (kind 'isostatic' or 'planetary') for task = "
                         "'train_tolerance'")
    return read_checked(t, kind, "ltca")


def set_keys(data: dict, values: dict, where: str = "set") -> dict:
    """A copy of a case's data with dotted keys set (a missing table is created; the case reader checks them)."""
    data = copy.deepcopy(data)
    for dotted, v in values.items():
        cur = data
        keys = dotted.split(".")
        for k in keys[:-1]:
            cur = cur.setdefault(k, {})
            if not isinstance(cur, dict):
                raise InputError(f"{where}.{dotted}", v, f"a key of the base case ({k!r} is a value, not a table)")
        cur[keys[-1]] = v
    return data


def read_tolerance_sweep(t: Table, sweep_path: Path) -> ToleranceSweep:
    """The ``base``, ``set`` and ``[samples]`` of a ``task = "train_tolerance"`` sweep file (module docstring); the
    base case fully read (bad input raises here, before any work)."""
    from pipelines.cases.reader import load_case

    base = t.get("base", str)
    data = load_case((Path(sweep_path).parent / base).resolve()).data
    if t.has("set"):
        st = t.table("set")
        data = set_keys(data, st.data)
    s = t.table("samples")
    count = s.get("count", int, lo=1, hi=MAX_SAMPLES)
    seed = s.get("seed", int, lo=0, hi=2 ** 63 - 1)
    band = ToleranceBand(s.get("radial_um", float, 0.0, lo=0.0, hi=MAX_BAND_UM) * 1e-3,
                         s.get("tangential_um", float, 0.0, lo=0.0, hi=MAX_BAND_UM) * 1e-3,
                         s.get("distribution", str, "uniform", choices=DISTRIBUTIONS))
    s.done()
    t.done()
    train = read_train_case(data)
    own = np.zeros((train.planets, 2)) if not train.errors.pins else np.asarray(train.errors.pins, float)
    rng = depth_range(train.sun, train.planet, train.ring)
    for corner in ((1, 1), (1, -1), (-1, 1), (-1, -1)):  # the band's extremes on the base case's own errors
        check_pin_errors(rng, own + band.half_widths * corner, lambda i: "samples.radial_um")
    return ToleranceSweep(base, data, train, band, count, seed)


def sample_pins(band: ToleranceBand, planets: int, seed: int, index: int) -> np.ndarray:
    """Sample ``index``'s pin errors (planets, 2) [mm], columns (radial, tangential) (module docstring)."""
    rng = np.random.default_rng((seed, index))
    if band.distribution == "uniform":
        u = rng.uniform(-1.0, 1.0, (planets, 2))
    else:
        u = rng.standard_normal((planets, 2)) / 3.0
        out = np.abs(u) > 1.0
        while out.any():  # truncated at the band: redraw the values outside it
            u[out] = rng.standard_normal(int(out.sum())) / 3.0
            out = np.abs(u) > 1.0
    return u * band.half_widths


def sample_errors(base: TrainErrors, pins: np.ndarray) -> TrainErrors:
    """The base case's errors with the sampled pin errors (planets, 2) [mm] added to its own."""
    from dataclasses import replace

    own = np.zeros_like(pins) if not base.pins else np.asarray(base.pins, float)
    return replace(base, pins=tuple((float(r), float(t)) for r, t in own + pins))


def _key(data: dict) -> str:
    return hashlib.sha1(json.dumps(data, sort_keys=True, default=str).encode()).hexdigest()


def tolerance_points(sweep: ToleranceSweep) -> tuple[list[dict], list[str]]:
    """(points, column keys): point k {'id', 'values' (sample, pin errors in um), 'case', 'sample'}; the id depends on
    the base case, the band, the seed and k (a finished sample is found again by a later run)."""
    n = sweep.train.planets
    tag = _key({"case": sweep.case, "band": [sweep.band.radial, sweep.band.tangential, sweep.band.distribution],
                "seed": sweep.seed})
    keys = ["sample"] + [f"p{i + 1}.{c}_um" for i in range(n) for c in ("radial", "tangential")]
    points = []
    for k in range(sweep.count):
        pins = sample_pins(sweep.band, n, sweep.seed, k)
        values = {"sample": k}
        for i in range(n):
            values[f"p{i + 1}.radial_um"] = float(pins[i, 0] * 1e3)
            values[f"p{i + 1}.tangential_um"] = float(pins[i, 1] * 1e3)
        ident = f"s{k:05d}-" + hashlib.sha1(f"{tag}:{k}".encode()).hexdigest()[:10]
        points.append({"id": ident, "values": values, "case": sweep.case,
                       "sample": {"index": k, "seed": sweep.seed, "pins_mm": pins.tolist()}})
    return points, keys


_MODELS: dict = {}  # this worker process's models: base-case key -> (TrainCase, TrainModel)


def sample_model(data: dict):
    """(TrainCase, TrainModel, build seconds) of a base case: built on this process's first call, then reused
    (build seconds 0). One model is kept (a sweep has one base case)."""
    from pipelines.models.trains.ltca import train_layout
    from pipelines.models.trains.model import build_train_model

    key = _key(data)
    hit = _MODELS.get(key)
    if hit is not None:
        return hit[0], hit[1], 0.0
    t0 = time.perf_counter()
    case = read_train_case(data)
    layout, _ = train_layout(case)
    model = build_train_model(layout, case.opts)
    model.build_phases()
    _MODELS.clear()
    _MODELS[key] = (case, model)
    return case, model, time.perf_counter() - t0


def solve_sample(model, case: TrainCase, pins: np.ndarray, psi1=None) -> SampleResult:
    """The train LTCA of one sample (its pin errors (planets, 2) [mm] added to the case's): every torque of the case
    over ``psi1`` (default: one mesh cycle where the errors repeat every cycle, else the case's run)."""
    errors = sample_errors(case.errors, pins)
    if psi1 is None:
        psi1 = train_positions(model)
        if errors.stationary():
            psi1 = psi1[:model.opts.positions_per_cycle]
    t0 = time.perf_counter()
    runs = [solve_run(model, errors, T, psi1) for T in case.opts.torques]
    kg = tuple(r.k_gamma for r in runs)
    members = max(r.k_gamma_members for r in runs) if len(model.layout.members) > 1 else None
    unl = {}
    for r in runs:
        for i, k in r.unloaded:
            unl[i] = max(unl.get(i, 0), k)
    return SampleResult(max(kg), kg, members, float(min(r.sun_share.min() for r in runs)),
                        float(max(r.sun_share.max() for r in runs)), tuple(sorted(unl.items())), len(psi1),
                        time.perf_counter() - t0)


def run_sample(point: dict, out: Path) -> dict:
    """One sample of a tolerance sweep (worker side): the model of this process, the solve; its summary."""
    case, model, build_s = sample_model(point["case"])
    pins = np.asarray(point["sample"]["pins_mm"], float)
    r = solve_sample(model, case, pins)
    return {"kind": "train_sample", "sample": point["sample"]["index"], "seed": point["sample"]["seed"],
            "pins_um": (pins * 1e3).tolist(), "k_gamma": r.k_gamma, "k_gamma_by_torque": list(r.k_gamma_by_torque),
            "torques_nm": [T * 1e-3 for T in case.opts.torques], "k_gamma_members": r.k_gamma_members,
            "share_min": r.share_min, "share_max": r.share_max,
            "unloaded_planets": [{"planet": i, "positions": k} for i, k in r.unloaded], "positions": r.positions,
            "model_build_s": build_s, "solve_s": r.solve_s, "worker_pid": os.getpid(), "files": ["summary.json"]}


def sample_scalars(s: dict) -> dict:
    """CSV columns of a sample's summary."""
    return {"k_gamma": s["k_gamma"], "k_gamma_members": s["k_gamma_members"], "share_min": s["share_min"],
            "share_max": s["share_max"], "unloaded_planets": len(s["unloaded_planets"]), "positions": s["positions"],
            "model_build_s": s["model_build_s"], "solve_s": s["solve_s"], "worker_pid": s["worker_pid"]}


def distribution(values) -> dict:
    """mean, std, min, max, p95 (linear interpolation) and the count of sample values."""
    v = np.asarray(values, float)
    return {"samples": int(v.size), "mean": float(v.mean()), "std": float(v.std(ddof=1)) if v.size > 1 else 0.0,
            "min": float(v.min()), "max": float(v.max()), "p95": float(np.percentile(v, 95))}


def tolerance_summary(sweep: ToleranceSweep, rows: list, out: Path, wall_s: float) -> dict:
    """The sweep's ``summary.json`` record and ``k_gamma_distribution.png`` (module docstring) from the rows of
    its samples (failed samples are counted, not used)."""
    from pipelines.render.tolerance import plot_k_gamma_distribution

    ok = [r for r in rows if r["status"] == "ok"]
    s = {"task": "train_tolerance", "base": sweep.base, "title": sweep.train.title, "kind": sweep.train.kind,
         "planets": sweep.train.planets, "sun_axis": sweep.train.opts.sun_axis,
         "torques_nm": [T * 1e-3 for T in sweep.train.opts.torques],
         "band_um": {"radial": sweep.band.radial * 1e3, "tangential": sweep.band.tangential * 1e3},
         "distribution": sweep.band.distribution, "seed": sweep.seed, "samples": sweep.count,
         "samples_ok": len(ok), "samples_failed": len(rows) - len(ok),
         "conventions": {"pin_error": "radial outwards, tangential along the carrier's rotation (Part 3, Eq. 3.12), "
                                      "added to the base case's own",
                         "k_gamma": "per sample: max over positions and torques of n x the largest planet share "
                                    "(docs/trains.md, Eq. T5)",
                         "p95": "95th percentile, linear interpolation between order statistics"}}
    files = []
    if ok:
        s["k_gamma"] = distribution([float(r["k_gamma"]) for r in ok])
        values = {"K_gamma": [float(r["k_gamma"]) for r in ok]}
        if sweep.train.kind == "planetary":
            s["k_gamma_members"] = distribution([float(r["k_gamma_members"]) for r in ok])
            values["K_gamma of the members"] = [float(r["k_gamma_members"]) for r in ok]
        s["positions_per_sample"] = int(ok[0]["positions"])
        s["samples_with_unloaded_planets"] = sum(1 for r in ok if int(r["unloaded_planets"]))
        builds = [float(r["model_build_s"]) for r in ok if float(r["model_build_s"]) > 0]
        s["timing"] = {"wall_s": wall_s, "model_builds": len(builds), "model_build_s": builds,
                       "solve_s_mean": float(np.mean([float(r["solve_s"]) for r in ok])),
                       "workers": len({r["worker_pid"] for r in ok})}
        files.append(plot_k_gamma_distribution(values, out, sweep.train.title or sweep.base))
    s["files"] = files + ["results.csv", "sweep.json", "summary.json"]
    return s
