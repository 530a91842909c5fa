"""gearfe against CalculiX on the same job: the quantities compared and how each is computed (issue 13).

Both solvers' results go through one function, :func:`quantities`, from nodal arrays on the
mesh nodes (:class:`NodalResults`; CalculiX node i+1 = mesh node i, :mod:`pipelines.calculix.job`):

* contact force [N]: magnitude of the resultant of the fixed body's support reactions (the fixed
  body carries only contact loads, so this is the resultant of the contact forces; on an involute
  mesh all contact normals are along the line of action, so it equals the sum of normal forces
  within cos of the normals' spread);
* reaction torque [N m]: moment of those reactions about the fixed body's axis (the reference of
  the torque balance, :mod:`pipelines.models.stress.results`);
* force per tooth pair [N] and load share: gearfe's pair forces (sum of lambda); CalculiX's the
  normal force of the pair's ``*CONTACT PRINT`` CF statistics (its nodal CPRESS extrapolated from
  the integration points does not integrate to the contact force: 3x on the small crowned pair);
  shares = pair / total;
* maximum von Mises per body, fillet maximum principal stress (all fillet sets), both from the
  nodal stress tensor (gearfe: Gauss-point stresses extrapolated and averaged; CalculiX: its own
  extrapolation and averaging), von Mises sqrt(3 J2), principal stresses the eigenvalues;
* peak contact pressure [MPa]: largest nodal pressure; maximum displacement [mm]: largest |u|;
* wall time [s] and peak memory [MB] of each solver (gearfe: the contact solve and the peak
  resident memory of its process; CalculiX: the ccx run and its peak resident memory).

:func:`write_reference` stores what the comparison needs next to ``job.inp`` (``crosscheck_ref.npz``:
node coordinates, node bodies, sets; ``crosscheck_gearfe.json``: gearfe's quantities);
:func:`crosscheck` runs ccx on a copy of the job in ``DIR/ccx`` and returns both sides.
"""

from __future__ import annotations

import json
import os
import resource
import shutil
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from fem.assembly import face_node_areas
from fem.constraints import set_nodes
from mesher.export import abaqus_name
from tca.errors import GearfeError, InputError

from pipelines.calculix.job import CcxJob, CcxOptions, run_ccx, write_job
from pipelines.calculix.frd import read_dat_contact, read_frd

__all__ = ["Quantities", "NodalResults", "quantities", "von_mises", "principal", "write_reference", "write_inp_job", "crosscheck",
           "TARGETS", "table", "load_reference", "load_gearfe", "check_folder"]

# acceptance targets of issue 13 (relative, except the load shares: absolute)
TARGETS = {"contact_force_n": 0.005, "reaction_torque_nm": 0.005, "load_share": 0.02, "fillet_max_principal_mpa": 0.03,
           "max_von_mises_mpa": 0.05, "peak_contact_pressure_mpa": 0.10}


@dataclass(frozen=True)
class Quantities:
    """The compared numbers of one solver (units in the names)."""

    solver: str
    contact_force_n: float
    reaction_torque_nm: float
    pair_force_n: dict
    load_share: dict
    max_von_mises_mpa: dict  # per body
    fillet_max_principal_mpa: float
    peak_contact_pressure_mpa: float
    max_displacement_mm: float
    wall_s: float
    peak_memory_mb: float


def von_mises(S: np.ndarray) -> np.ndarray:
    """von Mises stress of (n, 6) stresses xx yy zz xy yz zx [MPa]."""
    xx, yy, zz, xy, yz, zx = S.T
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (xy**2 + yz**2 + zx**2))


def principal(S: np.ndarray) -> np.ndarray:
    """Principal stresses (n, 3), descending, of (n, 6) stresses xx yy zz xy yz zx [MPa]."""
    xx, yy, zz, xy, yz, zx = S.T
    T = np.stack([np.stack([xx, xy, zx], -1), np.stack([xy, yy, yz], -1), np.stack([zx, yz, zz], -1)], 1)
    return np.linalg.eigvalsh(T)[:, ::-1]


@dataclass(frozen=True, eq=False)
class NodalResults:
    """One solver's results on the mesh nodes: displacements U (n, 3) [mm], stresses S (n, 6) xx yy zz xy yz zx
    [MPa], reaction forces RF (n, 3) [N] and contact pressure (n,) [MPa]."""

    U: np.ndarray
    S: np.ndarray
    RF: np.ndarray
    pressure: np.ndarray


def quantities(ref: dict, res: NodalResults, solver: str, wall_s: float, peak_mb: float, pair_force=None) -> Quantities:
    """The compared numbers of one solver's nodal results (see module docstring).

    ``ref``: :func:`write_reference`'s arrays; ``wall_s`` [s] and ``peak_mb`` [MB] the solver's cost.
    ``pair_force`` (name -> N) overrides the pressure-times-area pair forces (gearfe's exact lambda sums).
    """
    U, S, RF, pressure = res.U, res.S, res.RF, res.pressure
    pts = ref["points"]
    fixed = ref["fixed_nodes"]
    R = RF[fixed].sum(0)
    point, axis = ref["reaction_point"], ref["reaction_axis"] / np.linalg.norm(ref["reaction_axis"])
    torque = float(np.cross(pts[fixed] - point, RF[fixed]).sum(0) @ axis)
    p = np.nan_to_num(np.asarray(pressure, float))
    if pair_force is None:
        pair_force = {}
        for name in ref["pair_names"]:
            faces = ref[f"pair/{name}"]
            w = face_node_areas(pts, faces)  # (f, 4) tributary areas [mm^2]
            pair_force[name] = float(np.sum(w * p[faces]))
    total = sum(pair_force.values())
    share = {k: (v / total if total > 0 else 0.0) for k, v in pair_force.items()}
    vm = von_mises(S)
    body = ref["node_body"]
    vmb = {b: float(vm[body == i].max()) for i, b in enumerate(ref["bodies"])}
    fil = ref["fillet_nodes"]
    return Quantities(solver, float(np.linalg.norm(R)), abs(torque) * 1e-3, pair_force, share, vmb,
                      float(principal(S[fil])[:, 0].max()), float(p.max(initial=0.0)),
                      float(np.linalg.norm(U, axis=1).max()), float(wall_s), float(peak_mb))


def write_reference(out: Path, scene, mesh, result, solve_s: float) -> Quantities:
    """Store the sets and gearfe's quantities next to job.inp; return gearfe's quantities."""
    model = result.model
    body_of_node = np.full(mesh.n_points, -1)
    for i, b in enumerate(mesh.bodies):
        body_of_node[np.unique(mesh.cells[mesh.body_cells(b)])] = i
    fixed = np.unique(np.concatenate([set_nodes(mesh, s.set, "fixed") for b in model.bodies for s in b.supports
                                      if b.name == scene.reaction.body]))
    ref = {"points": mesh.points, "node_body": body_of_node, "bodies": np.array(mesh.bodies), "fixed_nodes": fixed,
           "reaction_point": np.asarray(scene.reaction.point, float), "reaction_axis": np.asarray(scene.reaction.axis, float),
           "fillet_nodes": np.unique(np.concatenate([set_nodes(mesh, s, "fillet") for s in model.fillet_sets])),
           "pair_names": np.array([c.name for c in model.contacts]),
           "pair_slave": np.array([abaqus_name(c.slave) for c in model.contacts]),
           "pair_master": np.array([abaqus_name(c.master) for c in model.contacts])}
    for c in model.contacts:
        ref[f"pair/{c.name}"] = mesh.face_nodes(c.slave)
    np.savez_compressed(out / "crosscheck_ref.npz", **ref)
    q = quantities(ref, NodalResults(result.displacement, result.stress, result.reaction, result.contact_pressure),
                   "gearfe", solve_s, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
                   pair_force={p.name: p.force for p in result.pairs})
    (out / "crosscheck_gearfe.json").write_text(json.dumps(asdict(q), indent=2) + "\n")
    return q


def write_inp_job(out: Path, scene, mesh, result, solve_s: float, formulation: str = "surface") -> CcxJob:
    """``job.inp`` of a solved scene (same penalty scale; gearfe's rotations close the contacts in step 1)
    and the reference files of :func:`crosscheck`."""
    rot = {b: float(np.asarray(r)[...] @ np.asarray(mesh.reference_points[b].axis, float))
           for b, (_, r) in result.rigid_motion.items() if b in mesh.reference_points}
    job = write_job(mesh, result.model, out / "job.inp", CcxOptions(formulation=formulation),
                    penalty_scale=result.info.penalty_scale, closing_rotation=rot,
                    title=f"gearfe stress scene: {scene.model} model")
    write_reference(out, scene, mesh, result, solve_s)
    return job


def load_reference(folder: Path) -> dict:
    """The arrays written by :func:`write_reference`; an InputError naming the file when one is absent or damaged."""
    folder = Path(folder)
    f = folder / "crosscheck_ref.npz"
    if not f.is_file() or not (folder / "job.inp").is_file():
        raise InputError("DIR", str(folder), "a folder written by 'gearfe stress CASE --out DIR --inp' (job.inp, crosscheck_ref.npz)")
    try:
        with np.load(f, allow_pickle=False) as z:
            ref = {k: z[k] for k in z.files}
        for k in ("pair_names", "pair_slave", "pair_master", "bodies"):
            ref[k] = [str(x) for x in ref[k]]
        for k in ("points",):
            ref[k] = np.asarray(ref[k], float)
    except Exception as e:  # noqa: BLE001 - zip, npy header, pickle refusal, missing array: all a damaged file
        raise InputError("DIR", str(folder), "a folder written by 'gearfe stress CASE --out DIR --inp'",
                         f"crosscheck_ref.npz is damaged: {type(e).__name__}: {e}") from None
    return ref


def load_gearfe(folder: Path) -> Quantities:
    """gearfe's quantities (crosscheck_gearfe.json); an InputError naming the file when absent or damaged."""
    f = Path(folder) / "crosscheck_gearfe.json"
    try:
        return Quantities(**json.loads(f.read_text()))
    except Exception as e:  # noqa: BLE001 - missing, not UTF-8, not JSON, other keys: all a damaged folder
        raise InputError("DIR", str(folder), "a folder written by 'gearfe stress CASE --out DIR --inp'",
                         f"crosscheck_gearfe.json is missing or damaged: {type(e).__name__}: {e}") from None


def check_folder(folder: Path) -> tuple[dict, Quantities]:
    """Everything ``gearfe crosscheck DIR`` reads, checked before ccx starts: the reference arrays, gearfe's
    quantities, and ``DIR/ccx`` (a previous run's folder, replaced; not a file)."""
    ref = load_reference(folder)
    gq = load_gearfe(folder)
    work = Path(folder) / "ccx"
    if (work.exists() or work.is_symlink()) and not (work.is_dir() and not work.is_symlink()):
        raise InputError("DIR", str(folder), "a folder whose 'ccx' entry is absent or a folder (CalculiX's results)",
                         f"{work} is a file or a link")
    return ref, gq


def _read_ccx(work: Path, ref: dict, run) -> Quantities:
    """CalculiX's quantities from job.frd and job.dat in ``work``; GearfeError naming the file when damaged."""
    for name in ("job.frd", "job.dat"):
        if not (work / name).is_file():
            raise GearfeError(f"ccx: finished without writing {name}")
    read = {}
    for name, reader in (("job.frd", read_frd), ("job.dat", read_dat_contact)):
        try:
            read[name] = reader(work / name)
        except GearfeError as e:
            raise GearfeError(f"ccx: {name} is damaged: {e}") from None
        except Exception as e:  # noqa: BLE001 - not text, truncated numbers: a damaged result file
            raise GearfeError(f"ccx: {name} is damaged: {type(e).__name__}: {e}") from None
    blocks, cf = read["job.frd"], read["job.dat"]
    missing = [k for k in ("DISP", "STRESS", "FORC", "CONTACT") if k not in blocks]
    if missing:
        raise GearfeError(f"ccx: job.frd has no {', '.join(missing)} block(s)")
    n = len(ref["points"])
    pair_force = {}
    for name, slave, master in zip(ref["pair_names"], ref["pair_slave"], ref["pair_master"]):
        # a pair without any contact element in the last iteration is not printed: no force
        pair_force[name] = max(0.0, cf[(slave, master)]["normal_force"]) if (slave, master) in cf else 0.0
    try:
        res = NodalResults(blocks["DISP"].field(n), blocks["STRESS"].field(n), blocks["FORC"].field(n),
                           blocks["CONTACT"].field(n)[:, 3])
    except (IndexError, ValueError) as e:
        raise GearfeError(f"ccx: job.frd does not match the mesh of job.inp ({n} nodes): {e}") from None
    return quantities(ref, res, "calculix", run.wall_s, run.peak_mb, pair_force=pair_force)


def crosscheck(folder: Path, timeout: float = 3600.0, progress=None) -> tuple[Quantities, Quantities]:
    """Run ccx on a copy of DIR/job.inp; gearfe's and CalculiX's quantities.

    ccx runs in a fresh temporary folder beside ``DIR/ccx``, which replaces ``DIR/ccx`` only once both
    solvers' quantities are read: on any failure (ccx's error, a damaged result, the time limit, a signal)
    the temporary folder is removed and nothing is left behind. ``progress(wall_s, peak_mb)`` is called
    about every 10 s while ccx runs (:func:`pipelines.calculix.job.run_ccx`)."""
    folder = Path(folder)
    ref, gq = check_folder(folder)
    work = Path(tempfile.mkdtemp(prefix=".ccx-", dir=folder))
    try:
        shutil.copy(folder / "job.inp", work / "job.inp")
        run = run_ccx(work / "job.inp", timeout=timeout, progress=progress)
        cq = _read_ccx(work, ref, run)
        final = folder / "ccx"
        if final.is_dir():
            shutil.rmtree(final)
        os.replace(work, final)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return gq, cq


def _rows(g: Quantities, c: Quantities):
    rows = [("contact force [N]", g.contact_force_n, c.contact_force_n, "rel", TARGETS["contact_force_n"]),
            ("reaction torque [N m]", g.reaction_torque_nm, c.reaction_torque_nm, "rel", TARGETS["reaction_torque_nm"])]
    for k in g.load_share:
        rows.append((f"load share {k}", g.load_share[k], c.load_share.get(k, float("nan")), "abs", TARGETS["load_share"]))
    for b in g.max_von_mises_mpa:
        rows.append((f"max von Mises {b} [MPa]", g.max_von_mises_mpa[b], c.max_von_mises_mpa.get(b, float("nan")), "rel",
                     TARGETS["max_von_mises_mpa"]))
    rows += [("fillet max principal [MPa]", g.fillet_max_principal_mpa, c.fillet_max_principal_mpa, "rel",
              TARGETS["fillet_max_principal_mpa"]),
             ("peak contact pressure [MPa]", g.peak_contact_pressure_mpa, c.peak_contact_pressure_mpa, "rel",
              TARGETS["peak_contact_pressure_mpa"]),
             ("max displacement [mm]", g.max_displacement_mm, c.max_displacement_mm, "rel", None),
             ("wall time [s]", g.wall_s, c.wall_s, "ratio", None),
             ("peak memory [MB]", g.peak_memory_mb, c.peak_memory_mb, "ratio", None)]
    out = []
    for name, a, b, kind, tol in rows:
        if kind == "abs":
            d = b - a
        elif kind == "ratio":
            d = b / a if a else float("nan")
        else:
            d = (b - a) / abs(a) if a else float("nan")
        ok = None if tol is None else bool(abs(d) <= tol)
        out.append({"quantity": name, "gearfe": a, "calculix": b, "difference": d, "kind": kind, "target": tol, "within": ok})
    return out


def table(g: Quantities, c: Quantities) -> tuple[str, list[dict]]:
    """Markdown side-by-side table and its rows (difference: relative, absolute for shares, ratio for cost)."""
    rows = _rows(g, c)
    lines = ["| quantity | gearfe | CalculiX | difference | target | within |", "|---|---|---|---|---|---|"]
    for r in rows:
        d = r["difference"]
        ds = f"{d:+.2%}" if r["kind"] == "rel" else (f"{d:+.4f}" if r["kind"] == "abs" else f"x{d:.2f} (ccx/gearfe)")
        tgt = "" if r["target"] is None else (f"{r['target']:.1%}" if r["kind"] == "rel" else f"{r['target']:g}")
        w = "" if r["within"] is None else ("yes" if r["within"] else "NO")
        lines.append(f"| {r['quantity']} | {r['gearfe']:.6g} | {r['calculix']:.6g} | {ds} | {tgt} | {w} |")
    return "\n".join(lines) + "\n", rows
