"""Results of a gear stress solve: per tooth pair, member and interface; edge contact; the summary.

Load share: each tooth pair's (and member's) fraction of the total normal contact force of its
interface (sun–planet, planet–ring, or the pair's mesh); they sum to 1 per interface.

Edge contact in the FE sense: contact pressure at the boundary nodes of a loaded flank face set
(nodes on an edge used by one face of the set only: the tip, the two ends of the face width and
the start of the fillet). The slave's nodal pressure is read there directly; at the master's
boundary nodes it is interpolated from the slave surface (closest-point projection on the slave
faces, bilinear shape functions). A pair has edge contact when that pressure exceeds
``EDGE_FRACTION`` of the peak contact pressure of its interface; ``edge_pressure_mpa`` reports the
value itself.

Torque balance (issue 6): the reaction torque of the fixed body about its axis against the applied
torque times the ratio (N1/N2 for a pair, N1/N3 for the twin drive through the planet).

A contact at a point with common normal n transmits torques in the ratio of the moment arms
m_i = ((x - o_i) x n) . a_i, which equals the instantaneous ratio of its mesh,
rho = m1/m2 = N1/N2 + dΔφ2/dφ1 (the TCA slope ``te_slope`` in the summary's position; they agree to
< 1e-5 on surface contact, tests/pipelines/models/stress/test_stress.py; at an edge or corner contact the TE has
a kink and the grid slope means nothing). So the nominal ratio holds only where the loaded
contacts' TE slopes vanish. When several pairs of teeth of one mesh carry load (near a
transition), the mesh's ratio is their ratios rho_q = rho + slope_q - slope (slope_q of the TE branch
of the pair q teeth on) weighted by their FE forces. For a pair T_driver / T = rho. For the twin drive, with sigma_k and
tau_k the shares of the planet's torque received from the sun contacts and passed to the ring
contacts of member k (FE forces times the planet's arms at the TCA points), the rigid planet's
equilibrium gives the *kinematic ratio*

    T_sun / T = (sum_k sigma_k rho12_k) / (sum_k tau_k / rho23_k),

which differs from N1/N3 when a loaded member is on the flank of its TE (rho12 rho23 != N1/N3) and
also when sigma != tau. Example 1.3's new design at its maximum TE: the leading member at its TE
maximum (rho12 rho23 = N1/N3 within 1.2e-4), the other on its flank (+7.1e-3), shares 0.51/0.49 at
the sun and 0.31/0.69 at the ring: kinematic ratio +3.0e-3 over N1/N3, FE reaction +2.8e-3.
``torque_balance_error_kinematic`` compares the FE reaction with this ratio (the FE forces act over
the contact zones, not at the TCA points: a few 1e-4); ``torque_balance_error`` with N1/N2 or N1/N3.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from fem.contact.faces import bilinear, project_to_faces, surface_mass
from fem.result import STRESS_RECOVERY, FEResult
from fem.model import FEModel
from fem.mesh.hexmesh import HexMesh
from tca.pair.analysis import ARCSEC, ContactKind

from pipelines.models.stress.headline import contact_peaks, fillet_peaks, root_stress
from pipelines.models.stress.scene import Scene

__all__ = ["EDGE_FRACTION", "boundary_nodes", "pressure_at", "pair_results", "member_teeth", "summarize", "lumped_peak", "loaded_te",
           "TWIN_RING_AXIS"]

TWIN_RING_AXIS = (0.0, 0.0, -1.0)  # the ring turns positively about -z_f (scene.twin_scene)

EDGE_FRACTION = 0.05


def boundary_nodes(mesh: HexMesh, face_set: str) -> np.ndarray:
    """Nodes on the boundary edges of a face set (edges used by one of its faces only)."""
    q = mesh.face_nodes(face_set)
    e = np.sort(np.stack([q, np.roll(q, -1, axis=1)], -1).reshape(-1, 2), axis=1)
    uniq, counts = np.unique(e, axis=0, return_counts=True)
    return np.unique(uniq[counts == 1])


def pressure_at(points: np.ndarray, mesh: HexMesh, face_set: str, pressure: np.ndarray, tol: float) -> np.ndarray:
    """Nodal field of a face set interpolated at points (closest point on its faces, within tol [mm]; else 0)."""
    if len(points) == 0:
        return np.zeros(0)
    q = mesh.face_nodes(face_set)
    X = mesh.points[q]
    kq = min(8, len(q))
    _, cand = cKDTree(X.mean(1)).query(points, k=kq)
    cand = np.asarray(cand).reshape(len(points), kq)
    xs = np.repeat(points, kq, axis=0)
    xi, eta, xp = project_to_faces(xs, X[cand.ravel()], limit=1.0)
    N, _, _ = bilinear(xi, eta)
    d = np.linalg.norm(xp - xs, axis=1).reshape(len(points), kq)
    best = np.argmin(d, axis=1)
    sel = np.arange(len(points)) * kq + best
    vals = np.einsum("pa,pa->p", N[sel], np.nan_to_num(pressure)[q[cand.ravel()[sel]]])
    return np.where(d[np.arange(len(points)), best] <= tol, vals, 0.0)


def _slave_normal(mesh: HexMesh, face_set: str, node: int) -> np.ndarray:
    q = mesh.face_nodes(face_set)
    sel = np.any(q == node, axis=1)
    p = mesh.points[q[sel]]
    n = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]).sum(0)
    return n / np.linalg.norm(n)


def pair_results(mesh: HexMesh, model: FEModel, r: FEResult) -> list[dict]:
    """Per contact pair: force, area, peak pressure, edge pressure (slave and master boundaries)."""
    out = []
    p = r.contact_pressure
    for cp, pr in zip(model.contacts, r.pairs):
        bs = boundary_nodes(mesh, cp.slave)
        slave_edge = float(np.nanmax(p[bs], initial=0.0))
        bm = boundary_nodes(mesh, cp.master)
        h = np.sqrt(np.median(np.linalg.norm(np.cross(*(mesh.points[mesh.face_nodes(cp.slave)][:, k] -
                                                         mesh.points[mesh.face_nodes(cp.slave)][:, 0] for k in (1, 3))), axis=1)))
        master_edge = float(pressure_at(mesh.points[bm], mesh, cp.slave, p, tol=max(0.02, 0.1 * h)).max(initial=0.0))
        out.append({"name": pr.name, "group": pr.group, "slave": cp.slave, "master": cp.master, "force_n": pr.force,
                    "area_mm2": pr.area, "max_pressure_mpa": pr.max_pressure, "active_nodes": pr.active_nodes,
                    "candidates": pr.candidates, "semi_axes_mm": [float(x) for x in pr.semi_axes],
                    "edge_pressure_mpa": max(slave_edge, master_edge),
                    "slave_edge_pressure_mpa": slave_edge, "master_edge_pressure_mpa": master_edge})
    return out


def _interfaces(scene: Scene, rows: list[dict]) -> tuple[dict, dict]:
    """Per interface: totals, per member, per tooth pair; and the load shares."""
    res, share = {}, {}
    for itf in scene.interfaces:
        key = itf.name
        if key not in res:
            res[key] = {"force_n": 0.0, "contact_area_mm2": 0.0, "max_contact_pressure_mpa": 0.0, "members": {}, "teeth": {}}
        d = res[key]
        pref = f"{itf.name}/"
        mine = [row for row in rows if row["group"] == f"{itf.name}/{itf.member}"]
        m = {"force_n": sum(x["force_n"] for x in mine), "contact_area_mm2": sum(x["area_mm2"] for x in mine),
             "max_contact_pressure_mpa": max((x["max_pressure_mpa"] for x in mine), default=0.0),
             "edge_pressure_mpa": max((x["edge_pressure_mpa"] for x in mine), default=0.0),
             "tca_contact_point_mm": [float(v) for v in itf.point], "tca_kind": _kind(itf.contact.kind),
             "tca_normal": [float(v) for v in itf.normal],
             "slave_body": (itf.driven if itf.slave == "driven" else itf.driver).body,
             "slave_is_driver": itf.slave != "driven",
             "face_width_mm": float(min(itf.driver.gear.face_width, itf.driven.gear.face_width)),
             "hertz_estimate": itf.hertz.as_json(),
             "mesh_sizes_mm": {k: float(getattr(itf.driven.sizes, k)) for k in ("contact", "axial", "fillet", "coarse", "extent_u", "extent_z")}}
        d["members"][itf.member] = m
        for q, (x, (off, j1, j2)) in enumerate(zip(mine, itf.tooth_pairs())):
            d["teeth"][x["name"][len(pref):]] = {**{k: v for k, v in x.items() if k not in ("name", "group")}, "offset": off}
        d["force_n"] += m["force_n"]
        d["contact_area_mm2"] += m["contact_area_mm2"]
        d["max_contact_pressure_mpa"] = max(d["max_contact_pressure_mpa"], m["max_contact_pressure_mpa"])
    for key, d in res.items():
        tot = d["force_n"]
        peak = d["max_contact_pressure_mpa"]
        share[key] = {"members": {k: (v["force_n"] / tot if tot > 0 else 0.0) for k, v in d["members"].items()},
                      "teeth": {k: (v["force_n"] / tot if tot > 0 else 0.0) for k, v in d["teeth"].items()}}
        for v in d["members"].values():
            v["edge_contact"] = bool(peak > 0 and v["edge_pressure_mpa"] > EDGE_FRACTION * peak)
        for v in d["teeth"].values():
            v["edge_contact"] = bool(peak > 0 and v["edge_pressure_mpa"] > EDGE_FRACTION * peak)
        d["edge_contact"] = any(v["edge_contact"] for v in d["members"].values())
        d["load_share"] = share[key]
    return res, share


def member_teeth(itf, interfaces: dict) -> list[dict]:
    """The per-tooth-pair results of one interface member (rows with 'offset' from its loaded pair)."""
    return [t for k, t in interfaces[itf.name]["teeth"].items() if k.startswith(f"{itf.member}/")]


def _mesh_ratio(itf, interfaces: dict) -> float:
    """Instantaneous ratio of one member's mesh: its loaded tooth pairs' ratios weighted by their FE forces."""
    rows = [t for t in member_teeth(itf, interfaces) if t["force_n"] > 0]
    tot = sum(t["force_n"] for t in rows)
    if tot <= 0:
        return abs(itf.contact.ratio)
    return abs(sum(t["force_n"] * itf.contact.ratio_of(t["offset"]) for t in rows) / tot)


def kinematic_ratio(scene: Scene, interfaces: dict) -> float:
    """Reaction / applied torque predicted by the TCA's instantaneous ratios and the FE load distribution."""
    if scene.model == "pair":
        return _mesh_ratio(scene.interfaces[0], interfaces)
    if scene.model == "train":  # carrier held: planet i passes its sun torque to the ring times 1 / (rho12 rho23)
        sun = [i for i in scene.interfaces if i.name == "sun-planet"]
        ring = {i.member: i for i in scene.interfaces if i.name == "planet-ring"}
        w = np.array([interfaces["sun-planet"]["members"][i.member]["force_n"] * abs(i.contact.arms[0]) for i in sun])
        w = w / w.sum()
        return float(sum(wi / (_mesh_ratio(i, interfaces) * _mesh_ratio(ring[i.member], interfaces))
                         for i, wi in zip(sun, w)))

    def weights(name, arm):
        itfs = [i for i in scene.interfaces if i.name == name]
        w = np.array([interfaces[name]["members"][i.member]["force_n"] * abs(i.contact.arms[arm]) for i in itfs])
        return itfs, w / w.sum()

    sun, s = weights("sun-planet", 1)
    ring, t = weights("planet-ring", 0)
    return float(sum(w * _mesh_ratio(i, interfaces) for i, w in zip(sun, s))
                 / sum(w / _mesh_ratio(i, interfaces) for i, w in zip(ring, t)))


def lumped_peak(mesh: HexMesh, model: FEModel, r: FEResult) -> float:
    """Largest nodal force over tributary area F_a / int N_a dA on the slave flanks [MPa] (no Jacobi step).

    The pressure without the consistent-projection step of ``fem.contact.ContactSet.pressure``: it
    smooths the peak by O(h^2) and converges from below where the recovered peak converges from above.
    """
    if r.contact_force is None:
        return float("nan")
    peak = 0.0
    for cp in model.contacts:
        q = mesh.face_nodes(cp.slave)
        D = np.asarray(surface_mass(mesh.points, q).sum(axis=1)).ravel()
        nodes = np.unique(q)
        peak = max(peak, float((r.contact_force[nodes] / D[nodes]).max(initial=0.0)))
    return peak


def _peak_semi_axes(rows: list[dict]) -> list[float]:
    """Hertz-equivalent semi-axes a >= b [mm] of the pair carrying the peak pressure (fem.contact.contact_patch)."""
    row = max(rows, key=lambda x: x["max_pressure_mpa"], default=None)
    return [0.0, 0.0] if row is None else list(row["semi_axes_mm"])


def _kind(k) -> str:
    return ContactKind.names.get(int(k), str(k))


def summarize(scene: Scene, mesh: HexMesh, model: FEModel, r: FEResult) -> dict:
    """The summary of a stress run (JSON-ready; the keys of ``gearfe stress``'s summary.json)."""
    rows = pair_results(mesh, model, r)
    interfaces, share = _interfaces(scene, rows)
    body, point, axis, expected = scene.reaction
    actual = r.support_torque(body, point, axis)
    tb = abs(actual - expected) / abs(expected)
    rk = kinematic_ratio(scene, interfaces)
    expected_k = expected / scene.ratio * rk
    fil = r.fillet_stress()
    fil_raw = max((v["max_principal_mpa"] for v in fil.values()), default=float("nan"))
    fil_vm = max((v["max_von_mises_mpa"] for v in fil.values()), default=float("nan"))
    peaks, clear = fillet_peaks(scene, mesh, r, tuple(fil))  # contact-induced peaks apart (headline.py)
    fil_at = max(clear, key=clear.get) if clear else None
    fil_p = clear[fil_at] if fil_at is not None else float("nan")
    cpeaks = contact_peaks(scene, mesh, model, r, rows)
    imax = int(np.argmax(r.von_mises))
    vm_body = mesh.bodies[int(mesh.cell_body[np.flatnonzero((mesh.cells == imax).any(axis=1))[0]])]
    ip = int(np.argmax(r.contact_pressure))
    pk = r.contact_pressure[ip]
    focus = None
    if pk > 0:
        row = max(rows, key=lambda x: x["max_pressure_mpa"])
        nrm = _slave_normal(mesh, row["slave"], ip)
        act = np.flatnonzero(np.nan_to_num(r.contact_pressure) > 0)
        act = act[np.isin(act, mesh.face_set_points(row["slave"]))]
        rad = float(np.linalg.norm(mesh.points[act] - mesh.points[ip], axis=1).max(initial=0.0))
        focus = {"point_mm": mesh.points[ip].tolist(), "normal": nrm.tolist(), "radius_mm": max(rad, 1.0),
                 "pair": row["name"]}
    first = scene.interfaces[0].name
    tca_edge = any(itf.contact.kind != ContactKind.SURFACE for itf in scene.interfaces)
    info = r.info
    return {
        "max_von_mises_mpa": float(r.von_mises.max()),
        "max_von_mises_body": vm_body,
        "max_contact_pressure_mpa": float(pk),
        "contact_force_n": interfaces[first]["force_n"],
        "contact_area_mm2": interfaces[first]["contact_area_mm2"],
        "contact_semi_axes_mm": _peak_semi_axes(rows),
        "max_contact_pressure_lumped_mpa": lumped_peak(mesh, model, r),
        "max_fillet_stress_mpa": fil_p,
        "max_fillet_von_mises_mpa": fil_vm,
        "max_fillet_set": fil_at,
        "max_fillet_stress_raw_mpa": fil_raw,
        "fillet_peaks": peaks,
        "root_stress": root_stress(scene, mesh, r, interfaces),
        "contact_peak_mpa": max((c["smooth_peak_mpa"] for c in cpeaks), default=0.0),
        "contact_peaks": cpeaks,
        "edge_peaks": [c for c in cpeaks if c["edge_flagged"]],
        "torque_balance_error": tb,
        "reaction_torque_nm": actual * 1e-3,
        "expected_reaction_torque_nm": expected * 1e-3,
        "reaction_body": body,
        "ratio": scene.ratio,
        "kinematic_ratio": rk,
        "torque_balance_error_kinematic": abs(actual - expected_k) / abs(expected_k),
        "edge_contact": bool(tca_edge),
        "fe_edge_contact": any(d["edge_contact"] for d in interfaces.values()),
        "load_share": share,
        "interfaces": interfaces,
        "contact_point_mm": [float(v) for v in scene.interfaces[0].point],
        "focus": focus,
        "dofs": int(info.dofs),
        "elements": int(mesh.n_cells),
        "nodes": int(mesh.n_points),
        "rigid_motion": {b: {"translation_mm": [float(x) for x in t], "rotation_rad": [float(x) for x in w]}
                         for b, (t, w) in r.rigid_motion.items()},
        "fe": {"solver": info.solver, "element": info.element, "reduced_dofs": int(info.reduced_dofs),
               "contact_candidates": int(info.candidates), "active_nodes": int(info.active),
               "active_set_iterations": int(info.iterations), "penalty_scale": float(info.penalty_scale),
               "penalty_doubling_change": float(info.penalty_change), "max_penetration_mm": float(info.max_penetration),
               "timings_s": {k: float(v) for k, v in info.timings.items()}},
        "stress_recovery": STRESS_RECOVERY,
        "edge_contact_rule": f"pressure at a loaded flank's boundary nodes > {EDGE_FRACTION:g} x the interface's peak",
    }


def loaded_te(case, summary: dict) -> dict:
    """Unloaded TE, elastic rotation of the driven body and loaded TE [arcsec] (:mod:`pipelines.sweep.points`: the driving body is held still)."""
    if case.model == "pair":
        body, axis = case.pair.gear2.name, np.asarray(case.pair.mounts()[1].axis, float)
        te = summary["position"]["te_arcsec"]
    else:
        body, axis = "ring", np.array(TWIN_RING_AXIS)
        te = summary["position"]["te3_arcsec"]
    w = np.asarray(summary["rigid_motion"][body]["rotation_rad"], float)
    d = float(w @ axis) / ARCSEC
    return {"body": body, "axis": axis.tolist(), "unloaded_te_arcsec": te, "elastic_rotation_arcsec": d,
            "loaded_te_arcsec": te + d}
