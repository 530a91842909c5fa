"""The exported .inp runs in CalculiX as a linear static model (skipped only when ccx is absent).

Small models on purpose: CalculiX 2.20 from Debian solves with SPOOLES only (MEASURED.md).
Checks that can fail: equilibrium of the reactions with the applied loads, the total element volume
computed by CalculiX (EVOL) against ours, and the moment taken by a rigid rim about the gear axis.
"""

import re
import shutil
import subprocess

import numpy as np
import pytest

from mesher import MeshOptions, mesh_gear, quality, write_inp

from tests.mesher.gears import gear

CCX = shutil.which("ccx")
pytestmark = pytest.mark.skipif(CCX is None, reason="CalculiX (ccx) not installed: apt-get install calculix-ccx")


def _run(tmp_path, deck):
    (tmp_path / "job.inp").write_text(deck)
    r = subprocess.run([CCX, "-i", "job"], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "Job finished" in r.stdout, r.stdout[-2000:]
    return (tmp_path / "job.dat").read_text()


def _totals(dat, what, nset=""):
    """Numbers on the line after the 'total <what> ... for set <nset>' header of a .dat file."""
    m = re.search(rf"total {what}[^\n]*for set {nset}[^\n]*\n\s*\n\s*(.+)\n", dat)
    assert m, dat
    return np.array([float(x) for x in m.group(1).split()])


@pytest.fixture(scope="module")
def model():
    return mesh_gear(gear("sun"), MeshOptions(teeth=3, coarse_size=1.5))


def _head(names, ref_extra=""):
    return f"""*INCLUDE, INPUT=mesh.inp
{ref_extra}*MATERIAL, NAME=STEEL
*ELASTIC
206800., 0.29
*SOLID SECTION, ELSET={names['sun']}, MATERIAL=STEEL
"""


def test_fixed_rim_static_model_balances_the_load(model, tmp_path):
    m = model
    names = write_inp(m, tmp_path / "mesh.inp")
    flank = "sun/tooth0/flank_pos"
    n = len(m.point_sets[flank])
    F = -1000.0  # N along y on the driving flank of tooth 0
    dat = _run(tmp_path, _head(names) + f"""*STEP
*STATIC
*BOUNDARY
{names['sun/rim']}, 1, 3, 0.
*CLOAD
{names[flank]}, 2, {F / n!r}
*NODE PRINT, NSET={names['sun/rim']}, TOTALS=ONLY
RF
*EL PRINT, ELSET={names['sun']}, TOTALS=ONLY
EVOL
*END STEP
""")
    rf = _totals(dat, "force")
    # reactions balance the applied force (CalculiX prints 7 significant digits)
    np.testing.assert_allclose(rf, [0.0, -F, 0.0], atol=1e-6 * abs(F))
    vol = _totals(dat, "volume")[0]
    assert vol == pytest.approx(quality(m).volume.sum(), rel=2e-6)


def test_rim_as_rigid_body_on_the_reference_node(model, tmp_path):
    # the rim coupled to the gear-axis reference node (Fig. 1.7); CalculiX needs a rotation node too
    m = model
    names = write_inp(m, tmp_path / "mesh.inp")
    flank = "sun/tooth0/flank_pos"
    ids = m.point_sets[flank]
    F = -1000.0
    ref, rot = m.n_points + 1, m.n_points + 2
    dat = _run(tmp_path, _head(names, f"*NODE, NSET=ROT\n{rot}, 0., 0., 0.\n") + f"""*RIGID BODY, NSET={names['sun/rim']}, REF NODE={ref}, ROT NODE={rot}
*STEP
*STATIC
*BOUNDARY
SUN_REF, 1, 3, 0.
ROT, 1, 3, 0.
*CLOAD
{names[flank]}, 2, {F / len(ids)!r}
*NODE PRINT, NSET=SUN_REF, TOTALS=ONLY
RF
*NODE PRINT, NSET=ROT, TOTALS=ONLY
RF
*END STEP
""")
    force = _totals(dat, "force", "SUN_REF")
    np.testing.assert_allclose(force, [0.0, -F, 0.0], atol=1e-6 * abs(F))
    # the rotation node takes the moment about the axis: minus that of the nodal loads, M_z = sum(x_i F_y)
    mz = np.sum(m.points[ids, 0]) * F / len(ids)
    assert _totals(dat, "force", "ROT")[2] == pytest.approx(-mz, rel=1e-5)
