"""Aligned spur pair through `gearfe stress` against closed forms: Hertz line contact and ISO 6336-3 root stress.

Case: pipelines/cases/stress_spur_pair.toml (19/24 teeth, m = 4.5 mm, b = 14 mm, T2 = 120 N m), one
tooth per gear (the whole load on one pair: ISO's and Hertz's assumption), default refinement.
Measured (this machine, 78k DOF, ~15 s each): at the pitch point the nodal peak pressure in the middle
half of the face is +2.1 % over p0 = 862 MPa, the second-moment half-width -4.8 %, the total normal force
-0.01 %; at the HPSTC the pinion's fillet maximum principal stress 121.4 MPa against σ_F0 = 117.7 MPa (+3.2 %)
(asserted in test_headline.py, which solves that model once for its critical-section check as well).
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cli import main
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress
from tca.pair.te import path_of_contact

E, NU = 2.068e5, 0.29


def spur(position: str, teeth: int = 1, **mesh):
    c = read_stress_case(load_case(CASES_DIR / "stress_spur_pair.toml"))
    return replace(c, position=position, mesh=replace(c.mesh, teeth=teeth, **mesh))


def test_hertz_line_contact_at_the_pitch_point(tmp_path):
    c = spur("pitch")
    g1, g2 = c.pair.gear1, c.pair.gear2
    run = run_stress(c, tmp_path)
    s, r, mesh = run.summary, run.result, run.mesh
    # closed forms, independent of the TCA curvatures: rho from the base radii and the pressure angle
    al = path_of_contact(c.pair).alpha_wt
    rho = 1.0 / (1.0 / (g1.r_b * math.tan(al)) + 1.0 / (g2.r_b * math.tan(al)))
    force = c.torque / g2.r_b  # T2 / r_b2 = T1 / r_b1
    w = force / g1.face_width
    e_star = E / (2 * (1 - NU ** 2))
    p0 = math.sqrt(w * e_star / (math.pi * rho))
    b = math.sqrt(4 * w * rho / (math.pi * e_star))
    assert s["contact_force_n"] == pytest.approx(force, rel=0.005)
    p = np.nan_to_num(r.contact_pressure)
    z = mesh.points[:, 2]
    mid = (p > 0) & (np.abs(z) <= 0.25 * g1.face_width)
    assert p[mid].max() == pytest.approx(p0, rel=0.05)
    # half-width from the pressure's second moment across the band: b^2/4 for the Hertz ellipse p0 sqrt(1 - x^2/b^2)
    n = np.asarray(s["interfaces"]["pinion-wheel"]["members"]["a"]["tca_normal"])
    e = np.cross(n, [0.0, 0.0, 1.0])
    x = mesh.points[:, :3] @ (e / np.linalg.norm(e))
    widths = []
    for zc in np.unique(np.round(z[mid], 6)):
        sel = mid & (np.abs(z - zc) < 1e-6)
        xb = np.average(x[sel], weights=p[sel])
        widths.append(2 * math.sqrt(np.average((x[sel] - xb) ** 2, weights=p[sel])))
    assert np.mean(widths) == pytest.approx(b, rel=0.10)
    # the face ends of an uncrowned line contact carry a pressure peak (edge of a finite body), reported as such
    assert s["max_contact_pressure_mpa"] >= p[mid].max()


# The pinion's root stress at the HPSTC against ISO 6336-3 (fillet maximum principal stress of the same model,
# spur("hpstc", contact=0.2)) is asserted in test_headline.py, on the one solve of that model.


@pytest.mark.parametrize("over, key", [({"position": "tip"}, "position"), ({"roll_deg": 60.0}, "roll_deg"),
                                       ({"roll_deg": 2.0}, "roll_deg")])
def test_a_position_that_names_no_contact_exits_2_without_files(tmp_path, over, key, capsys):
    text = (CASES_DIR / "stress_spur_pair.toml").read_text()
    lines = [ln for ln in text.splitlines() if not ln.startswith("position")]
    k, v = next(iter(over.items()))
    path = tmp_path / "bad.toml"
    path.write_text("\n".join(lines[:1] + [f"{k} = {v!r}".replace("'", '"')] + lines[1:]) + "\n")
    out = tmp_path / "out"
    assert main(["stress", str(path), "--out", str(out)]) == 2
    assert key in capsys.readouterr().err
    assert not out.exists()
