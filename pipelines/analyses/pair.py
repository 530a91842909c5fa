"""TCA of a gear pair (kind = "pair"): gears, driver/driven, misalignment, resolution.

Case keys: ``driver``, ``driven`` (names in ``[gears]``), optional ``center_distance_mm``,
``[misalignment]``, ``[tca]`` (see :mod:`pipelines.cases.reader`). Writes ``tca.csv``, ``te.png``,
``contact_paths.png``. A stress file (``model = "pair"``) or a pair file with a load gives its pair the same
way (:func:`pipelines.cases.ltca.read_loaded_pair`: its other keys are checked, not used). The summary's ``pair_geometry`` holds the pair checks' findings
(:func:`tca.pair.checks.check_pair`: the centre distance analysed and where it comes from, backlash,
tip-root clearances, contact ratios) and ``warnings`` what they warn of (a contact ratio below 1), also
printed on stderr.
"""

from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

import numpy as np

from tca.pair.analysis import ContactKind, run_pair_tca
from tca.pair.checks import check_pair

from pipelines.cases.ltca import loaded, read_loaded_pair
from pipelines.cases.reader import read_gears, read_pair, read_tca_options
from pipelines.render.plots import plot_contact_paths, plot_pair_te
from pipelines.cases.schema import Table

__all__ = ["run", "write_pair_csv"]


def run(case: Table, out: Path) -> dict:
    """The pair TCA of a pair file, or of the pair of a stress file (its other keys checked and not used)."""
    if loaded(case):  # a stress file, or a pair file with a load: every key checked, the load not used
        pair, opts, _ = read_loaded_pair(case)
        driver, driven = pair.gear1.name, pair.gear2.name
    else:
        pair, driver, driven = read_pair(case, read_gears(case))
        opts = read_tca_options(case.table("tca", required=False))
    geo = check_pair(pair)  # remembered from the reader's check: no second computation
    for w in geo.warnings:
        print(f"warning: {w}", file=sys.stderr)
    r = run_pair_tca(pair, opts)
    write_pair_csv(r, out / "tca.csv")
    plot_pair_te(r, out / "te.png", title=case.get("title", str, "") or None)
    plot_contact_paths(r, out / "contact_paths.png", names=(driver, driven))
    s = r.summary()
    s.update(
        driver=driver,
        driven=driven,
        ratio=pair.ratio,
        center_distance_mm=pair.E,
        center_distance_source=geo.source,
        pair_geometry=geo.summary(),
        warnings=list(geo.warnings),
        files=["summary.json", "tca.csv", "te.png", "contact_paths.png"],
    )
    return s


def write_pair_csv(r, path: Path) -> None:
    """One row per position: angles, TE, pair in contact, contact point, ellipse, residual."""
    cols = ["phi1_deg", "phi2_deg", "te_arcsec", "pair", "contact", "x_mm", "y_mm", "z_mm",
            "u1_mm", "v1_mm", "radius1_mm", "z1_mm", "u2_mm", "v2_mm", "radius2_mm", "z2_mm",
            "ellipse_a_mm", "ellipse_b_mm", "ellipse_angle_deg", "residual_mm"]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols)
        for i in range(len(r.phi1)):
            p1, p2 = r.point1[i], r.point2[i]
            w.writerow([
                f"{math.degrees(r.phi1[i]):.9f}", f"{math.degrees(r.phi2[i]):.9f}", f"{r.te_arcsec[i]:.6f}",
                int(r.active_pair[i]), ContactKind.names[int(r.kind[i])],
                *(f"{v:.6f}" for v in r.point_f[i]),
                f"{r.params[i, 0]:.6f}", f"{r.params[i, 1]:.6f}", f"{np.hypot(p1[0], p1[1]):.6f}", f"{p1[2]:.6f}",
                f"{r.params[i, 2]:.6f}", f"{r.params[i, 3]:.6f}", f"{np.hypot(p2[0], p2[1]):.6f}", f"{p2[2]:.6f}",
                f"{r.ellipse_a[i]:.6f}", f"{r.ellipse_b[i]:.6f}",
                f"{math.degrees(r.ellipse_angle[i]):.4f}" if np.isfinite(r.ellipse_angle[i]) else "nan",
                f"{r.residual[i]:.3e}",
            ])
