"""Contact stresses of a gear pair at a TCA position, from Python (report section 1.6, Fig. 1.7).

Reads the shipped stress case (Table 1.1 sun driving the double-crowned planet, 3 arcmin shaft angle
error, 156 N m on the planet), makes the mesh coarser for a quick look, and runs TCA → position →
three-tooth hexahedral models → penalty-contact FE. The sun is fixed on its rim; the planet is rigid
on its rim with only its rotation free, loaded by the resisting torque. Writes ``result.vtu``.

Run: ``python examples/stress_pair.py [OUT_DIR]``
"""

import sys
import tempfile
from dataclasses import replace
from pathlib import Path

from pipelines.cases import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress


def main(out: Path, refine: float = 0.35) -> dict:  # the summary
    case = read_stress_case(load_case(CASES_DIR / "stress_pair_small.toml"))
    case = replace(case, mesh=replace(case.mesh, refine=refine))  # element sizes divided by `refine`
    return run_stress(case, out, progress=print).summary


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="gearfe-stress-"))
    s = main(out)
    print(f"{s['dofs']} DOF; contact force {s['contact_force_n']:.0f} N; max contact pressure "
          f"{s['max_contact_pressure_mpa']:.0f} MPa; max von Mises {s['max_von_mises_mpa']:.0f} MPa; fillet max "
          f"principal {s['max_fillet_stress_mpa']:.0f} MPa; sun reaction {s['reaction_torque_nm']:.2f} N m "
          f"(T N1/N2 = {s['expected_reaction_torque_nm']:.2f}); results in {out}")
