"""Contact stress analysis of gear drives at a TCA position (report section 1.6, Numerical Example 1.3).

Library API (used by ``gearfe stress`` and by the ``run``/``compare``/``sweep`` commands)::

    case = read_stress_case(load_case("pipelines/cases/stress_part1_new.toml"))
    run = run_stress(case, Path("out/new"), progress=print)   # writes out/new/result.vtu
    run.summary["max_contact_pressure_mpa"], run.mesh, run.result  # the summary and the objects behind it

Near a transition of a mesh the next pair of teeth (``position.next_pair_gap_um`` from the TCA)
closes under load and shares it: the other teeth's loaded flanks are meshed at
``neighbour_size_mm`` for that, and (pair model) every pair whose TCA separation is within
``neighbour_reach_um`` gets its own refined zone at the loaded pair's sizes, around the reference
pair's TCA point at its angle (``position.refined_neighbours``). The summary's ``warnings`` flag a next pair closer than the elastic
approach that still carries nothing in the FE (its flanks too coarse to close).

Stages (times in the summary): ``tca_s`` tooth contact analysis (and, for the twin drive, the
axial regulation of Part 1), ``mesh_s`` hexahedral models of the parts, ``solve_s`` the contact FE
solve (:func:`fem.solve`), ``results_s`` post-processing and the VTU file.

Models (:mod:`pipelines.models.stress.scene`): ``pair`` — a gear pair at a TCA position, driver fixed on
its rim (Fig. 1.7's sun), driven gear rigid with its rotation free and the torque ``torque_nm``
against its sense of rotation; ``twin`` — Part 1's twin subgear drive (sun fixed, twin planet
rigid with only its rotation free, ring rigid with the torque T), positioned by the Part 1 TCA with
the shaft errors and the axial regulation ΔZ of members a and b; ``train`` — the whole planetary train of an
isostatic train case (``kind = "isostatic"``, the file ``gearfe ltca`` takes, read by
:func:`pipelines.cases.stress.read_train_stress`) at one position of the train LTCA's run
(:mod:`pipelines.models.stress.train_scene`: torque on the sun, ring held, carrier the frame), with the summary's
``train`` record of the planets' shares of the FE beside the LTCA's (:mod:`pipelines.models.stress.train_results`).
Stress recovery, load share and edge contact: :mod:`pipelines.models.stress.results`.

Case file (TOML, ``kind = "stress"``)::

    kind = "stress"
    model = "twin"                # or "pair"
    title = "..."
    torque_nm = 500.0             # T: on the ring (twin) or the driven gear (pair), resisting
    position = "max_te"           # "max_te", "min_te" or an index of the TCA grid; pair model also
                                  # "pitch", "hpstc", "lpstc" (tca.pair.te: on the path of contact);
    # phi1_deg = 12.3             # or instead the driving gear's angle,
    # roll_deg = 25.0             # or (pair model) the driver's roll angle of the contact at mid-face
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
    # growth, zone: override the defaults of pipelines.models.stress.scene (Hertz-based contact sizes)
    sizing = "loaded"             # zones from the loaded estimate at the position (pipelines.models.stress.loaded,
                                  # issue 26): a zone per pair carrying >= 0.1 of its mesh's force, sized from its
                                  # loaded contact; "tca": from the unloaded TCA (the whole load at the TCA point,
                                  # and every pair within neighbour_reach_um meshed like it: the models before issue 26)
    remesh = false                # true: when the FE loads a pair without a zone beyond 0.1 of its mesh's force
                                  # (a summary warning either way), remesh once with a zone there
    # neighbour_reach_um: sizing = "tca": neighbouring pairs closer than this (TCA) are meshed like the loaded
    # one (default 3 P / (c' b), pipelines.models.stress.sizing.SizeRules.reach; 0: none)
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

import math
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from fem.result import FEResult
from fem.mesh.hexmesh import HexMesh
from tca.errors import InputError
from tca.pair.analysis import ARCSEC, run_pair_tca
from tca.rating.from_gears import nominal_contact
from tca.rating.root_stress import tooth_root
from tca.pair.te import grid_index, position_angle
from tca.planetary.subgear import phi1_grid, run_subgear_tca
from tca.planetary.regulation import RegulationOptions, nominal_peak, regulate_member, twin_te

from pipelines.jsonio import plain
from pipelines.models.stress.case import StressCase
from pipelines.models.stress.loaded import EstimateGrid, Estimator
from pipelines.models.stress.model import ELEMENTS, check_resources, mesh_scene, solve_scene
from pipelines.models.stress.results import member_teeth, summarize
from pipelines.models.stress.scene import Scene, TwinSetting, pair_scene, twin_scene
from pipelines.models.stress.train_results import check_loaded, ltca_at, train_psi1, train_record
from pipelines.models.stress.train_scene import TrainSetting, train_scene
from pipelines.models.stress.zones import ZONE_SHARE

__all__ = ["StressRun", "run_stress", "build_scene", "estimator", "unzoned_loads"]


@dataclass(frozen=True, eq=False)
class StressRun:
    """A solved stress case: its summary and the objects behind it, for reports and further analysis."""

    summary: dict  # JSON-ready record, written as summary.json (keys in the module docstring)
    tca: object  # PairTCAResult (pair model), TwinTE (twin model) or the train LTCA at the position (TrainRun, train)
    scene: Scene  # the parts, interfaces and supports that were meshed
    mesh: HexMesh
    result: FEResult  # displacements, stresses, contact pressure


def _regulation(case: StressCase, cache: dict, progress) -> tuple[tuple, dict]:
    """Axial positions (ΔZ_a, ΔZ_b) [mm] of the twin's members and a JSON-ready record."""
    tr, e = case.train, case.errors
    if case.regulation == "none":
        return (0.0, 0.0), {"mode": "none"}
    if case.regulation == "given":
        return case.dz, {"mode": "given", "dz_a_mm": case.dz[0], "dz_b_mm": case.dz[1]}
    target = nominal_peak(tr, case.tca, cache)
    regulation = RegulationOptions(case.regulation_tol, case.regulation_maxiter)
    ra = regulate_member(tr, 0, "a", e, target, case.tca, regulation, cache)
    rb = ra if e.d_gamma == 0.0 else regulate_member(tr, 0, "b", e, target, case.tca, regulation, cache)
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


def estimator(case: StressCase, forced: dict | None = None) -> Estimator | None:
    """The loaded estimate of a case's scene (``[mesh] sizing = "loaded"``, the default), or None (``"tca"``)."""
    if case.mesh.sizing != "loaded":
        return None
    return Estimator(EstimateGrid(), case.fe.material, ELEMENTS[case.fe.element], case.fe.solver, case.mesh.teeth, forced)


def _build(case: StressCase, progress=None, forced: dict | None = None):
    """:func:`build_scene` and the TCA result (PairTCAResult, or TwinTE of the twin drive)."""
    mat = case.fe.material
    est = estimator(case, forced)
    if case.model == "pair":
        r = run_pair_tca(case.pair, case.tca)
        phi1 = position_angle(r, case.position, case.phi1, case.roll)
        scene = pair_scene(case.pair, r, phi1, case.torque, case.mesh, mat, est)
        rec = {"te_peak_to_peak_arcsec": r.te_peak_to_peak_arcsec, "edge_contact": r.edge_contact,
               "elapsed_s": r.elapsed}
        return scene, rec, r
    if case.model == "train":
        return _build_train(case, est, progress)
    cache: dict = {}
    dz, reg = _regulation(case, cache, progress)
    tw = twin_te(case.train, 0, case.errors, dz, case.tca, cache)
    phi1 = float(tw.phi1[grid_index(tw.te, case.position)]) if case.phi1 is None else case.phi1
    grid = phi1_grid(case.train, case.tca)
    subs = {k: run_subgear_tca(case.train, 0, k, case.errors, dz[0 if k == "a" else 1], case.tca, np.array([phi1]), cache)
            for k in ("a", "b")}
    scene = twin_scene(case.train, subs, TwinSetting(case.errors, dz, case.member_phase), phi1, case.torque, case.mesh, mat,
                       est)
    rec = {"twin_te_peak_to_peak_arcsec": float(np.ptp(tw.te) / ARCSEC), "twin_te_max_arcsec": float(tw.te.max() / ARCSEC),
           "edge_contact": bool(tw.members["a"].edge_contact or tw.members["b"].edge_contact),
           "phi1_grid_deg": [math.degrees(grid[0]), math.degrees(grid[-1])], "regulation": reg,
           "member_te_max_arcsec": {k: float(tw.members[k].te3.max() / ARCSEC) for k in ("a", "b")}}
    return scene, rec, tw


def _build_train(case: StressCase, est: Estimator | None, progress=None):
    """The train model's scene at its position, after the train LTCA there (the planets' loads for the sizes, and the
    check that every planet carries load: :func:`pipelines.models.stress.train_results.check_loaded`)."""
    tc = case.train_case
    psi1 = train_psi1(tc, case.position) if case.phi1 is None else case.phi1
    t0 = time.perf_counter()
    ltca = ltca_at(tc, psi1, case.torque)
    check_loaded(tc, ltca)  # a planet without load would be a free body: refused before meshing
    if progress is not None:
        progress(f"tca: train LTCA at psi1 = {math.degrees(psi1):.4f} deg in {time.perf_counter() - t0:.1f} s, planet shares "
                 + ", ".join(f"{x:.4f}" for x in ltca.sun_share[0]))
    setting = TrainSetting(tc.sun, tc.planet, tc.ring, tc.planets, tc.errors, tc.opts.sun_axis, case.torque, psi1,
                           case.tca, tuple(float(x) for x in ltca.sun_share[0]))
    scene = train_scene(setting, case.mesh, case.fe.material, est)
    rec = {"ltca_s": time.perf_counter() - t0, "ltca_sun_shares": [float(x) for x in ltca.sun_share[0]],
           "ltca_k_gamma_position": float(tc.planets * ltca.sun_share[0].max())}
    return scene, rec, ltca


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


def unzoned_loads(scene: Scene, interfaces: dict) -> dict:
    """(interface, member) -> ((driver tooth, driven tooth), share) of the pairs of teeth that the FE loads with more
    than ``ZONE_SHARE`` of their mesh's force although the loaded estimate gave them no zone (the neighbour mesh:
    their force is right, their peak pressure is not resolved). Meshes sized by the unloaded TCA are not checked."""
    out = {}
    for itf in scene.interfaces:
        if itf.load is None:
            continue
        total = interfaces[itf.name]["members"][itf.member]["force_n"]
        zoned = {z.teeth for z in itf.zones}
        teeth = {off: (j1, j2) for off, j1, j2 in itf.tooth_pairs()}
        for row in member_teeth(itf, interfaces):
            t = teeth.get(row["offset"])
            share = row["force_n"] / total if total > 0 else 0.0
            if t is not None and t not in zoned and share > ZONE_SHARE:
                out.setdefault((itf.name, itf.member), []).append((t, share))
    return out


def _unzoned_warnings(found: dict) -> list[str]:
    return [f"{name} {member}: the FE loads teeth {t[0]}-{t[1]} with {share:.2f} of the mesh's force but the loaded "
            f"estimate gave them no refined zone (neighbour mesh: force right, peak pressure not resolved); "
            "[mesh] remesh = true remeshes once with a zone there"
            for (name, member), rows in found.items() for t, share in rows]


TORQUE_BALANCE_LIMIT = 1e-2  # relative error of the reaction torque above which the result is flagged
FORCE_RATIO_RANGE = (0.5, 2.0)  # contact force / (T / (r_b cos beta_b)) outside this: flagged


def plausibility_warnings(case: StressCase, s: dict) -> list[str]:
    r"""Checks of a solved case against statics: the reaction torque balances T, and (pair model) the
    normal contact force is near the nominal :math:`F_n = T / (r_{b2}\cos\beta_b)` of the driven gear
    (load shared by up to two pairs of teeth, so a factor of two either way is plausible)."""
    out = []
    tb = s.get("torque_balance_error")
    if not (isinstance(tb, float) and tb <= TORQUE_BALANCE_LIMIT):
        out.append(f"torque balance error {tb:.3g} > {TORQUE_BALANCE_LIMIT:g}: the reaction torque does not balance "
                   f"the applied {case.torque * 1e-3:g} N m (check the elastic constants, the penalty and the mesh)")
    if case.model == "pair":
        g = case.pair.gear2
        beta_b = math.atan(math.tan(g.beta_ref) * math.cos(g.transverse_pressure_angle))
        nominal = case.torque / (g.r_b * math.cos(beta_b))
        f = s.get("contact_force_n")
        lo, hi = FORCE_RATIO_RANGE
        if not (isinstance(f, float) and lo * nominal <= f <= hi * nominal):
            out.append(f"contact force {f:.4g} N is far from the nominal T / (r_b2 cos beta_b) = {nominal:.4g} N "
                       f"(ratio outside [{lo:g}, {hi:g}])")
    return out


def _iso6336(case: StressCase) -> dict:
    """Pair model: ISO 6336-3 method B nominal root stress σ_F0 of both gears beside the FE fillet stress.

    σ_F0 assumes the whole load on one tooth at the HPSTC (no load factors); the FE fillet stress equals it only
    where the model does too (``position = "hpstc"``, ``mesh.teeth = 1``; the driven gear's HPSTC is the driver's
    ``"lpstc"``). External and internal gears, straight and parabolic racks (:mod:`tca.rating.root_stress`); a gear where
    method B does not apply (ε_α outside [1, 2)) is None, and ``iso6336.not_covered`` says why.
    """
    if case.model != "pair":
        return {}
    try:
        rec = tooth_root(case.pair, case.torque)
    except InputError as e:
        return {"iso6336_sigma_f0_mpa": None, "iso6336": {"not_covered": str(e)}}
    try:
        nc = nominal_contact(case.pair, case.torque, (case.fe.material.E, case.fe.material.nu))
        rec["contact"] = {**asdict(nc), "note": "ISO 6336-2 sigma_H0 (H1) at the pitch point with Z_eps, no load factors; "
                          "sigma_H0 Z_B / Z_eps: one pair carrying the whole load at the pinion's inner point of single "
                          "contact (the wheel's: Z_D)"}
    except InputError as e:
        rec["contact"] = {"not_covered": str(e)}
    return {"iso6336_sigma_f0_mpa": {g.name: (rec[g.name] or {}).get("sigma_f0_mpa") for g in (case.pair.gear1, case.pair.gear2)},
            "iso6336_sigma_h0_mpa": rec["contact"].get("sigma_h0"), "iso6336": rec}


def _mesh_and_solve(case: StressCase, scene: Scene, say):
    """Resource check, mesh and contact solve of a scene: mesh, FE result, model, search-gap attempts, (mesh, solve) [s]."""
    est = check_resources(scene, case.mesh)  # refuses a model beyond the memory limit, before meshing
    say(f"mesh: estimated {est.elements} elements, {est.dofs} DOF, {est.memory_gb:.2g} GB")
    t1 = time.perf_counter()
    mesh = mesh_scene(scene)
    t_mesh = time.perf_counter() - t1
    say(f"mesh: {len(scene.parts)} parts, {mesh.n_cells} elements, {3 * mesh.n_points} DOF in {t_mesh:.1f} s")
    check_resources(scene, case.mesh, mesh=mesh)  # the real size, before the solve
    t1 = time.perf_counter()
    say("solve: contact FE (" + case.fe.element + ")")
    r, model, attempts = solve_scene(scene, mesh, case.fe, say)
    t_solve = time.perf_counter() - t1
    say(f"solve: {r.info.active} active contact nodes of {r.info.candidates} candidates, "
        f"{r.info.iterations} active-set iterations, {t_solve:.1f} s")
    return mesh, r, model, attempts, (t_mesh, t_solve)


def run_stress(case: StressCase, out: Path, progress=None) -> StressRun:
    """TCA, mesh, contact solve and results of a case; writes ``out/result.vtu``; the summary and its objects.

    ``progress(message)`` (optional) receives one line per stage, starting with the stage name
    ('tca', 'mesh', 'solve', 'results').
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
    mesh, r, model, attempts, (t_mesh, t_solve) = _mesh_and_solve(case, scene, say)
    t1 = time.perf_counter()
    s = summarize(scene, mesh, model, r)
    found = unzoned_loads(scene, s["interfaces"])
    remeshed = None
    if found and case.mesh.remesh:  # once: a zone on every pair the FE loaded beyond the estimate
        forced = {k: tuple(t for t, _ in rows) for k, rows in found.items()}
        say("mesh: remeshing with zones on " + ", ".join(f"{k[0]} {k[1]} {t}" for k, v in forced.items() for t in v))
        first = {"dofs": s["dofs"], "pairs": {f"{k[0]}/{k[1]}": [[list(t), sh] for t, sh in v] for k, v in found.items()},
                 "warnings": _unzoned_warnings(found), "mesh_s": t_mesh, "solve_s": t_solve}
        scene, _, _ = _build(case, None, forced)
        mesh, r, model, attempts, (t_mesh, t_solve) = _mesh_and_solve(case, scene, say)
        t_mesh, t_solve = t_mesh + first["mesh_s"], t_solve + first["solve_s"]
        s = summarize(scene, mesh, model, r)
        found, remeshed = unzoned_loads(scene, s["interfaces"]), first
        pos = scene.info
    pos = {**pos, "remeshed": remeshed}
    if case.model == "train":  # the planets' shares of the FE beside the LTCA's (train_results)
        s["train"] = train_record(scene, mesh, model, r, tca_obj, s["interfaces"])
        say("results: planet shares FE " + ", ".join(f"{p['sun_share']:.4f}" for p in s["train"]["planets"])
            + " / LTCA " + ", ".join(f"{p['ltca_sun_share']:.4f}" for p in s["train"]["planets"]))
    out.mkdir(parents=True, exist_ok=True)
    r.write_vtu(out / "result.vtu")
    t_res = time.perf_counter() - t1
    say(f"results: max von Mises {s['max_von_mises_mpa']:.1f} MPa, max contact pressure {s['max_contact_pressure_mpa']:.1f} MPa, "
        f"torque balance error {s['torque_balance_error']:.2e}")
    iso = _iso6336(case)
    warnings = (_warnings(scene, case.tca.elastic_approach, s["interfaces"]) + _unzoned_warnings(found)
                + plausibility_warnings(case, s))
    for w in warnings:
        say("warning: " + w)
    summary = {
        "model": case.model, "title": case.title, "torque_nm": case.torque * 1e-3,
        **s,
        **iso,
        "warnings": warnings,
        "position": pos, "tca": tca_rec,
        "tca_s": t_tca, "mesh_s": t_mesh, "solve_s": t_solve, "results_s": t_res,
        "total_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
        "search_gap_attempts": attempts,
        "mesh": {"refine": case.mesh.refine, "teeth": case.mesh.teeth, "parts": len(scene.parts)},
        "files": ["result.vtu"],
    }
    return StressRun(plain(summary), tca_obj, scene, mesh, r)

