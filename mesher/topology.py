"""Node numbering of a row of tooth sections: shared node rows, quadrilaterals and named edges.

Every transverse section of a member has the same topology (only positions change with z), so
the 3D mesh is the 2D quadrilateral mesh of a section extruded through the axial levels: node
``(level k, section node a)`` has index ``k * n_section + a`` and the hexahedron over quad q
between levels k and k+1 is cell ``k * n_quads + q``.

Blocks of a tooth are logical grids ``(n_i + 1, n_j + 1)`` (see :mod:`mesher.tooth`); node rows
shared by two blocks (base, split surface, mid-surface) or by two teeth (space-centre line) are
identified here, so conformity is by construction, never by matching coordinates.
Quad ``q = (i, j)`` of a block is ``(P[i,j], P[i+1,j], P[i+1,j+1], P[i,j+1])`` with edges
e0 (j side), e1 (i+1 side), e2 (j+1 side), e3 (i side); a block whose quads turn clockwise in
the section is reversed, which maps edge e to 3 - e. The hexahedron's lateral face over edge e is
local face 2 + e (VTK/C3D8 order, :data:`fem.mesh.hexmesh.HEX_FACES`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from mesher.tooth import BLOCKS, ToothPlan

__all__ = ["SectionTopology"]


@dataclass(frozen=True, eq=False)
class SectionTopology:
    """Section node ids of every (tooth, block), the quads and the named boundary edges."""

    ids: dict  # (tooth position t, block) -> (ni+1, nj+1) int array
    n_nodes: int
    quads: np.ndarray  # (nq, 4), orientation fixed later by `orient`
    quad_block: dict  # (t, block) -> slice of quads

    @classmethod
    def build(cls, plans: list[ToothPlan], n_rim: int, closed: bool = False):
        """Topology of teeth t = 0..len(plans)-1 side by side (closed: the last meets the first)."""
        counter = 0
        raw = {}
        for t, p in enumerate(plans):
            for b in BLOCKS:
                ni, nj = p.shape(b, n_rim)
                raw[(t, b)] = np.arange(counter, counter + (ni + 1) * (nj + 1)).reshape(ni + 1, nj + 1)
                counter += (ni + 1) * (nj + 1)
        pairs = []

        def same(a, b):
            a, b = np.asarray(a).ravel(), np.asarray(b).ravel()
            assert a.shape == b.shape
            pairs.append(np.stack([a, b]))

        T = len(plans)
        for t in range(T):
            r = {b: raw[(t, b)] for b in BLOCKS}
            same(r["A+"][:, 0], r["A-"][:, 0])  # mid-surface
            same(r["B+"][:, 0], r["B-"][:, 0])
            same(r["C+"][:, 0], r["C-"][:, 0])
            for s in "+-":
                same(r["A" + s][0, :], r["B" + s][0, :])  # base
                same(r["B" + s][-1, :], r["C" + s][0, :])  # split surface
            nxt = t + 1 if t + 1 < T else (0 if closed else None)
            if nxt is not None:  # space-centre line shared with the next tooth
                same(r["C+"][:, -1], raw[(nxt, "C-")][:, -1])
        P = np.concatenate(pairs, axis=1) if pairs else np.zeros((2, 0), int)
        g = coo_matrix((np.ones(P.shape[1]), (P[0], P[1])), shape=(counter, counter))
        _, lab = connected_components(g, directed=False)
        _, first = np.unique(lab, return_index=True)
        order = np.argsort(first)  # labels in order of first appearance
        relabel = np.empty(len(order), np.int64)
        relabel[order] = np.arange(len(order))
        new = relabel[lab]
        ids = {k: new[v] for k, v in raw.items()}
        quads, qb, q0 = [], {}, 0
        for t in range(T):
            for b in BLOCKS:
                G = ids[(t, b)]
                q = np.stack([G[:-1, :-1], G[1:, :-1], G[1:, 1:], G[:-1, 1:]], -1).reshape(-1, 4)
                quads.append(q)
                qb[(t, b)] = slice(q0, q0 + len(q))
                q0 += len(q)
        return cls(ids, len(order), np.concatenate(quads), qb)

    def block_edge(self, key, side: str, lo: int = 0, hi: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(quad indices, edge numbers before orientation) along one side of a block, rows lo..hi."""
        G = self.ids[key]
        ni, nj = G.shape[0] - 1, G.shape[1] - 1
        i = np.arange(ni)
        j = np.arange(nj)
        if side in ("j0", "j1"):
            sel = i[lo:hi]
            jj = 0 if side == "j0" else nj - 1
            q = sel * nj + jj
            e = 0 if side == "j0" else 2
        else:
            sel = j[lo:hi]
            ii = 0 if side == "i0" else ni - 1
            q = ii * nj + sel
            e = 3 if side == "i0" else 1
        return self.quad_block[key].start + q, np.full(len(q), e)
