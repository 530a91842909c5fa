"""CalculiX/ABAQUS job of a stress scene: the same mesh, supports, load and penalty contact (issue 13).

:func:`write_job` writes one self-contained input deck (``job.inp``) that ``ccx job`` runs
unchanged (how CalculiX solves it: :class:`CcxOptions`); :func:`run_ccx` runs it. Conventions (see also ``docs/calculix.md``):

* Units mm, N, MPa (as gearfe): E [MPa], torque [N mm], penalty slope K [MPa/mm].
* Node ids 1..n are the mesh nodes in gearfe's order (node i+1 = mesh node i), then one
  reference node per reference point of the mesh (node set ``<BODY>_REF``, as ``mesher.write_inp``),
  then one rotation node per rigid body (``<BODY>_ROT``). Element ids 1..m in gearfe's order. Ids are
  compact because CalculiX sizes its arrays by the largest id.
* Sets: ABAQUS names of the mesh's sets (``planet/tooth0/flank_neg`` -> ``PLANET_TOOTH0_FLANK_NEG``,
  :func:`mesher.export.abaqus_name`); an element set per body; surfaces of type ELEMENT per face set.
* Supports (Fig. 1.7): a :class:`fem.Fixed` set -> ``*BOUNDARY`` on its nodes; a :class:`fem.Rigid`
  set -> ``*RIGID BODY, NSET=.., REF NODE=.., ROT NODE=..``. The reference node's DOFs 1-3 are
  its translations, the rotation node's DOFs 1-3 its rotations about the global axes. gearfe holds
  the rigid DOFs not listed in ``free`` in the reference frame R = [e1 e2 e3] (e3 the axis,
  :func:`fem.constraints.axis_frame`): a held rotation about e_j is the linear constraint
  e_j . theta = 0, written as ``*BOUNDARY`` when e_j is a global axis and as ``*EQUATION``
  otherwise (a misaligned planet's axis is tilted by the shaft error).
* Torque T about the axis e3 -> ``*CLOAD`` on the rotation node, moment vector T e3.
* Contact: one ``*CONTACT PAIR`` per gearfe contact pair, slave first, frictionless, with a linear
  pressure-overclosure law ``p = K d``. gearfe's penalty per unit area is
  eps = s * f * E / h (``fem.contact``: f the penalty factor, h the thickness of the slave element
  under the node, s the penalty scale the solve reached, ``penalty_scale`` of the summary). One slope
  per pair: K = s f E / h_min, h_min the thinnest slave element of the pair (the contact zone is
  the finest part of the flank), so K is gearfe's penalty where the load is carried and stiffer
  elsewhere; both penalties are stiff enough that the solution is within 1 % of the hard-contact
  limit (gearfe's doubling check).
  ``NODE TO SURFACE`` (default): a slave node against the master faces, force K d A_a with A_a the
  node's tributary area -- gearfe's ``quadrature = 0``. gearfe's default (``quadrature = 2``)
  averages the gap over the node's faces first (segment-to-segment), which smooths the pressure on
  non-matching meshes; forces and stresses away from the zone agree, the nodal peak pressure
  differs by the node-to-surface ripple (docs/calculix.md). ``SURFACE TO SURFACE`` is also
  writable (``formulation = "surface"``).
* Analysis: ``*STATIC, SOLVER=ITERATIVE CHOLESKY`` (Debian's ccx links SPOOLES only, which is
  slow: MEASURED.md), small displacements (no NLGEOM, as gearfe).
* Output: ``*NODE FILE`` U, RF; ``*EL FILE`` S (nodal, extrapolated and averaged by ccx);
  ``*CONTACT FILE`` CDIS, CSTR; ``*NODE PRINT`` totals of RF on the fixed rims and on the reference
  and rotation nodes, and ``*CONTACT PRINT`` CF of every pair (total and normal contact force on its
  slave surface) into ``job.dat``.
"""

from __future__ import annotations

import math
import os
import shutil
import signal
import subprocess
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.linalg as sla

from fem.constraints import axis_frame
from fem.model import RIGID_DOFS, FEModel, Fixed, Rigid
from mesher.export import abaqus_name, write_inp
from fem.mesh.hexmesh import HEX_FACES, HexMesh
from tca.errors import GearfeError, InputError

__all__ = ["CCX_INSTALL", "FORMULATIONS", "CcxOptions", "CcxRigid", "CcxPair", "CcxJob", "pair_penalty", "write_job", "ccx_path",
           "CcxRun", "run_ccx", "check_timeout", "MAX_TIMEOUT_S", "PROGRESS_S"]

CCX_INSTALL = "apt-get install calculix-ccx"
FORMULATIONS = {"node": "NODE TO SURFACE", "surface": "SURFACE TO SURFACE"}
SOLVERS = ("SPOOLES", "ITERATIVE CHOLESKY", "ITERATIVE SCALING", "PARDISO", "PASTIX")
ELEMENT_TYPES = {"hex8i": "C3D8I", "hex8": "C3D8"}
_OPPOSITE = np.array([1, 0, 4, 5, 2, 3])


@dataclass(frozen=True)
class CcxOptions:
    """How CalculiX solves a job: contact ``formulation`` (a key of FORMULATIONS), linear ``solver`` (one of
    SOLVERS), the clearance ``c0`` [mm] of the node-to-surface pressure-overclosure law, and the
    ``increment`` of the static steps."""

    formulation: str = "node"
    solver: str = "SPOOLES"
    c0: float = 1e-3
    increment: float = 1.0

    def __post_init__(self):
        if self.formulation not in FORMULATIONS:
            raise InputError("formulation", self.formulation, "one of " + ", ".join(repr(f) for f in FORMULATIONS))
        if self.solver not in SOLVERS:
            raise InputError("solver", self.solver, "one of " + ", ".join(repr(f) for f in SOLVERS))


@dataclass(frozen=True)
class CcxRigid:
    """A rigid body of the job: body, reference and rotation node ids (1-based), set names."""

    body: str
    ref_node: int
    rot_node: int
    nset: str
    ref_set: str
    rot_set: str


@dataclass(frozen=True)
class CcxPair:
    """A contact pair of the job: gearfe name, slave and master surface names, slope K [MPa/mm]."""

    name: str
    group: str
    slave: str
    master: str
    slave_set: str
    penalty: float


@dataclass(frozen=True)
class CcxJob:
    """What :func:`write_job` wrote: the deck, element type, formulation, rigid bodies, pairs, fixed sets."""

    path: Path
    element: str
    formulation: str
    n_nodes: int
    rigid: tuple[CcxRigid, ...]
    pairs: tuple[CcxPair, ...]
    fixed: tuple[tuple[str, str], ...]  # (body, ABAQUS node set)
    names: dict


def pair_penalty(mesh: HexMesh, slave: str, E: float, factor: float, scale: float = 1.0) -> float:
    """gearfe's penalty eps = s f E / h at the thinnest slave element of a face set [MPa/mm]."""
    fs = mesh.face_sets[slave]
    X = mesh.points[mesh.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]]]
    opp = mesh.points[mesh.cells[fs[:, 0][:, None], HEX_FACES[_OPPOSITE[fs[:, 1]]]]]
    h = np.linalg.norm(X.mean(1) - opp.mean(1), axis=1)
    return float(scale * factor * E / h.min())


def _num(x) -> str:
    """A number as CalculiX reads it (shortest round-trip repr of a Python float, at most 20 characters)."""
    return repr(float(x) + 0.0)


def _node_dofs(node: int, R: np.ndarray, held: list[int], values: np.ndarray, load: np.ndarray):
    """``*BOUNDARY``, ``*EQUATION`` and ``*CLOAD`` lines of one node's three DOFs (global components).

    The DOFs are held along the frame columns ``R[:, held]`` (e_j . u = value) and free along the
    others. The held rows are reduced to row echelon form with column pivoting: a row with one
    coefficient is a boundary condition, the others equations (first term the dependent DOF).
    The load vector (global) is put on the independent DOFs as the generalized force of equal
    virtual work: with u = R_F phi on the free directions F, c = R[ind, F]^-T (R_F^T load).
    """
    free = [j for j in range(3) if j not in held]
    rows = R[:, held].T
    bnd, eqs, cl = [], [], []
    if len(held):
        _, _, piv = sla.qr(rows, pivoting=True)
        dep = list(piv[: len(held)])
        C = np.linalg.solve(rows[:, dep], rows)
        v = np.linalg.solve(rows[:, dep], values)
        C[np.abs(C) < 1e-14] = 0.0
        for i, d in enumerate(dep):
            others = [(j, C[i, j]) for j in range(3) if j != d and C[i, j] != 0.0]
            if not others:
                bnd.append(f"{node}, {d + 1}, {d + 1}, {_num(v[i])}")
            elif v[i] != 0.0:
                raise InputError("rigid body", "prescribed motion along a tilted axis", "zero (not writable for CalculiX)")
            else:
                eqs.append(f"{1 + len(others)}\n{node}, {d + 1}, 1.\n" + "\n".join(f"{node}, {j + 1}, {_num(c)}" for j, c in others))
    else:
        dep = []
    ind = [j for j in range(3) if j not in dep]
    if free and np.any(load != 0.0):
        g = R[:, free].T @ load
        c = np.linalg.solve(R[np.ix_(ind, free)].T, g)
        cl = [f"{node}, {j + 1}, {_num(x)}" for j, x in zip(ind, c) if x != 0.0]
    return bnd, eqs, cl


def write_job(mesh: HexMesh, model: FEModel, path: str | Path, options: CcxOptions = CcxOptions(), *,
              penalty_scale: float = 1.0, closing_rotation: dict | None = None,
              title: str = "gearfe stress scene") -> CcxJob:
    """Write the complete CalculiX job of a contact model on a mesh (see module docstring).

    ``penalty_scale``: the scale of gearfe's penalty the solve reached. ``closing_rotation`` (body ->
    rotation [rad] about its axis, e.g. gearfe's solution): a first step prescribes it to close the
    contacts, the second releases it and applies the torque.
    """
    formulation, solver, c0, increment = options.formulation, options.solver, options.c0, options.increment
    if not (penalty_scale > 0 and np.isfinite(penalty_scale)):
        raise InputError("penalty_scale", penalty_scale, "a finite scale > 0")
    path = Path(path)
    element = ELEMENT_TYPES[model.solver.element]
    names = write_inp(mesh, path, element_type=element)  # nodes, elements, sets, surfaces; <BODY>_REF nodes
    refs = list(mesh.reference_points)
    n = mesh.n_points
    rigid, fixed, bnd, eqs, cload, mats, closing = [], [], [], [], [], {}, []
    closing_rotation = dict(closing_rotation or {})
    out = [f"** {title}", "** written by gearfe (pipelines.calculix.job); units mm, N, MPa"]
    for b in model.bodies:
        mats.setdefault(b.material, f"STEEL{len(mats) + 1}" if len(mats) else "STEEL")
        if b.loads:
            raise InputError(f"bodies[{b.name!r}].loads", b.loads, "no surface loads (not written for CalculiX)")
        for s in b.supports:
            nset = names[s.set] if s.set in names else None
            if nset is None:
                raise InputError(f"bodies[{b.name!r}].supports", s.set, "a node or face set of the mesh")
            if s.set in mesh.face_sets and s.set not in mesh.point_sets:
                raise InputError(f"bodies[{b.name!r}].supports", s.set, "a node set (face sets are not written as node sets)")
            if isinstance(s, Fixed):
                fixed.append((b.name, nset))
                bnd += [f"{nset}, {c + 1}, {c + 1}, 0." for c in s.components]
                continue
            assert isinstance(s, Rigid)
            if s.reference not in refs:
                raise InputError(f"bodies[{b.name!r}].supports.reference", s.reference, "a reference point of the mesh")
            i = refs.index(s.reference)
            ref_node, rot_node = n + 1 + i, n + 1 + len(refs) + len(rigid)
            rp = mesh.reference_points[s.reference]
            R = axis_frame(rp.axis)
            held = [j for j, d in enumerate(RIGID_DOFS) if d not in s.free]
            moment = np.asarray(s.moment, float) + s.torque * R[:, 2]
            for node, hj, vals, load in (
                    (ref_node, [j for j in held if j < 3], np.zeros(3), np.asarray(s.force, float)),
                    (rot_node, [j - 3 for j in held if j >= 3], np.array([0.0, 0.0, s.rotation]), moment)):
                bl, el, cl = _node_dofs(node, R, hj, vals[hj], load)
                bnd += bl
                eqs += el
                cload += cl
            if b.name in closing_rotation:
                if "rz" not in s.free or [j for j in held if j >= 3] != [3, 4]:
                    raise InputError("closing_rotation", b.name, "a rigid body whose only free rotation is about its axis")
                ind = [ln for ln in _node_dofs(rot_node, R, [0, 1], np.zeros(2), R[:, 2])[2]]
                # the independent DOF j of the rotation node: theta_j = e3_j phi
                j = int(ind[0].split(",")[1]) - 1
                closing.append(f"{rot_node}, {j + 1}, {j + 1}, {_num(R[j, 2] * closing_rotation[b.name])}")
            ref_set = abaqus_name(s.reference) + "_REF"
            rigid.append(CcxRigid(b.name, ref_node, rot_node, nset, ref_set, abaqus_name(s.reference) + "_ROT"))
    # rotation nodes (their coordinates are not used by CalculiX): after the reference nodes
    out.append("*NODE")
    for r in rigid:
        out.append(f"{r.rot_node}, " + ", ".join(_num(x) for x in mesh.reference_points[refs[r.ref_node - n - 1]].point))
    for r in rigid:
        out += [f"*NSET, NSET={r.rot_set}", f"{r.rot_node}"]
    for mat, mname in mats.items():
        out += [f"*MATERIAL, NAME={mname}", "*ELASTIC", f"{_num(mat.E)}, {_num(mat.nu)}"]
    for b in model.bodies:
        out.append(f"*SOLID SECTION, ELSET={names[b.name]}, MATERIAL={mats[b.material]}")
    for r in rigid:
        out.append(f"*RIGID BODY, NSET={r.nset}, REF NODE={r.ref_node}, ROT NODE={r.rot_node}")
    if eqs:
        out.append("*EQUATION")
        out += eqs
    E_min = min(b.material.E for b in model.bodies)
    pairs = []
    for k, cp in enumerate(model.contacts):
        K = pair_penalty(mesh, cp.slave, E_min, model.contact.penalty_factor, penalty_scale)
        inter = f"CONTACT{k + 1}"
        pairs.append(CcxPair(cp.name, cp.group, names[cp.slave], names[cp.master], names[cp.slave], K))
        out += [f"*SURFACE INTERACTION, NAME={inter}", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
                # slope K, tension at large clearances sigma_inf (node-to-surface only; 0.1 MPa, negligible
                # against GPa contact pressures), c0 default
                f"{_num(K)}, 0.1, {_num(c0)}" if formulation == "node" else _num(K),
                f"*CONTACT PAIR, INTERACTION={inter}, TYPE={FORMULATIONS[formulation]}",
                f"{names[cp.slave]}, {names[cp.master]}"]
    static = [f"*STATIC, SOLVER={solver}", f"{_num(increment)}, 1.0, {_num(increment * 1e-3)}, {_num(increment)}"]
    if closing:
        out += ["** step 1: the rigid bodies turned by closing_rotation, to close the contacts (no output)",
                "*STEP, INC=200"] + static + ["*BOUNDARY"] + bnd + closing + ["*NODE FILE, FREQUENCY=0", "*EL FILE, FREQUENCY=0",
                                                                           "*CONTACT FILE, FREQUENCY=0", "*END STEP"]
        out += ["** step 2: rotations released, torque applied", "*STEP, INC=200"] + static + ["*BOUNDARY, OP=NEW"] + bnd
    else:
        out += ["*STEP, INC=200"] + static + ["*BOUNDARY"] + bnd
    if cload:
        out += ["*CLOAD"] + cload
    out += ["*NODE FILE", "U, RF", "*EL FILE", "S", "*CONTACT FILE", "CDIS, CSTR"]
    for _, nset in fixed:
        out += [f"*NODE PRINT, NSET={nset}, TOTALS=ONLY", "RF"]
    for r in rigid:
        out += [f"*NODE PRINT, NSET={r.ref_set}", "RF", f"*NODE PRINT, NSET={r.rot_set}", "RF"]
    for p in pairs:  # total force, normal force and area of each pair's slave surface
        out += [f"*CONTACT PRINT, SLAVE={p.slave}, MASTER={p.master}, TOTALS=ONLY", "CF"]
    out.append("*END STEP")
    with open(path, "a") as fh:
        fh.write("\n".join(out) + "\n")
    return CcxJob(path, element, formulation, n, tuple(rigid), tuple(pairs), tuple(fixed), names)


def ccx_path() -> str:
    """The ``ccx`` executable, or an InputError naming the install command."""
    exe = shutil.which("ccx")
    if exe is None:
        raise InputError("ccx", "not found on PATH", f"CalculiX installed ({CCX_INSTALL})")
    return exe


@dataclass(frozen=True)
class CcxRun:
    """A finished ccx run: wall time [s], peak memory of the ccx process [MB], exit status, log tail."""

    wall_s: float
    peak_mb: float
    returncode: int
    log: str


PROGRESS_S = 10.0  # [s] between progress calls while ccx runs
MAX_TIMEOUT_S = 1e6  # [s] the largest time limit of a ccx run (11.6 days)


def check_timeout(timeout: float, key: str = "--timeout") -> float:
    """A time limit of a ccx run in (0, MAX_TIMEOUT_S] s (NaN, infinite, zero and negative refused)."""
    if not (isinstance(timeout, (int, float)) and math.isfinite(timeout) and 0 < timeout <= MAX_TIMEOUT_S):
        raise InputError(key, timeout, f"a time limit in (0, {MAX_TIMEOUT_S:g}] s")
    return float(timeout)


def _stop(proc: subprocess.Popen, grace: float = 5.0) -> None:
    """SIGTERM to ccx, SIGKILL after ``grace`` s, and reap it: no ccx is left running after gearfe."""
    if proc.poll() is not None:
        return
    try:
        proc.terminate()
        proc.wait(grace)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
    except ProcessLookupError:
        pass


@contextmanager
def _signals_held():
    """SIGINT / SIGTERM that arrive while ccx is being started are recorded, not raised (yields the list).

    Raised inside ``subprocess.Popen`` (after the fork) or before the caller's ``try``, they would leave a
    ccx running that nobody stops; the caller raises them again once ``proc`` is under its ``try``. Python
    handlers only (the main thread): the OS signal mask, which ccx would inherit, is not touched."""
    held: list[int] = []
    old = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            old[sig] = signal.signal(sig, lambda signum, frame: held.append(signum))
        except ValueError:  # not the main thread: signals are not delivered here anyway
            break
    try:
        yield held
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)


def run_ccx(job: str | Path, threads: int = 1, timeout: float = 3600.0, progress=None) -> CcxRun:
    """Run ``ccx -i <job>`` in the job's folder (log in ``<job>.log``); raise GearfeError when it fails.

    The peak memory is the ccx process's own high-water mark of resident memory (``/proc/<pid>/status``
    VmHWM, polled every 0.05 s), not the Python process's. ``progress(wall_s, peak_mb)`` is called every
    :data:`PROGRESS_S` s while ccx runs (it may raise to stop the run: a signal). Whatever ends the wait
    (the time limit, SIGINT or SIGTERM raised in the main thread, any exception), ccx is stopped and reaped
    before the exception goes on.
    """
    timeout = check_timeout(timeout, "timeout")
    exe = ccx_path()
    job = Path(job)
    env = {**os.environ, "OMP_NUM_THREADS": str(threads), "CCX_NPROC_EQUATION_SOLVER": str(threads)}
    logfile = job.with_suffix(".log")
    t0 = time.perf_counter()
    with open(logfile, "w") as fh:
        proc = None
        peak_kb = 0
        next_report = PROGRESS_S
        try:
            with _signals_held() as held:
                proc = subprocess.Popen([exe, "-i", job.stem], cwd=job.parent, stdout=fh, stderr=subprocess.STDOUT,
                                        env=env)
            for sig in held:  # a signal of the start-up: now ccx is stopped below
                signal.raise_signal(sig)
            while True:
                pid, status, ru = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    proc.returncode = os.waitstatus_to_exitcode(status)
                    break
                peak_kb = max(peak_kb, _hwm_kb(proc.pid))
                wall = time.perf_counter() - t0
                if wall > timeout:
                    raise GearfeError(f"ccx: {job.name} did not finish within {timeout:g} s")
                if progress is not None and wall >= next_report:
                    next_report += PROGRESS_S
                    progress(wall, peak_kb / 1024.0)
                time.sleep(0.05)
        except BaseException:
            if proc is not None:
                _stop(proc)
            raise
    wall = time.perf_counter() - t0
    log = logfile.read_text(errors="replace")
    tail = "\n".join(log.splitlines()[-30:])
    if proc.returncode != 0 or "Job finished" not in log:
        errs = " | ".join(line.strip() for line in log.splitlines() if "ERROR" in line.upper())[:500]
        raise GearfeError(f"ccx: {job.name} failed (exit status {proc.returncode}): {errs or tail[-300:]}")
    return CcxRun(wall, peak_kb / 1024.0, proc.returncode, tail)


def _hwm_kb(pid: int) -> int:
    """Peak resident memory (VmHWM) of a running process [kB]; 0 once it has gone.

    Polled because the child's rusage counts the parent's pages it shared before exec."""
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0
