"""Benchmark of the hexahedral mesher: volumes, quality, speed, CalculiX; writes bench_mesher.md.

Run: ``.venv/bin/python -m benchmarks.mesher --out DIR [--quick]``. Measures

1. meshed tooth volume against the exact tooth-region volume for the gears of Tables 1.1 and 3.1
   at element sizes 0.5, 0.25, 0.125 and 0.0625 modules (one tooth);
2. minimum scaled Jacobian (Gauss points, corners, and gmsh's own 'minSJ') and maximum aspect ratio
   for three-tooth models graded at a contact point, coarse to fine;
3. wall and CPU time of a three-tooth pair model of the Table 1.1 sun and planet with about
   40,000 hexahedra per gear (TCA, meshing, checks, export);
4. the shipped ``mesh_*.toml`` cases (contact node gaps, sizes) and a CalculiX linear static run of
   the sun body of the Table 1.1 model (equilibrium, volume, time).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from mesher import (Focus, MeshOptions, ToothGeometry, check_conformity, check_quality, gmsh_quality, mesh_gear,
                    mesh_pair, quality, tooth_region_volume, write_inp, write_msh, write_vtu)
from tca import Gear, GearPair, run_pair_tca
from tca.report_data import (table_1_1_planet, table_1_1_ring, table_1_1_sun, table_3_1_planet, table_3_1_ring,
                              table_3_1_sun)

from pipelines.cases.reader import CASES_DIR, load_case, read_gears, read_misalignment


def gears() -> dict[str, Gear]:
    return {
        "sun (T1.1)": table_1_1_sun(),
        "planet (T1.1)": table_1_1_planet(),
        "ring (T1.1)": table_1_1_ring(),
        "sun (T3.1)": table_3_1_sun("sun3"),
        "planet (T3.1)": table_3_1_planet(crowned=True, name="planet3"),
        "ring (T3.1)": table_3_1_ring("ring3"),
    }


def _timed(f, *a, **k):
    t, c = time.perf_counter(), time.process_time()
    r = f(*a, **k)
    return r, time.perf_counter() - t, time.process_time() - c


def volumes(gs, levels):
    rows = []
    for label, g in gs.items():
        exact = tooth_region_volume(g, ToothGeometry(g, 3 * g.module).r_rim)
        for f in levels:
            m, dt, _ = _timed(mesh_gear, g, MeshOptions(teeth=1, coarse_size=f * g.module))
            v = quality(m).volume.sum()
            rows.append({"gear": label, "h_modules": f, "elements": m.n_cells, "volume_mm3": v, "exact_mm3": exact,
                         "rel_error": (v - exact) / exact, "mesh_s": dt})
    return rows


def qualities(gs, levels):
    rows = []
    for label, g in gs.items():
        for name, (c, h) in levels.items():
            m, dt, _ = _timed(mesh_gear, g, MeshOptions(teeth=3, coarse_size=c * g.module, contact_size=h * g.module),
                              centre=2, focus=Focus(1, 0.2 * g.module, 0.2 * g.face_width))
            q = check_quality(m)
            rows.append({"gear": label, "level": name, "elements": m.n_cells, "min_sj_gauss": float(q.min_scaled_jacobian.min()),
                         "min_sj_corner": float(q.min_corner_scaled_jacobian.min()),
                         "gmsh_min_sj": float(gmsh_quality(m).min()), "max_aspect_ratio": float(q.aspect_ratio.max()),
                         "mesh_s": dt})
    return rows


def speed(opts: MeshOptions):
    c = load_case(CASES_DIR / "part1_sun_planet.toml")
    t0, c0 = time.perf_counter(), time.process_time()
    g = read_gears(c)
    pair = GearPair(g["sun"], g["planet"], read_misalignment(c.table("misalignment")))
    tca, t_tca, _ = _timed(run_pair_tca, pair)
    pm, t_mesh, _ = _timed(mesh_pair, pair, "max_te", opts, tca=tca)
    m = pm.mesh
    q, t_q, _ = _timed(check_quality, m)
    _, t_c, _ = _timed(check_conformity, m)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    with tempfile.TemporaryDirectory() as d:
        _, t_vtu, _ = _timed(write_vtu, m, Path(d) / "m.vtu")
        _, t_inp, _ = _timed(write_inp, m, Path(d) / "m.inp")
        _, t_msh, _ = _timed(write_msh, m, Path(d) / "m.msh")
    return {"per_gear": [int(np.sum(m.cell_body == i)) for i in range(2)], "nodes": m.n_points,
            "gears_and_tca_s": t_tca, "mesh_s": t_mesh, "quality_s": t_q, "conformity_s": t_c,
            "model_wall_s": wall, "model_cpu_s": cpu, "vtu_s": t_vtu, "inp_s": t_inp, "msh_s": t_msh,
            "min_sj": float(q.min_scaled_jacobian.min()), "max_ar": float(q.aspect_ratio.max()),
            "contact_node_gap_mm": pm.contact_node_gap}


def cases():
    from pipelines.cli.mesh import build

    rows = []
    for p in sorted(CASES_DIR.glob("mesh_*.toml")):
        case = load_case(p)
        (m, extra, _), dt, cpu = _timed(build, case, p)
        q = check_quality(m)
        rows.append({"case": p.name, "elements": m.n_cells, "nodes": m.n_points,
                     "min_sj": float(q.min_scaled_jacobian.min()), "max_ar": float(q.aspect_ratio.max()),
                     "gap_mm": extra.get("contact_node_gap_mm"), "kind": extra.get("position", {}).get("kind"),
                     "wall_s": dt, "cpu_s": cpu})
    return rows


def calculix(opts: MeshOptions):
    ccx = shutil.which("ccx")
    if ccx is None:
        return {"skipped": "ccx not installed"}
    g = gears()["sun (T1.1)"]
    m = mesh_gear(g, opts, focus=Focus(1, 0.3, 2.0))
    with tempfile.TemporaryDirectory() as d:
        names = write_inp(m, Path(d) / "mesh.inp")
        flank = "sun/tooth0/flank_pos"
        n = len(m.point_sets[flank])
        (Path(d) / "job.inp").write_text(f"""*INCLUDE, INPUT=mesh.inp
*MATERIAL, NAME=STEEL
*ELASTIC
206800., 0.29
*SOLID SECTION, ELSET=SUN, MATERIAL=STEEL
*STEP
*STATIC, SOLVER=ITERATIVE CHOLESKY
*BOUNDARY
{names['sun/rim']}, 1, 3, 0.
*CLOAD
{names[flank]}, 2, {-1000.0 / n!r}
*NODE PRINT, NSET={names['sun/rim']}, TOTALS=ONLY
RF
*EL PRINT, ELSET=SUN, TOTALS=ONLY
EVOL
*END STEP
""")
        t = time.perf_counter()
        r = subprocess.run([ccx, "-i", "job"], cwd=d, capture_output=True, text=True, timeout=900,
                           env={**os.environ, "OMP_NUM_THREADS": "2"})
        dt = time.perf_counter() - t
        dat = (Path(d) / "job.dat").read_text()
    nums = [line.split() for line in dat.splitlines() if line.strip() and line.strip()[0] in "-0123456789"]
    return {"elements": m.n_cells, "dof": 3 * m.n_points, "returncode": r.returncode, "wall_s": dt,
            "reaction_N": [float(x) for x in nums[0]] if nums else None,
            "ccx_volume_mm3": float(nums[1][0]) if len(nums) > 1 else None,
            "mesh_volume_mm3": float(quality(m).volume.sum()), "solver": "ITERATIVE CHOLESKY"}


def _table(rows, cols, fmt):
    head = "| " + " | ".join(cols) + " |\n|" + "---|" * len(cols) + "\n"
    return head + "".join("| " + " | ".join(fmt.get(c, "{}").format(r[c]) for c in cols) + " |\n" for r in rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--quick", action="store_true", help="skip the finest volume level and CalculiX")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    load = os.getloadavg()
    gs = gears()
    res = {"load_avg": load}
    res["volumes"] = volumes(gs, (0.5, 0.25, 0.125) if a.quick else (0.5, 0.25, 0.125, 0.0625))
    res["quality"] = qualities(gs, {"coarse": (1.0, 0.25), "default": (0.5, 0.125), "fine": (0.25, 0.0625)})
    big = MeshOptions(coarse_size=0.55, contact_size=0.15, fillet_size=0.3)
    res["speed"] = speed(big)
    res["cases"] = cases()
    res["calculix"] = {"skipped": "--quick"} if a.quick else calculix(MeshOptions())
    (out / "bench_mesher.json").write_text(json.dumps(res, indent=2, default=float) + "\n")
    s = res["speed"]
    md = [f"# Mesher benchmark\n\nLoad average at start: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} (2 cores, shared).\n",
          "## 1. Meshed tooth volume vs exact tooth-region volume (one tooth, rim 3 m)\n",
          _table(res["volumes"], ["gear", "h_modules", "elements", "rel_error", "mesh_s"],
                 {"rel_error": "{:+.2e}", "mesh_s": "{:.3f}"}),
          "\n## 2. Quality of three-tooth models graded at a contact point (coarse, contact) = (1, 0.25), "
          "(0.5, 0.125), (0.25, 0.0625) modules\n",
          _table(res["quality"], ["gear", "level", "elements", "min_sj_gauss", "min_sj_corner", "gmsh_min_sj",
                                  "max_aspect_ratio", "mesh_s"],
                 {k: "{:.3f}" for k in ("min_sj_gauss", "min_sj_corner", "gmsh_min_sj", "mesh_s")} | {"max_aspect_ratio": "{:.1f}"}),
          "\n## 3. Speed: Table 1.1 sun + planet, three teeth each, at max TE\n",
          f"Hexahedra per gear {s['per_gear']}, nodes {s['nodes']}. Gear data + TCA {s['gears_and_tca_s']:.2f} s, "
          f"meshing both gears {s['mesh_s']:.2f} s, quality {s['quality_s']:.2f} s, conformity {s['conformity_s']:.2f} s: "
          f"model {s['model_wall_s']:.2f} s wall / {s['model_cpu_s']:.2f} s CPU (target < 10 s). Export: VTU "
          f"{s['vtu_s']:.2f} s, INP {s['inp_s']:.2f} s, MSH {s['msh_s']:.2f} s. min SJ {s['min_sj']:.3f}, "
          f"max AR {s['max_ar']:.1f}, contact node gap {s['contact_node_gap_mm']:.2e} mm.\n",
          "\n## 4. Shipped mesh cases\n",
          _table(res["cases"], ["case", "elements", "nodes", "min_sj", "max_ar", "gap_mm", "kind", "wall_s", "cpu_s"],
                 {"min_sj": "{:.3f}", "max_ar": "{:.1f}", "gap_mm": "{:.2e}", "wall_s": "{:.2f}", "cpu_s": "{:.2f}"}),
          "\n## 5. CalculiX linear static run (sun body, default grading, rim fixed, 1 kN on the loaded flank)\n",
          "```\n" + json.dumps(res["calculix"], indent=2) + "\n```\n"]
    (out / "bench_mesher.md").write_text("\n".join(md))
    print("\n".join(md))


if __name__ == "__main__":
    main()
