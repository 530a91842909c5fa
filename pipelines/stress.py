"""Contact stress analysis of gear drives at a TCA position (report section 1.6, Numerical Example 1.3).

Library API (used by ``gearfe stress`` and by the ``run``/``compare``/``sweep`` commands)::

    case = read_stress_case(load_case("pipelines/cases/stress_part1_new.toml"))
    summary = run_stress(case, Path("out/new"), progress=print)   # writes out/new/result.vtu

Near a transition of a mesh the next pair of teeth (``position.next_pair_gap_um`` from the TCA)
closes under load and shares it: the other teeth's loaded flanks are meshed at
``neighbour_size_mm`` for that. The summary's ``warnings`` flag a next pair closer than the elastic
approach that still carries nothing in the FE (its flanks too coarse to close).

Stages (times in the summary): ``tca_s`` tooth contact analysis (and, for the twin drive, the
axial regulation of Part 1), ``mesh_s`` hexahedral models of the parts, ``solve_s`` the contact FE
solve (:func:`fem.solve`), ``results_s`` post-processing and the VTU file.

Models (:mod:`pipelines.stress_scene`): ``pair`` — a gear pair at a TCA position, driver fixed on
its rim (Fig. 1.7's sun), driven gear rigid with its rotation free and the torque ``torque_nm``
against its sense of rotation; ``twin`` — Part 1's twin subgear drive (sun fixed, twin planet
rigid with only its rotation free, ring rigid with the torque T), positioned by the Part 1 TCA with
the shaft errors and the axial regulation ΔZ of members a and b. Stress recovery, load share and
edge contact: :mod:`pipelines.stress_results`.

Case file (TOML, ``kind = "stress"``)::

    kind = "stress"
    model = "twin"                # or "pair"
    title = "..."
    torque_nm = 500.0             # T: on the ring (twin) or the driven gear (pair), resisting
    position = "max_te"           # "max_te", "min_te" or an index of the TCA grid; or instead:
    # phi1_deg = 12.3             # the driving gear's angle
    # pair: driver = "sun", driven = "planet", [gears.*], [misalignment], center_distance_mm
    # twin: planets = 5, member_gap_mm = 10.0, [gears.sun], [gears.planet], [gears.ring] (members a)
    [shaft]                       # twin: errors of the modelled planet shaft
    d_ex_um = 0.0
    d_gamma_arcmin = 3.0
    [regulation]                  # twin: axial positions of members a and b
    mode = "tca"                  # "tca" (ΔZ(2) of Part 1), "none", or "given" with dz_a_mm, dz_b_mm
    member_phase = "assembled"    # members turned to touch the sun (default unless mode = "none"),
                                  # or "nominal": one angle, a one-piece planet (default for "none")
    tol_arcsec = 0.001
    max_iterations = 12
    [tca]                         # cycles, steps_per_cycle, elastic_approach_mm
    [mesh]
    refine = 1.0                  # all element sizes are divided by this factor
    teeth = 3                     # teeth per gear part
    # coarse_size_mm, contact_size_mm, axial_contact_size_mm, fillet_size_mm, neighbour_size_mm, rim_depth_mm,
    # growth, zone: override the defaults of pipelines.stress_scene (Hertz-based contact sizes)
    [fe]
    element = "C3D8I"             # or "C3D8"
    solver = "auto"               # "pardiso", "superlu"
    youngs_modulus_mpa = 2.068e5
    poisson_ratio = 0.29
    penalty_factor = 100.0
    max_penetration_mm = 1e-4
    quadrature = 2
    penalty_check_tol = 0.01      # allowed change of the peak pressure when the penalty doubles
    search_gap_mm = 0.03
    max_search_gap_mm = 0.5
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from tca.errors import InputError
from tca.pair import GearPair
from tca.pair_tca import ARCSEC, TCAOptions, run_pair_tca
from tca.planetary import PlanetaryTrain, ShaftErrors
from tca.planetary_mesh import phi1_grid, run_subgear_tca
from tca.planetary_regulation import nominal_peak, regulate_member, twin_te

from .cases import ARCMIN, read_gears, read_pair, read_tca_options
from .schema import Table
from .stress_model import FESettings, mesh_scene, solve_scene
from .stress_results import member_teeth, summarize
from .stress_scene import PHASES, SizeRules, pair_scene, twin_scene

__all__ = ["StressCase", "read_stress_case", "run_stress", "build_scene", "MODELS", "REGULATION"]

MODELS = ("pair", "twin")
REGULATION = ("tca", "none", "given")


@dataclass(frozen=True)
class StressCase:
    """A stress load case: model, gears, position, torque [N mm], mesh rules and FE settings."""

    model: str
    torque: float  # [N mm] magnitude, on the driven gear (pair) or the ring (twin)
    title: str = ""
    pair: GearPair | None = None
    train: PlanetaryTrain | None = None
    errors: ShaftErrors = field(default_factory=ShaftErrors)
    regulation: str = "tca"
    dz: tuple = (0.0, 0.0)  # [mm] given axial regulation of members a, b
    regulation_tol: float = 1e-3 * ARCSEC  # [rad]
    regulation_maxiter: int = 12
    member_phase: str = ""  # 'assembled' or 'nominal'; '' -> 'nominal' without regulation, else 'assembled'
    position: object = "max_te"  # 'max_te', 'min_te' or a grid index
    phi1: float | None = None  # [rad] instead of position
    tca: TCAOptions = field(default_factory=TCAOptions)
    mesh: SizeRules = field(default_factory=SizeRules)
    fe: FESettings = field(default_factory=FESettings)

    def __post_init__(self):
        if self.model not in MODELS:
            raise InputError("model", self.model, "one of " + ", ".join(repr(m) for m in MODELS))
        if not (self.torque > 0 and math.isfinite(self.torque)):
            raise InputError("torque_nm", self.torque * 1e-3, "a torque > 0 N m")
        if self.model == "pair" and (self.pair is None or self.train is not None):
            raise InputError("model", self.model, "a gear pair (driver, driven) for model 'pair'")
        if self.model == "twin" and (self.train is None or self.pair is not None):
            raise InputError("model", self.model, "a planetary train (sun, planet, ring) for model 'twin'")
        if self.regulation not in REGULATION:
            raise InputError("regulation.mode", self.regulation, "one of " + ", ".join(repr(m) for m in REGULATION))
        if not self.member_phase:
            object.__setattr__(self, "member_phase", "nominal" if self.regulation == "none" else "assembled")
        if self.member_phase not in PHASES:
            raise InputError("regulation.member_phase", self.member_phase, "one of " + ", ".join(repr(p) for p in PHASES))
        dz = tuple(float(x) for x in self.dz)
        if len(dz) != 2 or any(not math.isfinite(x) for x in dz):
            raise InputError("regulation.dz_mm", self.dz, "two finite numbers (members a and b)")
        object.__setattr__(self, "dz", dz)
        if self.train is not None:
            lim = 0.5 * self.train.planet.face_width
            if any(abs(x) > lim for x in dz):
                raise InputError("regulation.dz_a_mm", dz, f"|value| <= half the face width, {lim:g} mm")
        pos = self.position
        if not (pos in ("max_te", "min_te") or (isinstance(pos, int) and not isinstance(pos, bool))):
            raise InputError("position", pos, "'max_te', 'min_te' or an integer index of the TCA positions")
        if self.phi1 is not None and not math.isfinite(self.phi1):
            raise InputError("phi1_deg", self.phi1, "a finite angle")


def _read_mesh(t: Table | None) -> SizeRules:
    if t is None:
        return SizeRules()
    pos = dict(lo=0.0, lo_open=True)
    r = SizeRules(
        refine=t.get("refine", float, 1.0, lo=0.1, hi=10.0),  # default chosen by pipelines.bench_stress
        teeth=t.get("teeth", int, 3, lo=1, hi=9),
        rim_depth=t.get("rim_depth_mm", float, None, **pos),
        coarse=t.get("coarse_size_mm", float, None, **pos),
        contact=t.get("contact_size_mm", float, None, **pos),
        axial=t.get("axial_contact_size_mm", float, None, **pos),
        fillet=t.get("fillet_size_mm", float, None, **pos),
        neighbour=t.get("neighbour_size_mm", float, None, **pos),
        growth=t.get("growth", float, 1.3, lo=1.05, hi=3.0),
        zone=t.get("zone", float, 1.2, lo=0.0, hi=5.0),
    )
    t.done()
    return r


def _read_fe(t: Table | None) -> FESettings:
    if t is None:
        return FESettings()
    f = FESettings(
        E=t.get("youngs_modulus_mpa", float, 2.068e5, lo=0.0, lo_open=True),
        nu=t.get("poisson_ratio", float, 0.29, lo=-1.0, hi=0.5, lo_open=True, hi_open=True),
        element=t.get("element", str, "C3D8I", choices=("C3D8I", "C3D8")),
        solver=t.get("solver", str, "auto", choices=("auto", "pardiso", "superlu")),
        penalty_factor=t.get("penalty_factor", float, 100.0, lo=0.0, lo_open=True, hi=1e6),
        max_penetration=t.get("max_penetration_mm", float, 1e-4, lo=0.0, lo_open=True, hi=0.1),
        quadrature=t.get("quadrature", int, 2, choices=(0, 2, 3, 4)),
        penalty_check_tol=t.get("penalty_check_tol", float, 0.01, lo=0.0, hi=1.0, lo_open=True, hi_open=True),
        search_gap=t.get("search_gap_mm", float, 0.03, lo=0.0, lo_open=True, hi=5.0),
        max_search_gap=t.get("max_search_gap_mm", float, 0.5, lo=0.0, lo_open=True, hi=5.0),
    )
    t.done()
    return f


def _read_position(case: Table):
    has_phi = case.has("phi1_deg")
    if has_phi and case.has("position"):
        raise InputError("phi1_deg", case.data["phi1_deg"], "either phi1_deg or position, not both")
    phi1 = math.radians(case.get("phi1_deg", float, lo=-3600.0, hi=3600.0)) if has_phi else None
    v = case.data.get("position", "max_te")
    if isinstance(v, int) and not isinstance(v, bool):
        pos = case.get("position", int)
    elif isinstance(v, str):
        pos = case.get("position", str, "max_te", choices=("max_te", "min_te"))
    else:
        raise InputError("position", v, "'max_te', 'min_te' or an integer index of the TCA positions")
    return pos, phi1


def read_stress_case(case: Table) -> StressCase:
    """A :class:`StressCase` from a case table (module docstring); every key is checked, unknown keys rejected."""
    kind = case.get("kind", str, "stress", choices=("stress",))
    del kind
    model = case.get("model", str, choices=MODELS)
    title = case.get("title", str, "")
    torque = case.get("torque_nm", float, lo=0.0, lo_open=True, hi=1e7) * 1e3
    pos, phi1 = _read_position(case)
    tca = read_tca_options(case.table("tca", required=False))
    mesh = _read_mesh(case.table("mesh", required=False))
    fe = _read_fe(case.table("fe", required=False))
    if model == "pair":
        for k in ("planets", "member_gap_mm", "shaft", "regulation"):
            if case.has(k):
                raise InputError(k, case.data[k], "no planetary-train keys in a 'pair' case")
        pair, _, _ = read_pair(case, read_gears(case))
        out = StressCase("pair", torque, title, pair=pair, position=pos, phi1=phi1, tca=tca, mesh=mesh, fe=fe)
    else:
        for k in ("driver", "driven", "center_distance_mm", "misalignment"):
            if case.has(k):
                raise InputError(k, case.data[k], "no pair keys in a 'twin' case (the train fixes the meshes)")
        from .tca_planetary import read_train

        train = read_train(case)
        st = case.table("shaft", required=False)
        errors = ShaftErrors()
        if st is not None:
            errors = ShaftErrors(d_ex=st.get("d_ex_um", float, 0.0, lo=-1000.0, hi=1000.0) * 1e-3,
                                 d_gamma=st.get("d_gamma_arcmin", float, 0.0, lo=-60.0, hi=60.0) * ARCMIN)
            st.done()
        rt = case.table("regulation", required=False)
        mode, dz, tol, maxit, phase = "tca", (0.0, 0.0), 1e-3, 12, ""
        if rt is not None:
            mode = rt.get("mode", str, "tca", choices=REGULATION)
            phase = rt.get("member_phase", str, "", choices=("",) + PHASES)
            if mode == "given":
                dz = (rt.get("dz_a_mm", float, lo=-1000.0, hi=1000.0), rt.get("dz_b_mm", float, lo=-1000.0, hi=1000.0))
            else:
                for k in ("dz_a_mm", "dz_b_mm"):
                    if rt.has(k):
                        raise InputError(f"regulation.{k}", rt.data[k], "set only with mode = 'given'")
            tol = rt.get("tol_arcsec", float, tol, lo=1e-6, hi=10.0)
            maxit = rt.get("max_iterations", int, maxit, lo=2, hi=50)
            rt.done()
        if tca.steps_per_cycle % train.planets:
            raise InputError("tca.steps_per_cycle", tca.steps_per_cycle, f"a multiple of the number of planets n = {train.planets}")
        out = StressCase("twin", torque, title, train=train, errors=errors, regulation=mode, dz=dz,
                         regulation_tol=tol * ARCSEC, regulation_maxiter=maxit, member_phase=phase, position=pos, phi1=phi1, tca=tca,
                         mesh=mesh, fe=fe)
    case.done()
    return out


def _pick(te: np.ndarray, position) -> int:
    n = len(te)
    if position == "max_te":
        return int(np.argmax(te[:-1] if n > 1 else te))
    if position == "min_te":
        return int(np.argmin(te[:-1] if n > 1 else te))
    if not -n <= position < n:
        raise InputError("position", position, f"an integer index in [{-n}, {n - 1}] (negative: from the end), "
                         "'max_te' or 'min_te'")
    return int(position) % n


def _regulation(case: StressCase, cache: dict, progress) -> tuple[tuple, dict]:
    """Axial positions (ΔZ_a, ΔZ_b) [mm] of the twin's members and a JSON-ready record."""
    tr, e = case.train, case.errors
    if case.regulation == "none":
        return (0.0, 0.0), {"mode": "none"}
    if case.regulation == "given":
        return case.dz, {"mode": "given", "dz_a_mm": case.dz[0], "dz_b_mm": case.dz[1]}
    target = nominal_peak(tr, case.tca, cache)
    ra = regulate_member(tr, 0, "a", e, target, case.tca, case.regulation_tol, case.regulation_maxiter, cache)
    rb = ra if e.d_gamma == 0.0 else regulate_member(tr, 0, "b", e, target, case.tca, case.regulation_tol,
                                                     case.regulation_maxiter, cache)
    if progress is not None:
        progress(f"tca: regulation dZ(2) a = {ra.dz2:+.4f} mm, b = {rb.dz2:+.4f} mm")
    rec = {"mode": "tca", "target_peak_arcsec": target / ARCSEC, "dz1_a_mm": ra.dz1, "dz2_a_mm": ra.dz2,
           "dz1_b_mm": rb.dz1, "dz2_b_mm": rb.dz2, "iterations": ra.iterations + (0 if rb is ra else rb.iterations),
           "peak_after_a_arcsec": ra.after.peak() / ARCSEC, "peak_after_b_arcsec": rb.after.peak() / ARCSEC}
    return (ra.dz2, rb.dz2), rec


def build_scene(case: StressCase, progress=None):
    """TCA stage: the scene to mesh and solve, and a JSON-ready record of the TCA (position, TE, regulation)."""
    scene, rec, _ = _build(case, progress)
    return scene, rec


def _build(case: StressCase, progress=None):
    """:func:`build_scene` and the TCA result (PairTCAResult, or TwinTE of the twin drive)."""
    E, nu = case.fe.E, case.fe.nu
    if case.model == "pair":
        r = run_pair_tca(case.pair, case.tca)
        phi1 = float(r.phi1[_pick(r.te, case.position)]) if case.phi1 is None else case.phi1
        scene = pair_scene(case.pair, r, phi1, case.torque, case.mesh, E, nu)
        rec = {"te_peak_to_peak_arcsec": r.te_peak_to_peak_arcsec, "edge_contact": r.edge_contact,
               "elapsed_s": r.elapsed}
        return scene, rec, r
    cache: dict = {}
    dz, reg = _regulation(case, cache, progress)
    tw = twin_te(case.train, 0, case.errors, dz, case.tca, cache)
    phi1 = float(tw.phi1[_pick(tw.te, case.position)]) if case.phi1 is None else case.phi1
    grid = phi1_grid(case.train, case.tca)
    subs = {k: run_subgear_tca(case.train, 0, k, case.errors, dz[0 if k == "a" else 1], case.tca, np.array([phi1]), cache)
            for k in ("a", "b")}
    scene = twin_scene(case.train, subs, case.errors, dz, phi1, case.torque, case.mesh, E, nu, case.member_phase)
    rec = {"twin_te_peak_to_peak_arcsec": float(np.ptp(tw.te) / ARCSEC), "twin_te_max_arcsec": float(tw.te.max() / ARCSEC),
           "edge_contact": bool(tw.members["a"].edge_contact or tw.members["b"].edge_contact),
           "phi1_grid_deg": [math.degrees(grid[0]), math.degrees(grid[-1])], "regulation": reg,
           "member_te_max_arcsec": {k: float(tw.members[k].te3.max() / ARCSEC) for k in ("a", "b")}}
    return scene, rec, tw


def _json(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.bool_):
        return bool(x)
    raise InputError("summary", type(x).__name__, "JSON-serialisable values")


def _finite(x):
    """Replace non-finite floats (JSON has none) by None, recursively."""
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_finite(v) for v in x]
    return x


def _warnings(scene, approach: float, interfaces: dict) -> list[str]:
    """Loaded meshes whose next pair of teeth is closer to contact (TCA) than the elastic approach [mm]
    but carries nothing in the FE: the actual approach is smaller than that gap, or its flanks are too coarse
    to close (``[mesh] neighbour_size_mm``)."""
    out = []
    for itf in scene.interfaces:
        g = itf.contact.next_gap
        d = interfaces[itf.name]
        if not (g < approach and d["members"][itf.member]["force_n"] > 0):
            continue
        others = [t["force_n"] for t in member_teeth(itf, interfaces) if t["offset"] != 0]
        if not any(f > 0 for f in others):
            out.append(f"{itf.name} {itf.member}: the next pair of teeth is {g * 1e3:.3g} um from contact by the TCA "
                       f"(< the TCA's elastic approach {approach * 1e3:g} um) but carries no load in the FE: either the "
                       "actual approach is smaller than that gap, or its flanks are meshed too coarsely to close "
                       "(check with a smaller [mesh] neighbour_size_mm)")
    return out


def run_stress(case: StressCase, out: Path, progress=None, artefacts: dict | None = None) -> dict:
    """TCA, mesh, contact solve and results of a case; writes ``out/result.vtu`` and returns the summary.

    ``progress(message)`` (optional) receives one line per stage, starting with the stage name
    ('tca', 'mesh', 'solve', 'results'). ``artefacts`` (optional dict) receives the objects behind
    the summary for further reports: ``tca`` (PairTCAResult or TwinTE), ``scene``, ``mesh``, ``result``.
    """
    out = Path(out)
    t0, c0 = time.perf_counter(), time.process_time()

    def say(msg):
        if progress is not None:
            progress(msg)

    say(f"tca: {case.model} model, torque {case.torque * 1e-3:g} N m")
    scene, tca_rec, tca_obj = _build(case, say)
    t_tca = time.perf_counter() - t0
    pos = scene.info
    say(f"tca: done in {t_tca:.1f} s (phi1 = {pos['phi1_deg']:.4f} deg)")
    t1 = time.perf_counter()
    mesh = mesh_scene(scene)
    t_mesh = time.perf_counter() - t1
    say(f"mesh: {len(scene.parts)} parts, {mesh.n_cells} elements, {3 * mesh.n_points} DOF in {t_mesh:.1f} s")
    t1 = time.perf_counter()
    say("solve: contact FE (" + case.fe.element + ")")
    r, model, attempts = solve_scene(scene, mesh, case.fe, say)
    t_solve = time.perf_counter() - t1
    say(f"solve: {r.info.active} active contact nodes of {r.info.candidates} candidates, "
        f"{r.info.iterations} active-set iterations, {t_solve:.1f} s")
    t1 = time.perf_counter()
    s = summarize(scene, mesh, model, r)
    out.mkdir(parents=True, exist_ok=True)
    r.write_vtu(out / "result.vtu")
    if artefacts is not None:
        artefacts.update(tca=tca_obj, scene=scene, mesh=mesh, result=r)
    t_res = time.perf_counter() - t1
    say(f"results: max von Mises {s['max_von_mises_mpa']:.1f} MPa, max contact pressure {s['max_contact_pressure_mpa']:.1f} MPa, "
        f"torque balance error {s['torque_balance_error']:.2e}")
    warnings = _warnings(scene, case.tca.elastic_approach, s["interfaces"])
    for w in warnings:
        say("warning: " + w)
    summary = {
        "model": case.model, "title": case.title, "torque_nm": case.torque * 1e-3,
        **s,
        "warnings": warnings,
        "position": pos, "tca": tca_rec,
        "tca_s": t_tca, "mesh_s": t_mesh, "solve_s": t_solve, "results_s": t_res,
        "total_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
        "search_gap_attempts": attempts,
        "mesh": {"refine": case.mesh.refine, "teeth": case.mesh.teeth, "parts": len(scene.parts)},
        "files": ["result.vtu"],
    }
    return _finite(json.loads(json.dumps(summary, default=_json)))

