"""The command line on solves that fail (issue 13): one error line, exit status 2, no output folder.

Newton-type iterations raise :class:`tca.errors.ConvergenceError` when they do not converge
(STYLE.md); ``gearfe`` prints it on one line and writes nothing (``pipelines/cli/outdir.py`` stages
the output). The failing solve here is real: the axial regulation of Part 1 (a secant iteration on
the TE maximum, ``tca.planetary.regulation``) limited to its two first-order evaluations with a
tolerance of 1e-6 arcsec, which it cannot meet in two evaluations.
"""

from pathlib import Path

from pipelines.cli import main

CASE = Path("pipelines/cases/stress_part1_new.toml")


def test_non_converging_regulation_exits_2_without_files(tmp_path, capsys):
    text = CASE.read_text()
    text = text.replace("tol_arcsec = 0.001", "tol_arcsec = 1e-6").replace("max_iterations = 12", "max_iterations = 2")
    text = text.replace("cycles = 2\n", "cycles = 1\n").replace("steps_per_cycle = 40 ", "steps_per_cycle = 10 ")
    assert "tol_arcsec = 1e-6" in text and "max_iterations = 2" in text
    case = tmp_path / "case.toml"
    case.write_text(text)
    out = tmp_path / "out"
    assert main(["stress", str(case), "--out", str(out)]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if "error" in line]  # besides progress lines
    assert len(err) == 1 and err[0].startswith("gearfe stress: error: axial regulation") and "did not converge" in err[0]
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]
