"""Loaded TCA of a gear pair over a mesh cycle: build the flank compliances once, then solve every position.

``run_ltca(case, opts, out)`` writes into ``out``:

- ``results.csv``: one row per torque and position: unloaded TE, elastic rotation and loaded TE
  [arcsec], total normal force [N], peak pressure [MPa], mesh stiffness [N/um], load share of
  each pair of teeth (``share.<driver><j1>-<driven><j2>``, the gears' own tooth indices as in
  ``gearfe stress``), pairs within reach and in contact;
- ``pressure.csv``: the slices of every contact line (position, pair, ξ, point, load, pressure), streamed to
  disk position by position (:mod:`pipelines.models.ltca.plan`: the resource plan checked before the build);
- ``te_loaded.png``, ``load_share.png``, ``pressure.png`` (Hertz pressure along the contact lines
  through the cycle, one panel per torque), ``mesh_stiffness.png`` (:mod:`pipelines.render.ltca`);
- the summary (``summary.json`` by the CLI): build and solve times, the cost of a further position
  and torque, and, with ``check_positions`` > 0, the check against the full contact FE
  (:func:`fe_check`).

Costs: the contact lines and their compliance W (:func:`pipelines.models.ltca.contact.contact_lines`)
depend on the position only, so a further torque costs one small contact solve per position.
"""

from __future__ import annotations

import csv
import dataclasses
import math
import sys
import time
from pathlib import Path

import numpy as np

from tca.errors import InputError
from tca.pair.analysis import ARCSEC, run_pair_tca
from tca.planetary.subgear import MeshTE

from pipelines.models.ltca.options import LTCAOptions
from pipelines.models.ltca.plan import PLOT_POSITIONS, LTCAPlan, check_plan
from pipelines.models.ltca.compliance import FlankGrid, flank_compliance, strip_constant, weber_constant
from pipelines.models.ltca.contact import contact_lines, solve_contact, teeth_in_reach
from pipelines.models.stress.case import StressCase
from pipelines.models.stress.model import ELEMENTS
from pipelines.models.stress.scene import mesh_contact

__all__ = ["LTCAModel", "build_model", "run_ltca", "fe_check", "TARGETS", "progress_bar", "ProgressBar", "solve_positions",
           "PRESSURE_COLUMNS"]

# acceptance of issue 18 against the full contact FE: elastic rotation (relative), load share (absolute),
# peak pressure (relative)
TARGETS = {"elastic_rotation": 0.02, "load_share": 0.03, "peak_pressure": 0.10}


@dataclasses.dataclass(frozen=True, eq=False)
class LTCAModel:
    """The pair, its TCA, the periodic TE and both gears' condensed flank compliances."""

    case: StressCase
    opts: LTCAOptions
    tca: object
    mte: MeshTE
    flanks: tuple
    sizes: tuple  # (profile, axial, slice) [mm]
    local: float  # constant c of the Hertzian flattening (pipelines.models.ltca.compliance.flattening)
    build_s: float
    tca_s: float
    plan: LTCAPlan | None = None  # the resource plan checked before the flank models were built


def build_model(case: StressCase, opts: LTCAOptions, say=None) -> LTCAModel:
    """TCA and the one-off flank compliances of both gears (module docstring of :mod:`.compliance`)."""
    t0 = time.perf_counter()
    pair = case.pair
    r = run_pair_tca(pair, case.tca)
    mte = MeshTE.from_result(r)
    t_tca = time.perf_counter() - t0
    m = max(pair.gear1.module, pair.gear2.module)
    hu, hz, ds = opts.sizes(m, min(pair.gear1.face_width, pair.gear2.face_width))
    teeth = teeth_in_reach(pair, mte, r.phi1, ds, opts.reach, case.mesh.teeth)
    if teeth > case.mesh.teeth:  # every pair within reach modelled, here and in the FE check of the same case
        if teeth > 9:
            raise InputError("ltca.reach_um", opts.reach * 1e3, f"a reach whose pairs of teeth fit a model of at most 9 "
                             f"teeth per gear (they span {teeth})")
        if say is not None:
            say(f"build: {teeth} teeth per gear ([mesh] teeth = {case.mesh.teeth}): pairs of teeth within reach span them")
        case = dataclasses.replace(case, mesh=dataclasses.replace(case.mesh, teeth=teeth))
    plan = check_plan(case, opts)  # GEARFE_MAX_MEMORY_GB, before the flank models are built
    if say is not None:
        say(f"plan: per gear about {max(plan.elements)} elements, {max(plan.dofs)} DOF, {max(plan.flank_nodes)} flank "
            f"nodes, {plan.memory_gb:.2g} GB (limit GEARFE_MAX_MEMORY_GB)")
    i = int(np.argmax(r.te[:-1] if len(r.te) > 1 else r.te))
    c = mesh_contact(r, float(r.phi1[i]))
    coarse = hz  # the body's elements as fine as the axial grid (a coarser body is too stiff in bending, docs/ltca.md)
    flanks = []
    for g, side, u in ((pair.gear1, pair.side1, c.params[0]), (pair.gear2, pair.side2, c.params[2])):
        fc = flank_compliance(g, side, FlankGrid(case.mesh.teeth, hu, hz, coarse, u), case.fe.material,
                              ELEMENTS[case.fe.element], case.fe.solver)
        if say is not None:
            say(f"build: {g.name}: {fc.info['elements']} elements, {fc.info['dofs']} DOF, {fc.info['flank_nodes']} flank nodes "
                f"condensed in {fc.info['total_s']:.1f} s")
        flanks.append(fc)
    c_loc = strip_constant(case.fe.material) if opts.local == "strip" else weber_constant(case.fe.material.nu)
    if say is not None:
        say(f"build: Hertzian flattening constant c = {c_loc:+.4f} ({opts.local})")
    return LTCAModel(case, opts, r, mte, tuple(flanks), (hu, hz, ds), c_loc, time.perf_counter() - t0, t_tca, plan)


class ProgressBar:
    """A callable (done, total) drawing a text progress bar on stderr; ``close()`` ends an unfinished bar's line
    (so that an error raised mid-run starts on a line of its own)."""

    def __init__(self, prefix: str, stream=None):
        self.prefix, self.stream, self.open = prefix, stream or sys.stderr, False

    def __call__(self, done: int, total: int) -> None:
        n = 30 * done // max(total, 1)
        self.stream.write(f"\r{self.prefix} [{'#' * n}{'.' * (30 - n)}] {done}/{total}")
        self.open = done < total
        if not self.open:
            self.stream.write("\n")
        self.stream.flush()

    def close(self) -> None:
        if self.open:
            self.stream.write("\n")
            self.stream.flush()
            self.open = False


def progress_bar(prefix: str, stream=None) -> ProgressBar:
    """A :class:`ProgressBar` on ``stream`` (stderr)."""
    return ProgressBar(prefix, stream)


def _pair_name(model: LTCAModel, teeth) -> str:
    p = model.case.pair
    return f"{p.gear1.name}{teeth[0]}-{p.gear2.name}{teeth[1]}"


def positions(model: LTCAModel) -> np.ndarray:
    """Driver angles [rad] of the cycle: ``opts.positions`` equal steps over one pitch from the TCA grid start."""
    p1 = 2 * math.pi / model.case.pair.gear1.teeth
    phi0 = float(model.tca.phi1[0])
    return phi0 + p1 * np.arange(model.opts.positions) / model.opts.positions


PRESSURE_COLUMNS = ("phi1_deg", "torque_nm", "pair", "xi_mm", "x_mm", "y_mm", "z_mm", "force_n", "line_load_n_per_mm",
                    "pressure_mpa")


def solve_positions(model: LTCAModel, phis, torques, bar=None, pressure_sink=None) -> tuple[list, list, dict]:
    """Rows of results.csv and pressure.csv for every position and torque; timing record.

    With ``pressure_sink`` (a callable taking a list of pressure rows) the pressure rows of every position go
    to it as they are solved and only those of at most :data:`PLOT_POSITIONS` evenly spread positions are
    returned (for the plots): a long run keeps its slices on disk, not in memory."""
    case, hu_hz_ds = model.case, model.sizes
    material = case.fe.material
    rows, prows = [], []
    t_lines = t_solve = 0.0
    n = len(phis)
    stride = 1 if pressure_sink is None else max(1, math.ceil(n / PLOT_POSITIONS))
    for ip, phi in enumerate(phis):
        here = []
        t0 = time.perf_counter()
        L = contact_lines(case.pair, model.mte, float(phi), model.flanks, hu_hz_ds[2], model.opts.reach, material)
        t1 = time.perf_counter()
        t_lines += t1 - t0
        names = [_pair_name(model, t) for t in L.teeth]
        for T in torques:
            t2 = time.perf_counter()
            s = solve_contact(L, T, material, model.local)
            t_solve += time.perf_counter() - t2
            tot = float(s.F.sum())
            row = {"phi1_deg": math.degrees(phi), "torque_nm": T * 1e-3, "active_branch": L.k,
                   "te_unloaded_arcsec": L.te / ARCSEC, "elastic_rotation_arcsec": -s.delta / ARCSEC,
                   "te_loaded_arcsec": (L.te - s.delta) / ARCSEC, "contact_force_n": tot,
                   "max_pressure_mpa": float(s.pressure.max()), "mesh_stiffness_n_per_um": s.stiffness * 1e-3,
                   "pairs_in_reach": len(L.branches), "pairs_loaded": int((s.pair_force > 0).sum()),
                   "iterations": s.iterations}
            for name, f in zip(names, s.pair_force):
                row[f"share.{name}"] = float(f / tot)
            row.update({f"length_mm.{n}": float(L.length[L.pair == q].sum()) for q, n in enumerate(names)})  # K_Hα
            rows.append(row)
            for j in np.flatnonzero(s.F > 0):
                here.append({"phi1_deg": math.degrees(phi), "torque_nm": T * 1e-3, "pair": names[L.pair[j]],
                              "xi_mm": float(L.xi[j]), "x_mm": float(L.x[j, 0]), "y_mm": float(L.x[j, 1]),
                              "z_mm": float(L.x[j, 2]), "force_n": float(s.F[j]), "line_load_n_per_mm": float(s.F[j] / L.length[j]),
                              "pressure_mpa": float(s.pressure[j])})
        if pressure_sink is not None:
            pressure_sink(here)
        if ip % stride == 0:
            prows += here
        if bar is not None:
            bar(ip + 1, n)
    nt = max(len(torques), 1)
    timing = {"positions": n, "torques": len(torques), "lines_s": t_lines, "solve_s": t_solve,
              "per_position_s": (t_lines + t_solve / nt) / max(n, 1), "per_torque_per_position_s": t_solve / max(n * nt, 1)}
    return rows, prows, timing


def _write_csv(path: Path, rows: list) -> None:
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, restval="")
        w.writeheader()
        w.writerows(rows)


def check_indices(rows: list, n: int) -> list[int]:
    """n positions for the FE check: both sides of every change of the pair in contact, the largest TE, then evenly spread."""
    if n <= 0:
        return []
    br = [r["active_branch"] for r in rows]
    pick = []
    for i in range(1, len(br)):
        if br[i] != br[i - 1]:
            pick += [i - 1, i]
    pick.append(int(np.argmax([r["te_unloaded_arcsec"] for r in rows])))
    for i in np.linspace(0, len(rows) - 1, n).round().astype(int):
        pick.append(int(i))
    out = []
    for i in pick:
        if i not in out:
            out.append(i)
    return sorted(out[:n])


def fe_check(model: LTCAModel, rows: list, indices: list[int], out: Path | None = None, say=None) -> dict:
    """Full contact FE (``gearfe stress`` of the same case) at the rows' positions and torques against the loaded TCA.

    The FE is sized from the unloaded TCA (``[mesh] sizing = "tca"``: a zone on every pair within the TCA's reach),
    never from the loaded estimate: a reference sized by the model it checks would share that model's view of
    which pairs carry load."""
    from pipelines.models.stress.run import run_stress
    from pipelines.models.stress.results import loaded_te

    pts = []
    for n, i in enumerate(indices):
        r = rows[i]
        c = dataclasses.replace(model.case, phi1=math.radians(r["phi1_deg"]), torque=r["torque_nm"] * 1e3,
                                mesh=dataclasses.replace(model.case.mesh, sizing="tca"))
        t0 = time.perf_counter()
        s = run_stress(c, out / f"fe_{i}").summary if out is not None else _run_tmp(c, run_stress)
        rot = loaded_te(c, s)["elastic_rotation_arcsec"]
        fe_sh = {k.split("/", 1)[-1]: v for k, v in next(iter(s["load_share"].values()))["teeth"].items()}
        names = sorted(set(fe_sh) | {k[6:] for k in r if k.startswith("share.")})
        dsh = max(abs(fe_sh.get(k, 0.0) - (r.get(f"share.{k}") or 0.0)) for k in names)
        arm = abs(mesh_contact(model.tca, c.phi1).arms[1])
        k_fe = s["contact_force_n"] / (abs(rot) * ARCSEC * arm) * 1e-3 if rot else float("inf")
        pts.append({"phi1_deg": r["phi1_deg"], "torque_nm": r["torque_nm"],
                    "fe_elastic_rotation_arcsec": rot, "ltca_elastic_rotation_arcsec": r["elastic_rotation_arcsec"],
                    "rotation_error": abs(r["elastic_rotation_arcsec"] - rot) / abs(rot),
                    "fe_shares": fe_sh, "ltca_shares": {k[6:]: v for k, v in r.items() if k.startswith("share.")},
                    "share_error": dsh,
                    "fe_peak_pressure_mpa": s["max_contact_pressure_mpa"], "ltca_peak_pressure_mpa": r["max_pressure_mpa"],
                    "pressure_error": abs(r["max_pressure_mpa"] - s["max_contact_pressure_mpa"]) / s["max_contact_pressure_mpa"],
                    "fe_mesh_stiffness_n_per_um": k_fe, "ltca_mesh_stiffness_n_per_um": r["mesh_stiffness_n_per_um"],
                    "fe_dofs": s["dofs"], "fe_s": time.perf_counter() - t0})
        if say is not None:
            p = pts[-1]
            say(f"check {n + 1}/{len(indices)}: phi1 = {r['phi1_deg']:.3f} deg, rotation FE {rot:.2f} / LTCA "
                f"{r['elastic_rotation_arcsec']:.2f} arcsec, share error {dsh:.3f}, pressure FE "
                f"{p['fe_peak_pressure_mpa']:.0f} / LTCA {p['ltca_peak_pressure_mpa']:.0f} MPa ({p['fe_s']:.0f} s)")
    worst = {"elastic_rotation": max((p["rotation_error"] for p in pts), default=float("nan")),
             "load_share": max((p["share_error"] for p in pts), default=float("nan")),
             "peak_pressure": max((p["pressure_error"] for p in pts), default=float("nan"))}
    return {"positions": pts, "worst": worst, "targets": TARGETS,
            "met": {k: bool(worst[k] <= TARGETS[k]) for k in TARGETS}}


def _run_tmp(c, run_stress):
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        return run_stress(c, Path(d)).summary


def run_ltca(case: StressCase, opts: LTCAOptions, out: Path, say=None, bar=None, keep_fe: bool = False) -> dict:
    """Build, solve every position and torque, write the files of the module docstring; the summary."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    model = build_model(case, opts, say)
    if say is not None:
        say(f"build: done in {model.build_s:.1f} s (TCA {model.tca_s:.1f} s)")
    phis = positions(model)
    torques = opts.torques or (case.torque,)
    t1 = time.perf_counter()
    with open(out / "pressure.csv", "w", newline="") as fh:  # streamed: a long run keeps its slices on disk
        w = csv.DictWriter(fh, fieldnames=PRESSURE_COLUMNS)
        w.writeheader()
        rows, prows, timing = solve_positions(model, phis, torques, bar, w.writerows)
    t_solve = time.perf_counter() - t1
    _write_csv(out / "results.csv", rows)
    from pipelines.render.ltca import plot_ltca

    files = ["results.csv", "pressure.csv"] + plot_ltca(rows, prows, out)
    check = None
    if opts.check_positions:
        base = [r for r in rows if r["torque_nm"] == case.torque * 1e-3] or rows[:len(phis)]
        idx = check_indices(base, opts.check_positions)
        check = fe_check(model, base, idx, out if keep_fe else None, say)
    hu, hz, ds = model.sizes
    summary = {
        "kind": "ltca", "title": case.title, "model": case.model, "positions": len(phis),
        "torques_nm": [T * 1e-3 for T in torques],
        "plan": model.plan.summary() if model.plan is not None else None,
        "flank_grid_mm": {"profile": hu, "axial": hz, "slice": ds, "teeth": model.case.mesh.teeth},
        "local": {"model": opts.local, "constant": model.local},
        "flanks": {fc.gear.name: {k: v for k, v in fc.info.items()} for fc in model.flanks},
        "build_s": model.build_s, "tca_s": model.tca_s, "solve_all_s": t_solve, "timing": timing,
        "te_loaded_peak_to_peak_arcsec": {f"{T * 1e-3:g}": float(np.ptp([r["te_loaded_arcsec"] for r in rows
                                                                         if r["torque_nm"] == T * 1e-3]))
                                          for T in torques},
        "max_pressure_mpa": max(r["max_pressure_mpa"] for r in rows),
        "fe_check": check, "files": files, "total_s": time.perf_counter() - t0,
    }
    return summary
