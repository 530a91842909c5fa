"""Condensed compliance of a body held on some nodes: responses to many unit loads from one factorization.

For a linear-elastic body with stiffness K (3n, 3n, DOFs interleaved per node) held at zero on
the DOFs ``fixed``, unit loads are the columns of a load matrix P (3n, m) and responses are read by
an observation matrix Q (k, 3n). The condensed (influence-coefficient) matrix is

    C = Q K_ff^-1 P_f        [mm/N]

(Maxwell–Betti: C is symmetric when Q = P^T). K_ff is factored once (PARDISO, or SuperLU as the
fallback of :mod:`fem.la.linsolve`) and solved for the m right-hand sides in blocks, so the cost is
one factorization plus m forward/backward substitutions; no dense (3n)² matrix is formed.
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp

from fem.la.linsolve import choose_solver, schur_system

__all__ = ["influence_matrix"]


def influence_matrix(K: sp.spmatrix, fixed: np.ndarray, P: sp.spmatrix, Q: sp.spmatrix, method: str = "auto",
                     block: int = 128) -> tuple[np.ndarray, dict]:
    """C = Q K_ff^-1 P (k, m) [mm/N] for K held on the boolean DOF mask ``fixed``; timing info."""
    t0 = time.perf_counter()
    free = np.flatnonzero(~np.asarray(fixed, bool))
    K = sp.csr_matrix(K)
    Kff = K[free][:, free].tocsr()
    Pf = sp.csc_matrix(P)[free]
    Qf = sp.csr_matrix(Q)[:, free]
    method = choose_solver(method)
    m = P.shape[1]
    C = np.empty((Q.shape[0], m))
    if method == "pardiso":
        from fem.la import pardiso

        fac = pardiso.Pardiso(Kff, None, mtype=2)
        t1 = time.perf_counter()
        for s in range(0, m, block):
            X = fac.solve(Pf[:, s:s + block].toarray())
            C[:, s:s + block] = Qf @ X
        fac.free()
    else:
        sysm = schur_system(Kff, np.zeros(0, np.int64), method)
        t1 = time.perf_counter()
        for s in range(0, m, block):
            B = Pf[:, s:s + block].toarray()
            X = np.column_stack([sysm.solve(B[:, j], lambda fc: fc) for j in range(B.shape[1])])
            C[:, s:s + block] = Qf @ X
    return C, {"method": method, "dofs": len(free), "factor_s": t1 - t0, "solves_s": time.perf_counter() - t1,
               "loads": m}
