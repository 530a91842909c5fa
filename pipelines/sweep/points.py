r"""Stress sweeps: one contact-stress run per grid point, its scalar results, loaded TE and load share through a cycle.

Used by ``gearfe sweep`` with ``task = "stress"`` (:mod:`pipelines.cli.sweep`). Each grid point is
a stress case (:mod:`pipelines.models.stress.run`) run by :func:`run_point_stress`; its summary gets two
records computed here:

Loaded transmission error (``loaded_te``). The FE models hold the driving body still (the
driver's rim in the pair model, the sun in the twin model) and leave the driven body rigid with
only its rotation free, the torque :math:`-T` about the axis :math:`\mathbf a` about which it turns
positively in the drive. The FE rotation vector :math:`\boldsymbol\omega` of that body
(``rigid_motion``, global components) gives its elastic rotation
:math:`\delta\phi = \boldsymbol\omega\cdot\mathbf a` (negative: it lags), and

.. math::  \Delta\phi_{loaded}(\phi_1) = \Delta\phi(\phi_1) + \delta\phi,

with :math:`\Delta\phi` the unloaded TE of the TCA at the same :math:`\phi_1` (absolute, as
:mod:`tca.pair.gear_pair`: negative is a lag). Pair: the driven gear 2, :math:`\mathbf a` =
``pair.mounts()[1].axis`` (:math:`-z_f` tilted by the misalignment for an external gear),
:math:`\Delta\phi = \Delta\phi_2`. Twin: the ring, :math:`\mathbf a = -z_f`
(:func:`pipelines.models.stress.scene.twin_scene`), :math:`\Delta\phi = \Delta\phi_3` of the member that
leads. Both in arcsec.

Gap to the next pair of teeth (``tca_second_pair_gap_arcsec``, pair model): at :math:`\phi_1`, the
difference between the TE branch in contact and the next largest branch of the other tooth
pairs (:func:`tca.pair.te.mesh_contact`, ``next_gap``; a tangency-only branch tied with the pair in
contact — conjugate flanks touching outside their working areas — does not count): the rigid-body rotation the driven gear must lag by
before a second pair touches. Where a branch is the tangency of the extended surfaces (its bounded
contact was not searched because it lies below the envelope) it is an upper bound of that pair's
:math:`\Delta\phi`, so the value is a lower bound of the gap. A second pair cannot carry load while
the elastic rotation stays below this gap.

Scaling with torque: the elastic rotation is a tooth-bending part (linear in the load P) plus the
Hertz approach of the contact (:math:`\propto P^{2/3}` for a point contact, Johnson, Contact
Mechanics, section 4.2); doubling the torque multiplies it by a factor between
:math:`2^{2/3} = 1.587` and 2.
"""

from __future__ import annotations

import copy
import math
import os
import time
from pathlib import Path

import numpy as np

from tca.errors import InputError
from tca.pair.analysis import ARCSEC

from pipelines.cases.schema import Table
from pipelines.models.stress.results import loaded_te

__all__ = ["POSITION_KEYS", "STEP_KEY", "validate_stress", "run_point_stress", "second_pair_gap",
           "stress_scalars", "expand_positions", "plot_cycle", "write_cycle_report"]

POSITION_KEYS = ("position", "phi1_deg", "roll_deg")  # keys of a stress case that choose the position
STEP_KEY = "positions.step"  # the CSV/axis column of a [positions] steps expansion

_SCALARS = ("max_von_mises_mpa", "max_contact_pressure_mpa", "contact_force_n", "contact_area_mm2",
            "max_fillet_stress_mpa", "max_fillet_von_mises_mpa", "torque_balance_error",
            "torque_balance_error_kinematic", "reaction_torque_nm", "edge_contact", "fe_edge_contact", "dofs",
            "elements", "tca_s", "mesh_s", "solve_s", "results_s", "total_s", "cpu_s")


def expand_positions(t: Table | None) -> tuple[str, list] | None:
    """The ``[positions]`` table of a sweep file -> (axis key, values), or None (cmd_sweep docstring)."""
    if t is None:
        return None
    has_steps, has_phi = t.has("steps"), t.has("phi1_deg")
    if has_steps == has_phi:
        raise InputError(f"{t.path}", sorted(t.data), "either steps (with optional start) or phi1_deg, not both")
    if has_phi:
        vals = t.get("phi1_deg", list)
        if not vals or any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in vals):
            raise InputError(f"{t.path}.phi1_deg", vals, "a non-empty list of finite angles [deg]")
        t.done()
        return "phi1_deg", [float(v) for v in vals]
    n = t.get("steps", int, lo=1, hi=2000)
    start = t.get("start", int, 0, lo=0)
    t.done()
    return STEP_KEY, [(i, n, start) for i in range(n)]


def apply_position(case: dict, key: str, value, where: str) -> object:
    """Set a position axis value on a case dict (replacing the base's position choice); returns the CSV value."""
    for k in POSITION_KEYS:
        case.pop(k, None)
    if key != STEP_KEY:
        case[key] = value
        return value
    i, n, start = value
    t = case.get("tca", {})
    s = t.get("steps_per_cycle", 40) if isinstance(t, dict) else 40
    cycles = t.get("cycles", 2) if isinstance(t, dict) else 2
    if not isinstance(s, int) or isinstance(s, bool) or s % n:
        raise InputError("positions.steps", n, f"a divisor of tca.steps_per_cycle = {s!r} (positions on the TCA grid)")
    if not isinstance(cycles, int) or isinstance(cycles, bool) or start + s > cycles * s:
        raise InputError("positions.start", start, f"an index in [0, {(cycles - 1) * s if isinstance(cycles, int) else 0}] "
                         f"(one pitch of the TCA grid of tca.cycles = {cycles!r} x {s!r} steps)")
    case["position"] = start + i * (s // n)
    return i


def validate_stress(case: dict) -> None:
    """Parse a stress case fully (no solve) and check a position index against its TCA grid."""
    from pipelines.cases.stress import read_stress_case

    c = read_stress_case(Table(copy.deepcopy(case), ""))
    if isinstance(c.position, int) and c.phi1 is None:
        n = c.tca.cycles * c.tca.steps_per_cycle + 1
        if not -n <= c.position < n:
            raise InputError("position", c.position, f"an index of the TCA grid in [{-n}, {n - 1}]")


def second_pair_gap(case, phi1: float) -> float:
    """Pair model: Δφ2 of the pair in contact minus the next branch at phi1 [rad] (a lower bound, module docstring)."""
    from tca.pair.analysis import run_pair_tca
    from tca.pair.te import mesh_contact

    mc = mesh_contact(run_pair_tca(case.pair, case.tca), phi1)  # next_gap: tca.pair.te (ties of conjugate flanks)
    return mc.next_gap / abs(mc.arms[1]) if mc.arms[1] else float("inf")


def run_point_stress(case_dict: dict, out: Path) -> dict:
    """Run one stress grid point into ``out`` (result.vtu); the summary with ``loaded_te`` and the next-pair gap."""
    from pipelines.cases.stress import read_stress_case
    from pipelines.models.stress.run import run_stress

    case = read_stress_case(Table(copy.deepcopy(case_dict), ""))
    s = run_stress(case, Path(out)).summary
    s["loaded_te"] = loaded_te(case, s)
    t0 = time.perf_counter()
    gap = second_pair_gap(case, math.radians(s["position"]["phi1_deg"])) / ARCSEC if case.model == "pair" else None
    s["tca_second_pair_gap_arcsec"] = gap if gap is None or math.isfinite(gap) else None
    s["gap_s"] = time.perf_counter() - t0
    return {"kind": "stress", **s, "files": ["result.vtu", "summary.json"]}


def stress_scalars(s: dict) -> dict:
    """CSV columns of a stress summary: position, TE, key stresses, times, load shares flattened."""
    pos, lt = s["position"], s["loaded_te"]
    row = {"phi1_deg": pos["phi1_deg"], "torque_nm": s["torque_nm"],
           "active_pair": pos.get("active_pair", pos.get("leading_member")),
           "te_unloaded_arcsec": lt["unloaded_te_arcsec"], "elastic_rotation_arcsec": lt["elastic_rotation_arcsec"],
           "te_loaded_arcsec": lt["loaded_te_arcsec"], "tca_second_pair_gap_arcsec": s.get("tca_second_pair_gap_arcsec")}
    row.update({k: s.get(k) for k in _SCALARS})
    for itf, sh in s["load_share"].items():
        for m, v in sh["members"].items():
            row[f"share.{itf}.member.{m}"] = v
        for name, v in sh["teeth"].items():
            row[f"share.{itf}.teeth.{name}"] = v
    return row


def _num(x) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def _save(fig, path: Path) -> Path:
    """Save a figure under a temporary name and rename it into place (a killed sweep leaves no half PNG)."""
    from pipelines.render.plots import savefig

    tmp = path.with_name(f".{path.stem}.tmp{path.suffix}")
    savefig(fig, tmp)
    os.replace(tmp, path)
    return path


def plot_cycle(rows: list[dict], keys: list[str], position_key: str, out: Path) -> list[Path]:
    """From the rows of a sweep over positions (one curve per group of the other axes), in ``out``:
    te_loaded.png, load_share.png, stress_cycle.png (peak contact pressure and root stress) and
    report.html (the three plots and the table of points, self-contained)."""
    from pipelines.render.plots import plt

    ok = [r for r in rows if r.get("status") == "ok"]
    if len({_num(r["phi1_deg"]) for r in ok}) < 2:
        return []
    others = [k for k in keys if k != position_key]
    groups: dict = {}
    for r in ok:
        groups.setdefault(tuple(str(r[k]) for k in others), []).append(r)
    label = {g: ", ".join(f"{k} = {v}" for k, v in zip(others, g)) or "sweep" for g in groups}
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for q, (g, rs) in enumerate(groups.items()):
        rs = sorted(rs, key=lambda r: _num(r["phi1_deg"]))
        x = [_num(r["phi1_deg"]) for r in rs]
        ax.plot(x, [_num(r["te_unloaded_arcsec"]) for r in rs], "--", color=f"C{q % 10}", marker=".",
                label=f"unloaded (TCA), {label[g]}")
        ax.plot(x, [_num(r["te_loaded_arcsec"]) for r in rs], "-", color=f"C{q % 10}", marker="o", ms=4,
                label=f"loaded (TCA + FE), {label[g]}")
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel("transmission error [arcsec]")
    ax.set_title("Loaded and unloaded transmission error (negative: the driven gear lags)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    paths = [_save(fig, out / "te_loaded.png")]
    ng = len(groups)
    fig, axs = plt.subplots(ng, 1, figsize=(8, 3.2 * ng), squeeze=False, sharex=True)
    for a, (g, rs) in zip(axs[:, 0], groups.items()):
        rs = sorted(rs, key=lambda r: _num(r["phi1_deg"]))
        x = np.array([_num(r["phi1_deg"]) for r in rs])
        cols = sorted({k for r in rs for k in r if k.startswith("share.") and ".teeth." in k and r[k] not in ("", None)})
        for c in cols:
            y = np.array([_num(r.get(c)) for r in rs])
            a.plot(x, y, marker="o", ms=3.5, label=c.split(".teeth.", 1)[1] + f" ({c.split('.')[1]})")
        a.set_ylim(-0.05, 1.05)
        a.set_ylabel("load share")
        a.set_title(label[g], fontsize=9)
        a.grid(alpha=0.3)
        a.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    axs[-1, 0].set_xlabel(r"$\phi_1$ [deg]")
    fig.suptitle("Load shared by neighbouring tooth pairs through the mesh cycle (FE normal forces)")
    paths.append(_save(fig, out / "load_share.png"))
    paths.append(_plot_stresses(groups, label, out / "stress_cycle.png"))
    paths.append(write_cycle_report(ok, rows, keys, out, paths))
    return paths


CYCLE_STRESSES = (("max_contact_pressure_mpa", "peak contact pressure [MPa]"),
                  ("max_fillet_stress_mpa", "root stress: largest principal\nstress on the fillets [MPa]"))


def _plot_stresses(groups: dict, label: dict, path: Path) -> Path:
    """stress_cycle.png: peak contact pressure and root stress (largest fillet principal stress) vs φ1, per group."""
    from pipelines.render.plots import plt

    fig, axs = plt.subplots(len(CYCLE_STRESSES), 1, figsize=(8, 3.3 * len(CYCLE_STRESSES)), sharex=True, squeeze=False)
    for ax, (key, name) in zip(axs[:, 0], CYCLE_STRESSES):
        for q, (g, rs) in enumerate(groups.items()):
            rs = sorted(rs, key=lambda r: _num(r["phi1_deg"]))
            ax.plot([_num(r["phi1_deg"]) for r in rs], [_num(r.get(key)) for r in rs], "-", marker="o", ms=4,
                    color=f"C{q % 10}", label=label[g])
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axs[-1, 0].set_xlabel(r"$\phi_1$ [deg]")
    fig.suptitle("Peak contact pressure and root stress through the mesh cycle (FE)")
    return _save(fig, path)


REPORT_COLUMNS = ("id", "phi1_deg", "torque_nm", "te_unloaded_arcsec", "te_loaded_arcsec", "max_contact_pressure_mpa",
                  "max_fillet_stress_mpa", "max_von_mises_mpa", "contact_force_n", "torque_balance_error", "dofs", "status")


def write_cycle_report(ok: list[dict], rows: list[dict], keys: list[str], out: Path, plots: list[Path]) -> Path:
    """``report.html`` of a stress sweep: the plots through the cycle and one table row per point (self-contained)."""
    from pipelines.render.html import image, section, table, write_page

    cols = [c for c in ("id", *keys) if c not in REPORT_COLUMNS] + list(REPORT_COLUMNS)
    caps = {"te_loaded.png": "Loaded (TCA + FE elastic rotation) and unloaded (TCA) transmission error",
            "load_share.png": "Load share of the modelled tooth pairs (FE normal forces)",
            "stress_cycle.png": "Peak contact pressure and root stress through the mesh cycle"}
    blocks = [f"<p>{len(ok)} of {len(rows)} points solved; axes: {', '.join(keys)}.</p>",
              section("Through the mesh cycle", *(image(p, caps.get(Path(p).name, "")) for p in plots)),
              section("Points", table(rows, [c for c in cols if any(c in r for r in rows)]))]
    tmp = out / ".report.tmp.html"
    write_page(tmp, "Stress sweep through the mesh cycle", *blocks)
    os.replace(tmp, out / "report.html")
    return out / "report.html"
