r"""Headline numbers of a stress solve that mean what they say: the loaded teeth's bending stress at ISO's critical
section, fillet maxima away from contact-induced peaks, and per tooth pair the smooth contact peak apart from edge
and corner peaks.

Root stress. For every tooth carrying load (its tooth pair's FE force > 0) the tension fillet is the one on the
loaded flank's side (``tooth<j>/fillet_pos`` for a loaded +y flank). Its nodes (fillet and root sets) are taken
into the gear's frame (:class:`pipelines.models.stress.scene.Part`: :math:`x = R^T(x_f - t)`) and grouped by axial
level :math:`\zeta` (the flank's nodes too: on an internal gear the flank's tangent can pass 30° above the
fillet). At each level the tooth centre line is the bisector of the two fillets (the mean of their polar
angles at a common radius); in the tooth frame (:math:`\xi` along the centre line, :math:`\eta` across) the fillet
curve's tangent makes the angle

.. math::
    \tau = \arctan\frac{|\Delta\eta|}{|\Delta\xi|} \quad (K1)

with the centre line: 90° at the root, small on the flank. The critical section of ISO 6336-3 is where
:math:`\tau = 30°` (linear interpolation between the segments enclosing it); the nodal largest principal stress is
interpolated there along the curve's arc length. Reported per gear: the largest over the loaded teeth and the face
(and the value at mid-face), the tooth and its load share.

Contact-induced fillet peaks. A fillet node closer than :data:`CONTACT_REACH` :math:`\cdot m_n` to a node in contact
(pressure > 0, any body) lies in the local stress field of that contact (a mating tip bearing on the fillet top, an
edge or corner contact at a face end): the fillet maximum of a tooth is taken over its other nodes, and the
excluded nodes' maximum, where it exceeds that, is reported under its own name with its location and cause
(``face-end contact`` when the point is within that reach of a face end, else ``mating tip bearing on the fillet
top``).

Contact peaks. Per tooth pair (contact pair), the slave's nodes in contact farther than :data:`EDGE_REACH`
:math:`\cdot m_n` from the boundary of the slave flank and from the boundary of the master flank (tip, face ends,
start of the fillet) give the smooth peak; the others the edge peak, flagged when it exceeds the smooth peak, with
its location and kind: ``tip edge``, ``face end``, ``corner`` (both) or ``fillet start``, of the gear whose
boundary it is.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from fem.mesh.hexmesh import HexMesh
from fem.result import FEResult

from pipelines.models.stress.scene import Scene

__all__ = ["CONTACT_REACH", "EDGE_REACH", "CRITICAL_ANGLE_DEG", "root_stress", "contact_peaks", "fillet_peaks",
           "critical_section", "gear_coords", "gear_frame_part"]

CONTACT_REACH = 0.25  # fillet nodes within this many normal modules of a contact node are in its local field
EDGE_REACH = 0.1  # contact nodes within this many normal modules of a flank boundary belong to the edge
CRITICAL_ANGLE_DEG = 30.0  # ISO 6336-3: tangent at 30° to the tooth centre line


def _side(s: int) -> str:
    return "pos" if s > 0 else "neg"


def gear_frame_part(scene: Scene, face_set: str):
    """The scene's part (gear member) a face set of the mesh belongs to."""
    return next(p for p in scene.parts if face_set.startswith(p.set("")))


def gear_coords(part, x: np.ndarray) -> np.ndarray:
    """Points of the fixed frame in the part's gear frame."""
    return (np.asarray(x, float) - np.asarray(part.t, float)) @ np.asarray(part.R, float)


def _nodes(mesh: HexMesh, names: list[str]) -> np.ndarray:
    have = [n for n in names if n in mesh.face_sets]
    return np.unique(np.concatenate([mesh.face_set_points(n) for n in have])) if have else np.zeros(0, int)


def _levels(zeta: np.ndarray, tol: float) -> list[np.ndarray]:
    """Indices grouped by axial level (levels closer than ``tol`` [mm] merge)."""
    order = np.argsort(zeta)
    cuts = np.flatnonzero(np.diff(zeta[order]) > tol) + 1
    return np.split(order, cuts)


def critical_section(part, mesh: HexMesh, r: FEResult, tooth: int, side: int) -> dict | None:
    """The 30° tangent section of one tooth's tension fillet (module docstring, K1): per level and its extremes."""
    mn = part.gear.module
    # the flank too: on an internal gear the flank's tangent may pass 30° before the fillet starts
    t_nodes = _nodes(mesh, [part.set(f"tooth{tooth}/{k}_{_side(side)}") for k in ("fillet", "root", "flank")])
    c_nodes = _nodes(mesh, [part.set(f"tooth{tooth}/fillet_{_side(-side)}"), part.set(f"tooth{tooth}/root_{_side(-side)}")])
    if len(t_nodes) < 3 or len(c_nodes) < 3:
        return None
    xt, xc = gear_coords(part, mesh.points[t_nodes]), gear_coords(part, mesh.points[c_nodes])
    th0 = 2 * math.pi * tooth / part.gear.teeth
    polar = lambda x: (np.hypot(x[:, 0], x[:, 1]), (np.arctan2(x[:, 1], x[:, 0]) - th0 + math.pi) % (2 * math.pi) - math.pi)  # noqa: E731
    rt, at = polar(xt)
    rc, ac = polar(xc)
    sig = r.principal[t_nodes, 0]
    tol = 1e-4 * mn
    lev_c = {round(float(np.mean(xc[g, 2])) / tol): g for g in _levels(xc[:, 2], tol)}
    rows = []
    for g in _levels(xt[:, 2], tol):
        if len(g) < 3:
            continue
        zeta = float(np.mean(xt[g, 2]))
        gc = lev_c.get(round(zeta / tol))
        if gc is None or len(gc) < 3:
            continue
        o_t, o_c = np.argsort(rt[g]), np.argsort(rc[gc])
        lo, hi = max(rt[g].min(), rc[gc].min()), min(rt[g].max(), rc[gc].max())
        if not hi > lo:
            continue
        rr = np.linspace(lo, hi, 5)
        centre = float(np.mean(0.5 * (np.interp(rr, rt[g][o_t], at[g][o_t]) + np.interp(rr, rc[gc][o_c], ac[gc][o_c]))))
        psi = at[g][o_t] - centre
        xi, eta = rt[g][o_t] * np.cos(psi), rt[g][o_t] * np.sin(psi)
        d_xi, d_eta = np.diff(xi), np.diff(eta)
        tau = np.degrees(np.arctan2(np.abs(d_eta), np.abs(d_xi)))  # per segment, (K1)
        s = np.concatenate([[0.0], np.cumsum(np.hypot(d_xi, d_eta))])
        s_mid = 0.5 * (s[1:] + s[:-1])
        cross = np.flatnonzero(np.diff(np.sign(tau - CRITICAL_ANGLE_DEG)) != 0)
        if len(cross) == 0:
            continue
        k = int(cross[-1] if part.gear.internal else cross[0])  # the crossing nearest the root
        w = (CRITICAL_ANGLE_DEG - tau[k]) / (tau[k + 1] - tau[k])
        s30 = s_mid[k] + w * (s_mid[k + 1] - s_mid[k])
        val = float(np.interp(s30, s, sig[g][o_t]))
        pts = mesh.points[t_nodes[g][o_t]]
        p30 = np.array([np.interp(s30, s, pts[:, i]) for i in range(3)])
        rows.append((zeta, val, p30, float(np.interp(s30, s, rt[g][o_t]))))
    if not rows:
        return None
    i = int(np.argmax([x[1] for x in rows]))
    mid = int(np.argmin([abs(x[0]) for x in rows]))
    return {"max_mpa": rows[i][1], "point_mm": rows[i][2].tolist(), "axial_mm": rows[i][0], "radius_mm": rows[i][3],
            "mid_face_mpa": rows[mid][1], "levels": len(rows)}


def _contact_tree(mesh: HexMesh, r: FEResult):
    on = np.flatnonzero(np.nan_to_num(r.contact_pressure) > 0)
    return (cKDTree(mesh.points[on]) if len(on) else None), on


def _fillet_split(mesh: HexMesh, r: FEResult, nodes: np.ndarray, tree, reach: float):
    """(clear nodes, nodes in a contact's local field) of a fillet."""
    if tree is None or len(nodes) == 0:
        return nodes, nodes[:0]
    d, _ = tree.query(mesh.points[nodes])
    return nodes[d > reach], nodes[d <= reach]


def root_stress(scene: Scene, mesh: HexMesh, r: FEResult, interfaces: dict) -> dict:
    """Per gear (body/label): the loaded teeth's bending stress at the 30° section and fillet maxima (module docstring)."""
    tree, _ = _contact_tree(mesh, r)
    out: dict = {}
    for itf in scene.interfaces:
        teeth = interfaces[itf.name]["teeth"]
        share = interfaces[itf.name]["load_share"]["teeth"]
        for off, j1, j2 in itf.tooth_pairs():
            name = next((k for k, v in teeth.items() if v["offset"] == off and k.startswith(f"{itf.member}/")), None)
            if name is None or teeth[name]["force_n"] <= 0:
                continue
            for part, j, side in ((itf.driver, j1, itf.side1), (itf.driven, j2, itf.side2)):
                key = f"{part.body}/{part.label}" if part.label else part.body
                sec = critical_section(part, mesh, r, j, side)
                nodes = _nodes(mesh, [part.set(f"tooth{j}/fillet_{_side(side)}")])
                clear, _ = _fillet_split(mesh, r, nodes, tree, CONTACT_REACH * part.gear.module)
                fil = float(r.principal[clear, 0].max(initial=-np.inf)) if len(clear) else None
                at = mesh.points[clear[np.argmax(r.principal[clear, 0])]].tolist() if len(clear) else None
                rec = {"interface": itf.name, "member": itf.member, "tooth": int(j), "offset": int(off),
                       "load_share": share.get(name, 0.0), "fillet_set": part.set(f"tooth{j}/fillet_{_side(side)}"),
                       "critical_section_mpa": None if sec is None else sec["max_mpa"],
                       "critical_section_mid_face_mpa": None if sec is None else sec["mid_face_mpa"],
                       "critical_section_point_mm": None if sec is None else sec["point_mm"],
                       "fillet_max_mpa": fil, "fillet_max_point_mm": at}
                g = out.setdefault(key, {"gear": part.gear.name, "teeth": []})
                g["teeth"].append(rec)
    for g in out.values():
        best = max(g["teeth"], key=lambda t: t["critical_section_mpa"] or -np.inf)
        g.update({k: best[k] for k in ("critical_section_mpa", "critical_section_mid_face_mpa", "critical_section_point_mm",
                                       "tooth", "load_share", "interface", "member")})
        fm = max(g["teeth"], key=lambda t: t["fillet_max_mpa"] if t["fillet_max_mpa"] is not None else -np.inf)
        g["fillet_max_mpa"], g["fillet_max_point_mm"], g["fillet_max_tooth"] = (fm["fillet_max_mpa"],
                                                                               fm["fillet_max_point_mm"], fm["tooth"])
    return out


def fillet_peaks(scene: Scene, mesh: HexMesh, r: FEResult, fillet_sets: tuple) -> tuple[list[dict], dict]:
    """Contact-induced fillet peaks (module docstring), and per fillet set its maximum away from them [MPa]."""
    tree, _ = _contact_tree(mesh, r)
    parts = {p.set(""): p for p in scene.parts}
    peaks, clear_max = [], {}
    for fs in fillet_sets:
        part = next((p for pre, p in parts.items() if fs.startswith(pre)), None)
        if part is None:
            continue
        mn = part.gear.module
        nodes = _nodes(mesh, [fs])
        clear, near = _fillet_split(mesh, r, nodes, tree, CONTACT_REACH * mn)
        cm = float(r.principal[clear, 0].max(initial=-np.inf)) if len(clear) else -np.inf
        clear_max[fs] = cm
        if len(near) == 0:
            continue
        i = near[int(np.argmax(r.principal[near, 0]))]
        v = float(r.principal[i, 0])
        if v <= cm:
            continue
        zeta = float(gear_coords(part, mesh.points[i:i + 1])[0, 2])
        end = abs(zeta) >= 0.5 * part.gear.face_width - CONTACT_REACH * mn
        peaks.append({"set": fs, "gear": part.gear.name, "value_mpa": v, "point_mm": mesh.points[i].tolist(),
                      "axial_mm": zeta, "clear_max_mpa": cm,
                      "cause": "face-end (edge or corner) contact" if end else "mating tip bearing on the fillet top"})
    peaks.sort(key=lambda p: -p["value_mpa"])
    return peaks, clear_max


def _boundary(mesh: HexMesh, face_set: str) -> np.ndarray:
    q = mesh.face_nodes(face_set)
    e = np.sort(np.stack([q, np.roll(q, -1, axis=1)], -1).reshape(-1, 2), axis=1)
    uniq, counts = np.unique(e, axis=0, return_counts=True)
    return np.unique(uniq[counts == 1])


def _edge_kind(part, x: np.ndarray, reach: float) -> str:
    g = gear_coords(part, x[None, :])[0]
    rad, z = math.hypot(g[0], g[1]), g[2]
    tip = abs(rad - part.gear.r_tip) <= reach + 0.02 * part.gear.module
    end = abs(z) >= 0.5 * part.gear.face_width - reach
    return "corner" if tip and end else "tip edge" if tip else "face end" if end else "fillet start"


def contact_peaks(scene: Scene, mesh: HexMesh, model, r: FEResult, rows: list[dict]) -> list[dict]:
    """Per tooth pair: the smooth peak and the edge/corner peak with its location and kind (module docstring)."""
    p = np.nan_to_num(r.contact_pressure)
    parts = {pt.set(""): pt for pt in scene.parts}
    out = []
    for cp, row in zip(model.contacts, rows):
        sp = next((pt for pre, pt in parts.items() if cp.slave.startswith(pre)), None)
        mp = next((pt for pre, pt in parts.items() if cp.master.startswith(pre)), None)
        if sp is None or mp is None:
            continue
        reach = EDGE_REACH * sp.gear.module
        nodes = mesh.face_set_points(cp.slave)
        act = nodes[p[nodes] > 0]
        rec = {"pair": row["name"], "slave_set": cp.slave, "master_set": cp.master, "force_n": row["force_n"],
               "smooth_peak_mpa": 0.0, "edge_peak_mpa": 0.0,
               "edge_point_mm": None, "edge_kind": None, "edge_of": None, "edge_flagged": False}
        if len(act):
            bs, bm = _boundary(mesh, cp.slave), _boundary(mesh, cp.master)
            ds, _ = cKDTree(mesh.points[bs]).query(mesh.points[act])
            dm, im = cKDTree(mesh.points[bm]).query(mesh.points[act])
            edge = (ds <= reach) | (dm <= reach)
            smooth = act[~edge]
            rec["smooth_peak_mpa"] = float(p[smooth].max(initial=0.0))
            if edge.any():
                k = int(np.argmax(np.where(edge, p[act], -1.0)))
                x = mesh.points[act[k]]
                own = ds[k] <= dm[k]
                part = sp if own else mp
                q = mesh.face_nodes(cp.slave)
                f = mesh.points[q[np.any(q == act[k], axis=1)]]
                nrm = np.cross(f[:, 2] - f[:, 0], f[:, 3] - f[:, 1]).sum(axis=0)
                rec["edge_normal"] = (nrm / np.linalg.norm(nrm)).tolist()  # out of the slave flank
                rec["slave_body"] = sp.body
                rec.update(edge_peak_mpa=float(p[act[k]]), edge_point_mm=x.tolist(),
                           edge_kind=_edge_kind(part, x if own else mesh.points[bm[im[k]]], reach),
                           edge_of=part.gear.name)
                rec["edge_flagged"] = bool(rec["edge_peak_mpa"] > rec["smooth_peak_mpa"])
        out.append(rec)
    return out
