"""TCA of an isostatic planetary train (kind = "isostatic", Part 3): floating sun, errors, carrier TE.

Case keys::

    planets = "involute"            # or "double_crowned": the planets get the [crowning] modification
    [gears.sun] / [gears.planet] / [gears.ring]     # spur gears (see pipelines.cases.reader); the planet involute
    [crowning]                      # double crowning of the planets (used when planets = "double_crowned")
    parabola_per_mm = 1.25e-3       # tool parabola a_p, both flanks (Eq. 1.5)
    disk_radius_mm = 100.0          # plunging disk r_D
    plunge_parabola_per_mm = 6.25e-5  # a_l (Eq. 1.6), see the case files for the reading of Table 3.1
    [train]
    planets = 3
    sun_axis = "floating"           # "floating" | "fixed"   (section 3.2: case 2)
    carrier_axis = "fixed"
    ring_axis = "fixed"
    sun_center_error_um = [0, 0]    # fixed axes only: installment errors (Eqs. 3.7, 3.13)
    carrier_center_error_um = [20, 0]
    ring_center_error_um = [0, 0]
    [[train.planet_errors]]         # optional, per planet (Eq. 3.12, Eqs. 3.5-3.6)
    planet = 1
    tangential_um = 20.0            # Delta E_t, carrier indexing error
    radial_um = 0.0                 # Delta r_c
    runout_um = 0.0                 # eccentricity of this planet's teeth
    runout_phase_deg = 0.0
    [run]
    carrier_revolutions = 1.0       # or sun_revolutions / planet_revolutions (relative to the carrier)
    positions = 720
    start_deg = 0.0
    [solver]
    method = "fictitious"           # or "direct"

Writes ``tca.csv`` (one row per position), ``sun_center.png`` (Figs. 3.5(a)-3.15(a)),
``carrier_te.png`` (Figs. 3.5(b)-3.15(b); both :mod:`pipelines.render.isostatic`); the summary adds the first-order closed form of
:mod:`tca.isostatic.linear` (exact for involute gears up to second-order terms).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from tca.isostatic.analysis import ARCSEC, IsostaticResult, fit_circle, run_isostatic_tca
from tca.isostatic.linear import indexing_closed_form, linear_response

from pipelines.cases.isostatic import read_run, read_solver, read_train
from pipelines.cases.schema import Table
from pipelines.render.isostatic import plot_carrier_te, plot_sun_center

__all__ = ["run", "write_csv"]



def run(case: Table, out: Path) -> dict:
    train = read_train(case)
    phi1 = read_run(case, train)
    opts = read_solver(case)
    title = case.get("title", str, "") or None
    r = run_isostatic_tca(train, phi1, opts)
    write_csv(r, out / "tca.csv")
    plot_sun_center(r, out / "sun_center.png", title=title)
    plot_carrier_te(r, out / "carrier_te.png", title=title)
    s = r.summary()
    lin = linear_response(train, phi1)
    lc, lrad = fit_circle(lin.sun_center * 1e3)
    s["closed_form_first_order"] = {
        "note": "tca.isostatic.linear: exact for involute gears up to second order in the errors",
        "carrier_te_mean_arcsec": float(lin.te.mean() / ARCSEC),
        "carrier_te_peak_to_peak_arcsec": float(np.ptp(lin.te) / ARCSEC),
        "sun_center_max_um": float(np.linalg.norm(lin.sun_center, axis=1).max() * 1e3),
        "sun_center_radius_um": float(lrad),
    }
    dEt = [p.tangential for p in train.placements]
    if train.constraints.free_centres == ("sun",) and train.n_planets == 3 and any(dEt):
        cf = indexing_closed_form(train.sun.r_b, train.pressure_angle, train.ratio, sum(dEt))
        s["closed_form_section_3_4_2"] = {"backlash_um": cf.s * 1e3, "sun_turn_arcsec": cf.dphi1 / ARCSEC,
                                          "carrier_lag_increase_arcsec": cf.dphic / ARCSEC,
                                          "sun_circle_radius_um": cf.dE1 * 1e3}
    s.update(planets_variant=case.get("planets", str, "involute"),
             files=["summary.json", "tca.csv", "sun_center.png", "carrier_te.png"])
    return s


def write_csv(r: IsostaticResult, path: Path) -> None:
    """One row per position: angles, TE, centres; per planet: phi2, contacting teeth, margins, loop backlash."""
    Np = r.train.n_planets
    cols = ["phi1_deg", "phic_deg", "te_arcsec", "sun_x_um", "sun_y_um", "carrier_x_um", "carrier_y_um"]
    for i in range(1, Np + 1):
        cols += [f"p{i}_phi2_deg", f"p{i}_sun_tooth", f"p{i}_planet_tooth_s", f"p{i}_planet_tooth_r",
                 f"p{i}_ring_tooth", f"p{i}_margin_s_mm", f"p{i}_margin_r_mm", f"p{i}_backlash_um"]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols)
        for j in range(len(r.phi1)):
            row = [f"{math.degrees(r.phi1[j]):.9f}", f"{math.degrees(r.phi_c[j]):.9f}", f"{r.te_arcsec[j]:.6f}",
                   f"{r.sun_center[j, 0] * 1e3:.6f}", f"{r.sun_center[j, 1] * 1e3:.6f}",
                   f"{r.carrier_center[j, 0] * 1e3:.6f}", f"{r.carrier_center[j, 1] * 1e3:.6f}"]
            for i in range(Np):
                row += [f"{math.degrees(r.phi2[j, i]):.9f}", *(int(k) for k in r.teeth[j, i]),
                        f"{r.margin[j, i, 0]:.6f}", f"{r.margin[j, i, 1]:.6f}", f"{r.planet_backlash[j, i] * 1e3:.6f}"]
            w.writerow(row)
