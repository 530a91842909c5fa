"""``solve(mesh, model)``: linear elasticity with rigid ties and penalty contact.

Steps (timings reported in ``FEResult.info.timings``):

1. element stiffness (C3D8I-like or C3D8) and block assembly of K (``fem.elements.hex8``, ``fem.assembly``);
2. supports by elimination, K_r = T^T K T, f_r = T^T (f - K u_p) + f_ref (``fem.constraints``);
3. contact geometry from the undeformed mesh; candidate slave nodes g0 < search_gap, and the
   seed (``fem.contact.search``);
4. the reduced stiffness is bordered by the gap rows of the k candidate nodes,

       A = [K_r  G_r^T]      (symmetric indefinite; unknowns (q, mu), mu = -lambda),
           [G_r    0  ]

   and factored once with the Schur complement on C = (free rigid DOFs, gap rows) (PARDISO factors only
   A_RR, the reduced stiffness with the free rigid DOFs clamped, which is positive definite: Cholesky):
   S = [[H, -B^T], [-B, -W]] in the notation of ``fem.contact.active_set``, and the forward substitution
   gives f^_F and the gaps g^ of the load with the free rigid DOFs clamped. The active-set
   penalty problem is solved on these k + n_F unknowns by dense algebra, and one backward
   substitution gives all DOFs (``fem.la.linsolve``): no refactorization per contact iteration;
5. checks: no slave node outside the candidate set penetrates; every Newton-like loop converged;
6. stresses by Gauss-point extrapolation and nodal averaging (``fem.recovery``); reactions.

Order of the work (with PARDISO and more than one kernel thread allowed; otherwise steps 1-4 in turn). The
pattern of A's upper triangle follows from the connectivity, the supports and the contact set alone
(``fem.bordered``: K_r's free block is a selection of K, its rigid columns and G_r^T are small). It is built first
while the element matrices are computed on a background thread (``fem.elements.hex8.Hex8Job``); PARDISO's
symbolic analysis of the pattern (ordering, one core) then runs on a thread while the assembly's scatter is built,
this thread joins the element matrices' chunks, and K and A's values (gathered from K) are made; the numeric
factorization takes those values on the analysed pattern.
Timings: ``contact_setup_s`` the patterns and contact set, ``assembly_s`` the scatter, the wait for the element
matrices and K, ``reduction_s`` A's values, ``analysis_s`` the symbolic analysis (overlapped with the two before),
``factor_s`` the wait for it and the numeric factorization.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from fem.mesh.hexmesh import HexMesh
from fem.errors import FEConvergenceError, FEInputError

from fem import recovery as st
from fem.assembly import block_assembly, block_pattern, surface_load
from fem.bordered import bordered_layout
from fem.constraints import known_names, reduction
from fem.contact.active_set import ReducedContact, penalty_active_set
from fem.contact.patch import contact_patch
from fem.contact.search import ContactSet, contact_set
from fem.elements.hex8 import ElementMatrices, Hex8Job, hex8_matrices, kernel_threads
from fem.la.linsolve import SchurSystem, choose_solver, schur_analysis, schur_system
from fem.model import FEModel
from fem.result import FEResult, PairResult, SolveInfo

__all__ = ["solve"]


def _cell_materials(mesh: HexMesh, model: FEModel):
    lam = np.empty(mesh.n_cells)
    mu = np.empty(mesh.n_cells)
    E = np.empty(mesh.n_cells)
    for b in model.bodies:
        if b.name not in mesh.bodies:
            raise FEInputError("bodies.name", b.name, "a body of the mesh (" + ", ".join(mesh.bodies) + ")")
        c = mesh.body_cells(b.name)
        lam[c], mu[c], E[c] = b.material.lam, b.material.mu, b.material.E
    return lam, mu, E


def _external_load(mesh: HexMesh, model: FEModel) -> np.ndarray:
    f = np.zeros(3 * mesh.n_points)
    for b in model.bodies:
        for i, load in enumerate(b.loads):
            if load.set not in mesh.face_sets:
                raise FEInputError(f"bodies[{b.name!r}].loads[{i}].set", load.set, f"a face set of the mesh ({known_names(mesh.face_sets)})")
            nodes, forces = surface_load(mesh.points, mesh.face_nodes(load.set), load.traction)
            for c in range(3):
                f[c::3] += np.bincount(nodes, weights=forces[:, c], minlength=mesh.n_points)
    return f


def _closed_area(cs, sel, gap, sol) -> float:
    """Area of the Gauss points of a pair whose gap is closed to within the solution's largest penetration [mm^2]."""
    tol = float(np.max(-sol.gap[sol.active], initial=0.0)) if sol is not None else 0.0
    return float(cs.area[sel][gap[sel] <= tol].sum())


def _contact(mesh: HexMesh, model: FEModel, red, Tt: sp.csr_matrix, E_c: np.ndarray):
    """What follows from the mesh and supports alone for the contact (steps 3 and 4 without values): the contact
    set and its candidates, the Schur rows C (free rigid DOFs, then the gap rows) and G_r^T; Tt = T^T as CSR."""
    cs = contact_set(mesh, model.contacts, E_c, model.contact.penalty_factor, model.contact.quadrature,
                     model.contact.points) if model.contacts else None
    cand = np.flatnonzero(cs.candidate) if cs is not None else np.zeros(0, np.int64)
    GrT = None
    if len(cand):
        GrT = (Tt @ cs.G[cand].T).tocsr()
        GrT.sort_indices()
    C = np.concatenate([red.free_rigid, red.n + np.arange(len(cand))])
    return cs, cand, C, GrT


@dataclass(frozen=True, eq=False)
class _Factored:
    """Steps 1-4 up to the factorization: element matrices, K, the reduced system, the contact set and its candidates,
    the Schur rows C and the factored bordered matrix."""

    em: ElementMatrices
    K: sp.csr_matrix
    f: np.ndarray
    kdiag: np.ndarray  # K_r's diagonal at the free rigid DOFs
    fr: np.ndarray
    cs: ContactSet | None
    cand: np.ndarray
    C: np.ndarray
    sysm: SchurSystem


def _factored(mesh: HexMesh, model: FEModel, red, materials, t: dict) -> _Factored:
    """Steps 1-4 (module docstring, "Order of the work"); the overlap only with PARDISO and more than one kernel
    thread allowed (``fem.elements.hex8.kernel_threads``; under a limit of one, all in turn)."""
    lam_c, mu_c, E_c = materials
    t0 = time.perf_counter()
    method = choose_solver(model.solver.solver)
    overlap = method == "pardiso" and kernel_threads() > 1
    args = (mesh.points, mesh.cells, lam_c, mu_c, model.solver.element == "hex8i")
    Tt = red.T.T.tocsr()  # T^T as CSR, for G_r^T and f_r
    em_job = Hex8Job(*args) if overlap else None
    pending = None
    try:
        bp = block_pattern(mesh.cells, mesh.n_points)
        cs, cand, C, GrT = _contact(mesh, model, red, Tt, E_c)
        layout = bordered_layout(bp, red, GrT)
        if overlap:  # the symbolic analysis of A's pattern (one core) runs while the values are assembled
            pending = schur_analysis(layout.pattern, C, method, definite=True)
        t["contact_setup_s"] = time.perf_counter() - t0

        t1 = time.perf_counter()
        ba = block_assembly(mesh.cells, mesh.n_points, bp)
        em = em_job.result() if overlap else hex8_matrices(*args)
        K = ba.assemble(em.stiffness)
        del ba
        f = _external_load(mesh, model)
        t["assembly_s"] = time.perf_counter() - t1

        t1 = time.perf_counter()
        fr = Tt @ (f - K @ red.u_prescribed) + red.f_ref
        A = layout.values(K)
        del layout
        t["reduction_s"] = time.perf_counter() - t1

        t1 = time.perf_counter()
        # only A_RR = K_r without the free rigid DOFs is factored: SPD (every body held), so Cholesky applies;
        # the gap rows' zero diagonal lies in the Schur block C (mtype 2 instead of -2: 2-11 % less factor CPU
        # time on the twin)
        sysm = pending.factor(A) if overlap else schur_system(A, C, method, definite=True, upper=True)
        t["factor_s"] = time.perf_counter() - t1
        if overlap:
            t["analysis_s"] = pending.analysis_s
    finally:
        if em_job is not None:
            em_job.cancel()
        if pending is not None:
            pending.close()
    return _Factored(em, K, f, A.data[A.indptr[red.free_rigid]], fr, cs, cand, C, sysm)


def solve(mesh: HexMesh, model: FEModel) -> FEResult:
    """Solve the model on the mesh; raises FEInputError, FEConvergenceError or FEError."""
    t = {}
    t0 = time.perf_counter()
    lam_c, mu_c, E_c = _cell_materials(mesh, model)
    red = reduction(mesh, model)
    fa = _factored(mesh, model, red, (lam_c, mu_c, E_c), t)
    em, K, f, kdiag, fr, cs, cand, C, sysm = fa.em, fa.K, fa.f, fa.kdiag, fa.fr, fa.cs, fa.cand, fa.C, fa.sysm
    del fa
    k = len(cand)
    n_r = red.n
    F = red.free_rigid
    iF, ig = np.arange(len(F)), len(F) + np.arange(k)

    state = {}

    def solve_c(yC: np.ndarray) -> np.ndarray:
        tc = time.perf_counter()
        S = sysm.schur
        W = -S[np.ix_(ig, ig)]
        B = -S[np.ix_(ig, iF)]
        H = S[np.ix_(iF, iF)]
        g_p = cs.gap0[cand] + cs.G[cand] @ red.u_prescribed if k else np.zeros(0)
        ghat = g_p - yC[ig]
        fhat = yC[iF]
        seed = cs.seed[cand] if k else np.zeros(0, bool)
        stiff = cs.stiffness[cand] if k else np.zeros(0)
        area = cs.area[cand] if k else np.zeros(0)
        peak = None
        if k and cs.mass is not None:  # Gauss-point constraints: check the recovered nodal peak

            def peak(lam_c):
                lam = np.zeros(len(cs.area))
                lam[cand] = lam_c
                return float(np.nanmax(cs.pressure(lam, mesh.n_points), initial=0.0))
        sol = penalty_active_set(ReducedContact(W, B, H, ghat, fhat, kdiag), stiff, area, seed, model.contact, peak)
        xC = np.empty(len(C))
        xC[iF] = sol.u_free
        xC[ig] = -sol.lam  # bordered unknowns are -lambda: K u + G^T (-lambda) = f
        state["sol"] = sol
        state["contact_s"] = time.perf_counter() - tc
        return xC

    t1 = time.perf_counter()
    q = sysm.solve(np.concatenate([fr, np.zeros(k)]), solve_c)[:n_r]
    t["solve_s"] = time.perf_counter() - t1
    t["contact_s"] = state.get("contact_s", 0.0)
    sol = state.get("sol")
    u = red.expand(q)
    uf = u.ravel()

    lam_all = np.zeros(len(cs.area)) if cs is not None else np.zeros(0)
    if cs is not None:
        lam_all[cand] = sol.lam
        gap_all = cs.gap0 + cs.G @ uf
        outside = ~cs.candidate & (gap_all < -model.contact.max_penetration)
        if outside.any():
            worst = int(np.argmin(np.where(outside, gap_all, np.inf)))
            pair = model.contacts[cs.pair[worst]]
            where = f"node {int(cs.node[worst])} outside the candidate set (raise search_gap = {pair.search_gap} mm)"
            raise FEConvergenceError(f"contact of pair {pair.name!r}", where, float(-gap_all[worst]), sol.iterations)

    t1 = time.perf_counter()
    sq = st.gauss_stress(em.geometry, mesh.cells, u, em.condensation, lam_c, mu_c)
    s_nodes = st.nodal_average(sq, em.geometry.xq, mesh.cells, mesh.n_points)
    vm = st.von_mises(s_nodes)
    pr = st.principal(s_nodes)
    t["recovery_s"] = time.perf_counter() - t1

    r = K @ uf - f
    pressure = np.zeros(mesh.n_points)
    force_nodes = np.zeros(mesh.n_points)
    gap_nodes = np.full(mesh.n_points, np.nan)
    pairs = []
    if cs is not None:
        r -= cs.G.T @ lam_all
        pressure = np.nan_to_num(cs.pressure(lam_all, mesh.n_points))
        force_nodes = cs.nodal_forces(lam_all, mesh.n_points)
        gap_nodes = cs.to_nodes(gap_all, mesh.n_points)
        for ip, pair in enumerate(model.contacts):
            sel = np.flatnonzero(cs.pair == ip)
            fv = np.asarray((cs.normal[sel] * lam_all[sel, None]).sum(axis=0))
            p_pair = np.nan_to_num(cs.pressure(lam_all, mesh.n_points, rows=sel))
            act = np.flatnonzero(p_pair > 0.0)  # slave nodes with pressure
            F_pair = cs.nodal_forces(lam_all, mesh.n_points, rows=sel)
            nrm = fv if np.linalg.norm(fv) > 0 else cs.normal[sel].sum(axis=0)
            patch = contact_patch(mesh.points[act], F_pair[act], nrm) if len(act) and np.linalg.norm(nrm) > 0 else None
            pairs.append(PairResult(pair.name, pair.group, float(lam_all[sel].sum()), tuple(float(x) for x in fv),
                                    _closed_area(cs, sel, gap_all, sol) if cs.mass is not None else
                                    float(cs.area[sel][lam_all[sel] > 0.0].sum()),  # tributary areas of the active nodes
                                    float(p_pair.max(initial=0.0)), len(act),
                                    int(cs.candidate[sel].sum()), patch.semi_axes if patch else (0.0, 0.0)))
    reaction = np.zeros((mesh.n_points, 3))
    held = np.unique(np.concatenate(list(red.support_nodes.values())))
    reaction[held] = r.reshape(-1, 3)[held]
    t["total_s"] = time.perf_counter() - t0
    info = SolveInfo(
        dofs=3 * mesh.n_points, reduced_dofs=red.n, schur_dofs=len(C), solver=sysm.method, element=model.solver.element,
        candidates=len(cand), active=(int(sol.active.sum()) if cs.mass is None else int(np.count_nonzero(pressure > 0)))
        if sol is not None else 0,
        iterations=sol.iterations if sol is not None else 0, penalty_scale=sol.scale if sol is not None else 1.0,
        penalty_change=sol.penalty_change if sol is not None else float("nan"),
        max_penetration=float(np.max(-sol.gap[sol.active], initial=0.0)) if sol is not None else 0.0,
        timings=t,
    )
    return FEResult(mesh, model, u, s_nodes, vm, pr, pressure, gap_nodes, tuple(pairs), reaction, red.rigid_motion(q), info,
                    force_nodes)
