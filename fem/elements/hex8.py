"""Element stiffness of 8-node hexahedra, plain (C3D8) or with incompatible modes (C3D8I-like).

Quadrature from scikit-fem (``intorder=3``: 2x2x2 Gauss points on the reference cube [0, 1]^3). The
geometry is computed here for all cells at once: the trilinear map's Jacobian J = sum_a x_a (dN_a/dxi)^T
(one matrix product over the cells), its inverse by cofactors, gradients dN_a/dx = J^-T dN_a/dxi; equal
to scikit-fem's ``Basis(mesh, ElementHex1(), intorder=3)`` to 2e-14 and 3x cheaper (no mapping objects).
The stiffness is computed by batched numpy kernels.

Isotropic stiffness. With shape-function gradients g_a (at a quadrature point, weight dx),

    K[(a,i),(b,j)] = sum_q dx ( lambda g_ai g_bj + mu g_aj g_bi + mu delta_ij g_a . g_b ),

which is B^T D B with D = lambda 1 1^T + mu diag(2, 2, 2, 1, 1, 1) (Voigt strains, engineering
shears). ``isotropic_stiffness`` evaluates it for any set of functions (nodal or not) as one batched
product per element, K = R^T R, where R stacks, at each Gauss point q, the 7 rows

    sqrt(lambda dx) (div),  sqrt(2 mu dx) (eps_xx, eps_yy, eps_zz),  sqrt(mu dx) (gam_xy, gam_yz, gam_xz)

of the strain operator on the interleaved DOFs (7 q x 3 nf): one BLAS product of (3nf x 7q)(7q x 3nf)
per element, with no strided permutations of the (3nf)^2 entries (3x faster than the split form
above, which it equals to round-off).

Incompatible modes (Wilson, Taylor, Beresford & Wilson 1976, "QM6"). The displacement of each
element is enriched by three bubble modes per component,

    u = sum_a N_a u_a + sum_k P_k(xi) alpha_k,   P_k = 1 - (2 xi_k - 1)^2,   k = 1, 2, 3,

which lets the element bend without parasitic shear. Their gradients use Taylor's correction,

    grad P_k (xi) = det J0 / det J(xi) * J0^-T  dP_k/dxi,

J0 the Jacobian at the element centre, so that  int grad P_k dV = det J0 J0^-T int dP_k/dxi = 0:
a constant strain field produces no work on the modes and the element passes the patch test on
distorted meshes. The 9 mode amplitudes are internal; they are condensed element by element
(batched 9x9 solves):

    K = K_uu - K_ua K_aa^-1 K_au,   alpha = -K_aa^-1 K_au u_e = -X u_e,

and X is kept to recover stresses with the modes included (``fem.recovery``).

Local node order is VTK's (= C3D8's), DOFs interleaved per node: (u_x, u_y, u_z) of node 0, ...
"""

from __future__ import annotations

import contextlib
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from fem.errors import FEInputError

__all__ = [
    "SKFEM_FROM_VTK",
    "HexGeometry",
    "hex_geometry",
    "isotropic_stiffness",
    "ElementMatrices",
    "hex8_matrices",
    "Hex8Job",
    "kernel_threads",
    "run_chunks",
]

# scikit-fem local node k of ElementHex1 sits at reference point doflocs[k]; VTK node P[k] sits there.
SKFEM_FROM_VTK = np.array([6, 2, 5, 7, 1, 3, 4, 0])
_VTK_FROM_SKFEM = np.argsort(SKFEM_FROM_VTK)
# VTK reference coordinates of the 8 nodes in [0, 1]^3
VTK_REF_NODES = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float
)


@dataclass(frozen=True, eq=False)
class HexGeometry:
    """Gradients at Gauss points of the 8 nodal (+ 3 incompatible) functions, and volume weights."""

    grads: np.ndarray  # (m, q, nf, 3) [1/mm], nodal functions in VTK order, then modes
    dx: np.ndarray  # (m, q) [mm^3] quadrature weight x det J
    xq: np.ndarray  # (3, q) reference coordinates of the Gauss points in [0, 1]^3


def _quadrature():
    """Gauss points (3, 8) in [0, 1]^3 and weights (8,) of scikit-fem's ``intorder=3`` on the reference hexahedron."""
    # the Gauss points and weights scikit-fem uses for intorder=3 on the reference cube (the same order)
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefHex
    X, W = get_quadrature(RefHex, 3)
    return np.asarray(X, float), np.asarray(W, float)

_XQ, _WQ = _quadrature()

def _ref_grads(xi):
    """dN_a/dxi_k (q, 8, 3) of the VTK-ordered trilinear functions at reference points xi (3, q)."""
    R = VTK_REF_NODES  # (8, 3)
    f = np.where(R[None, :, :] == 1.0, xi.T[:, None, :], 1.0 - xi.T[:, None, :])  # (q, 8, 3) factor per direction
    s = np.where(R == 1.0, 1.0, -1.0)  # d factor / d xi
    g = np.empty((xi.shape[1], 8, 3))
    g[..., 0] = s[None, :, 0] * f[..., 1] * f[..., 2]
    g[..., 1] = f[..., 0] * s[None, :, 1] * f[..., 2]
    g[..., 2] = f[..., 0] * f[..., 1] * s[None, :, 2]
    return g

def _inv3(J):
    """Inverse and determinant of (..., 3, 3) matrices (cofactors)."""
    a, b, c = J[..., 0, 0], J[..., 0, 1], J[..., 0, 2]
    d, e, f = J[..., 1, 0], J[..., 1, 1], J[..., 1, 2]
    g, h, i = J[..., 2, 0], J[..., 2, 1], J[..., 2, 2]
    A, B, C = e * i - f * h, f * g - d * i, d * h - e * g
    det = a * A + b * B + c * C
    inv = np.empty_like(J)
    inv[..., 0, 0], inv[..., 0, 1], inv[..., 0, 2] = A, c * h - b * i, b * f - c * e
    inv[..., 1, 0], inv[..., 1, 1], inv[..., 1, 2] = B, a * i - c * g, c * d - a * f
    inv[..., 2, 0], inv[..., 2, 1], inv[..., 2, 2] = C, b * g - a * h, a * e - b * d
    return inv / det[..., None, None], det

def _geometry(X: np.ndarray, incompatible: bool):
    """Gradients (m, q, nf, 3) and det J (m, q) of the hexahedra with node coordinates X (m, 8, 3)."""
    dN = _ref_grads(_XQ)  # (q, 8, 3)
    m = len(X)
    # J[m, q, i, k] = sum_a X[m, a, i] dN[q, a, k]: one matrix product (3m, 8) (8, 3q)
    J = (X.transpose(0, 2, 1).reshape(-1, 8) @ dN.transpose(1, 0, 2).reshape(8, -1))
    J = J.reshape(m, 3, -1, 3).transpose(0, 2, 1, 3)
    inv, det = _inv3(J)  # inv[k, i] = dxi_k/dx_i
    q = det.shape[1]
    nf = 11 if incompatible else 8
    g = np.empty((m, q, nf, 3))
    g[:, :, :8, :] = np.matmul(dN[None], inv)
    if incompatible:
        J0 = np.einsum("mai,ak->mik", X, _ref_grads(np.full((3, 1), 0.5))[0])  # (m, i, k)
        inv0, det0 = _inv3(J0)
        dP = -4.0 * (2.0 * _XQ - 1.0)  # (3, q)
        ratio = det0[:, None] / det
        for k in range(3):
            g[:, :, 8 + k, :] = (ratio[:, :, None] * dP[k][None, :, None]) * inv0[:, None, k, :]
    return g, det


def _first_inverted(det: np.ndarray) -> int | None:
    """Index of the first cell with det J <= 0 at a Gauss point (det (m, q)), None when there is none."""
    bad = np.flatnonzero((det <= 0.0).any(axis=1))
    return int(bad[0]) if len(bad) else None


def _inverted(cell: int) -> FEInputError:
    return FEInputError("mesh.cells", cell, "the index of a hexahedron with det J > 0 at all Gauss points (VTK node order)",
                        "this cell is inverted or degenerate")


def hex_geometry(points: np.ndarray, cells: np.ndarray, incompatible: bool) -> HexGeometry:
    """Gauss-point gradients (2x2x2) of VTK-ordered hexahedra, with the Taylor-corrected modes (module docstring)."""
    g, det = _geometry(points[cells], incompatible)
    bad = _first_inverted(det)
    if bad is not None:
        raise _inverted(bad)
    return HexGeometry(grads=g, dx=np.abs(det) * _WQ[None, :], xq=_XQ)


def isotropic_stiffness(grads: np.ndarray, dx: np.ndarray, lam: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """Element stiffness (m, 3nf, 3nf) [N/mm], DOFs interleaved; lam, mu (m,) [MPa] (K = R^T R, module docstring)."""
    m, q, nf, _ = grads.shape
    g = grads * np.sqrt(dx)[:, :, None, None]  # (m, q, nf, 3)
    sl = np.sqrt(lam)[:, None, None]
    s2 = np.sqrt(2.0 * mu)[:, None, None]
    sm = np.sqrt(mu)[:, None, None]
    R = np.zeros((m, q, 7, nf, 3))
    R[:, :, 0] = sl[..., None] * g  # divergence
    for i in range(3):  # normal strains
        R[:, :, 1 + i, :, i] = s2 * g[:, :, :, i]
    for r, (i, j) in enumerate(((0, 1), (1, 2), (0, 2))):  # engineering shears
        R[:, :, 4 + r, :, i] = sm * g[:, :, :, j]
        R[:, :, 4 + r, :, j] = sm * g[:, :, :, i]
    R = R.reshape(m, 7 * q, 3 * nf)
    return np.matmul(R.transpose(0, 2, 1), R)


@dataclass(frozen=True, eq=False)
class ElementMatrices:
    """Condensed element stiffness (m, 24, 24) and mode recovery X (m, 9, 24) or None."""

    stiffness: np.ndarray
    condensation: np.ndarray | None
    geometry: HexGeometry


def _one_blas_thread():
    """A context holding BLAS to one thread (threadpoolctl), or nothing when threadpoolctl is absent."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # pragma: no cover - optional dependency
        return contextlib.nullcontext()
    return threadpool_limits(1, user_api="blas")


def kernel_threads() -> int:
    """Threads for the chunked element kernels: the BLAS thread limit in force (threadpoolctl), at most the cores."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    try:
        from threadpoolctl import threadpool_info
    except ImportError:  # pragma: no cover - optional dependency
        return cores
    limits = [int(i["num_threads"]) for i in threadpool_info() if i.get("user_api") == "blas"]
    return max(1, min([cores, *limits]))


def run_chunks(run, m: int, chunk: int, threads: int | None = None) -> None:
    """Call ``run(start)`` for start = 0, chunk, 2 chunk, ... < m on ``threads`` threads (default
    :func:`kernel_threads`). The chunks are the parallelism: BLAS is held to one thread meanwhile (a BLAS team per
    small product only waits). Each ``run`` must write only its own rows, so the result does not depend on the
    threads."""
    starts = range(0, m, chunk)
    threads = kernel_threads() if threads is None else int(threads)
    with _one_blas_thread():
        if threads > 1 and len(starts) > 1:
            with ThreadPoolExecutor(max_workers=threads) as pool:
                list(pool.map(run, starts))
        else:
            for s in starts:
                run(s)


class _Hex8Chunks:
    """The outputs of :func:`hex8_matrices` and the work of one chunk of cells (``run``, which writes only its own
    rows); ``result`` checks for inverted cells once every chunk has run."""

    def __init__(self, points, cells, lam, mu, incompatible: bool, chunk: int):
        self.points, self.cells, self.lam, self.mu = points, cells, lam, mu
        self.incompatible, self.chunk = incompatible, chunk
        self.m = m = len(cells)
        nf = 11 if incompatible else 8
        self.grads = np.empty((m, len(_WQ), nf, 3))
        self.dx = np.empty((m, len(_WQ)))
        self.Ke = np.empty((m, 24, 24))
        self.X = np.empty((m, 9, 24)) if incompatible else None
        self.bad: list[int] = []

    def run(self, s: int) -> None:
        sl = slice(s, min(s + self.chunk, self.m))
        g, det = _geometry(self.points[self.cells[sl]], self.incompatible)
        first = _first_inverted(det)
        if first is not None:
            self.bad.append(s + first)
            return
        self.grads[sl], self.dx[sl] = g, det * _WQ[None, :]
        K = isotropic_stiffness(g, self.dx[sl], self.lam[sl], self.mu[sl])
        if self.incompatible:
            Kaa, Kau = K[:, 24:, 24:], K[:, 24:, :24]
            Xs = np.linalg.solve(Kaa, Kau)
            Kc = K[:, :24, :24] - np.matmul(K[:, :24, 24:], Xs)
            self.Ke[sl] = 0.5 * (Kc + Kc.transpose(0, 2, 1))  # symmetric to round-off; exactly, per chunk in cache
            self.X[sl] = Xs
        else:
            self.Ke[sl] = K  # R^T R: exactly symmetric

    def result(self) -> ElementMatrices:
        if self.bad:
            raise _inverted(min(self.bad))
        geo = HexGeometry(grads=self.grads, dx=self.dx, xq=_XQ)
        return ElementMatrices(stiffness=self.Ke, condensation=self.X, geometry=geo)


def hex8_matrices(points, cells, lam, mu, incompatible: bool = True, chunk: int = 1000,
                  threads: int | None = None) -> ElementMatrices:
    """Stiffness of all cells (C3D8 or C3D8I-like with condensed modes), chunked to bound memory.

    The chunks are independent (each computes its cells' geometry and writes its own rows of the outputs) and
    numpy releases the GIL in their batched products and solves, so they run on ``threads`` threads (default
    ``kernel_threads()``); the result does not depend on the number of threads (same chunks, same operations)."""
    work = _Hex8Chunks(points, cells, lam, mu, incompatible, chunk)
    run_chunks(work.run, work.m, chunk, threads)
    return work.result()


class Hex8Job:
    """:func:`hex8_matrices` started on one background thread; :meth:`result` joins in from the calling thread (both
    then take the remaining chunks, one at a time) and returns the same matrices (same chunks, same operations).

    For a caller with other work first: the element matrices use the core it leaves free, then both. BLAS is held
    to one thread from the start to :meth:`result` or :meth:`cancel` (one process-wide limit, entered and left on
    the calling thread); call one of them in a ``finally``."""

    def __init__(self, points, cells, lam, mu, incompatible: bool = True, chunk: int = 1000):
        self._work = _Hex8Chunks(points, cells, lam, mu, incompatible, chunk)
        self._next = iter(range(0, self._work.m, chunk))
        self._lock = threading.Lock()
        self._error: BaseException | None = None
        self._limit = _one_blas_thread()
        self._limit.__enter__()
        self._thread = threading.Thread(target=self._take, name="hex8", daemon=True)
        self._thread.start()

    def _take(self) -> None:
        try:
            while True:
                with self._lock:
                    s = next(self._next, None)
                if s is None or self._error is not None:
                    return
                self._work.run(s)
        except BaseException as exc:  # re-raised by result()
            self._error = exc

    def _finish(self) -> None:
        if self._thread is not None:
            self._thread.join()
            self._thread = None
            self._limit.__exit__(None, None, None)

    def result(self) -> ElementMatrices:
        """Take chunks on this thread too until none is left, wait for the background thread; the matrices."""
        self._take()
        self._finish()
        if self._error is not None:
            raise self._error
        return self._work.result()

    def cancel(self) -> None:
        """Hand out no more chunks; wait for the one running."""
        with self._lock:
            self._next = iter(())
        self._finish()


