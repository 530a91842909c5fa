"""The hostile-input corpus: cases that every ``gearfe`` subcommand must refuse cleanly.

Each entry is ``(id, command, base, edits, args, raw, expect)``:

* ``command`` a subcommand; ``base`` a shipped case (``pipelines/cases/<base>.toml``) written to a
  temporary folder after ``edits`` (dotted keys, list indices as numbers; ``DELETE`` removes a key);
* ``args`` extra command-line arguments (``{out}`` the output folder, ``{file}`` an existing file,
  ``{full}`` a non-empty folder);
* ``raw`` replaces the file's bytes (:data:`RAW`: other encodings, binary data, a folder...);
* ``expect`` a text the one error line must contain ("" for any).

The contract (docs/errors.md): exit status 2, exactly one error line on stderr, no traceback, no
files written, no temporary folder left, and every check before any heavy work (milliseconds).
"""

from __future__ import annotations

DELETE = "__delete__"
BAD_TYPES = ("text", True, [1, 2], {"zz": 1})  # never valid where a number is read

# raw file contents replacing a case file (the test turns the name into bytes)
RAW = ("random_bytes", "utf16", "latin1_comment", "nul_byte", "not_toml", "huge", "directory", "missing",
       "truncated_table", "bom_and_unknown_key")

_PAIR_NUMBERS = ("gears.sun.teeth", "gears.sun.module_mm", "gears.planet.face_width_mm", "gears.planet.helix_deg",
                 "misalignment.d_gamma_arcmin", "tca.cycles", "tca.steps_per_cycle")

_PAIR_RANGES = [
    ("gears.sun.teeth", 2), ("gears.sun.teeth", 0), ("gears.sun.teeth", -5), ("gears.sun.teeth", 100000),
    ("gears.sun.teeth", 41.5), ("gears.sun.module_mm", 0.0), ("gears.sun.module_mm", -1.0),
    ("gears.sun.module_mm", 1e308), ("gears.sun.module_mm", float("nan")), ("gears.sun.pressure_angle_deg", 0.0),
    ("gears.sun.pressure_angle_deg", 50.0), ("gears.sun.face_width_mm", 0.0), ("gears.sun.face_width_mm", -30.0),
    ("gears.sun.helix_deg", 45.0), ("gears.sun.helix_deg", float("inf")), ("gears.sun.helix_deg", -1.0),
    ("gears.sun.runout_um", 5000.0), ("gears.sun.runout_um", 500.0), ("gears.sun.runout_um", -1.0),
    ("gears.sun.hand", "up"), ("gears.sun.profile_shift", 5.0), ("gears.sun.addendum", 0.0),
    ("gears.sun.tool_addendum", 0.5), ("gears.sun.tool_tip_radius", 1.0), ("gears.planet.parabola_drive_per_mm", 0.5),
    ("gears.planet.plunge.disk_radius_mm", 0.0), ("misalignment.d_gamma_arcmin", 500.0),
    ("misalignment.d_center_um", 1e6), ("tca.cycles", 0), ("tca.cycles", 51), ("tca.steps_per_cycle", 3),
    ("tca.steps_per_cycle", 10**6), ("tca.elastic_approach_mm", 0.0), ("tca.elastic_approach_mm", 1.0),
    ("center_distance_mm", -10.0), ("center_distance_mm", 0.0), ("driver", "moon"), ("driven", "sun"),
    ("kind", "gearbox"), ("gears.sun.internal", "yes"),
]

_PAIR_MISSING = ("kind", "driver", "driven", "gears", "gears.sun.teeth", "gears.sun.module_mm",
                 "gears.planet.face_width_mm")
_PAIR_UNKNOWN = ("colour", "gears.sun.tooth", "tca.cycle", "misalignment.dgamma", "gears.planet.plunge.radius",
                 "gears.moon")

_PLANETARY = [
    ({"planets": 0}, "planets"), ({"planets": 7}, "planets"), ({"planets": 100}, "planets"),
    ({"member_gap_mm": -1.0}, "member_gap_mm"), ({"installment.d_ex_um": [1.0]}, "installment.d_ex_um"),
    ({"installment.d_ex_um": [1e9, 0.0, 0.0, 0.0, 0.0]}, "installment.d_ex_um"),
    ({"regulation.tol_arcsec": 0.0}, "regulation.tol_arcsec"),
    ({"regulation.max_iterations": 1}, "regulation.max_iterations"), ({"regulation.colour": 1}, "regulation.colour"),
    ({"extra": 1}, "extra"), ({"gears.sun.runout_um": 20.0}, "runout_um"), ({"gears.moon": {"teeth": 20}}, "gears"), ({"gears.ring.internal": False}, ""),
]

_ISOSTATIC = [
    ({"train.planets": 2}, "train.planets"), ({"train.planets": 4}, "train.planets"),
    ({"run.positions": 0}, "run.positions"), ({"run.carrier_revolutions": -1.0}, "run.carrier_revolutions"),
    ({"solver.method": "magic"}, "solver.method"), ({"train.planet_errors.0.planet": 9}, "planet"),
    ({"train.colour": "red"}, "train.colour"), ({"planets": "triple_crowned"}, "planets"),
    ({"crowning.disk_radius_mm": -1.0}, "crowning.disk_radius_mm"), ({"run.sun_revolutions": 1.0}, ""),
]

_FACE = [
    ({"delta_rad": 10.0}, "delta_rad"), ({"use": "both"}, "use"), ({"loss_per_mesh": 0.6}, "loss_per_mesh"),
    ({"gear1.teeth": 2}, "gear1.teeth"), ({"tca.cycles": 0}, "tca.cycles"),
    ({"plots.delta_offsets_rad": []}, "plots.delta_offsets_rad"),
]

_STRESS = [
    ({"fe.youngs_modulus_mpa": 1e-30}, "youngs_modulus_mpa"), ({"fe.youngs_modulus_mpa": 206.8}, "looks like GPa"),
    ({"fe.youngs_modulus_mpa": 2.068e11}, "looks like Pa"), ({"fe.poisson_ratio": 0.5}, "poisson_ratio"),
    ({"torque_nm": -1.0}, "torque_nm"), ({"mesh.refine": 0.0}, "mesh.refine"), ({"mesh.refine": 11.0}, "mesh.refine"),
    ({"mesh.teeth": 0}, "mesh.teeth"), ({"mesh.contact_size_mm": -1.0}, "mesh.contact_size_mm"),
    ({"position": 1.5}, "position"), ({"position": "middle"}, "position"), ({"fe.element": "C3D20"}, "fe.element"),
    ({"colour": "red"}, "colour"), ({"gears.planet.runout_um": 5000.0}, "runout_um"),
    ({"gears.sun.runout_um": 20.0}, "runout_um"),
]

_SWEEP = [
    ({"axes.0.key": "gears.sun.tooth"}, "tooth"), ({"axes.0.values": [-6.0, "3.0x", 0.0]}, "d_gamma_arcmin"),
    ({"axes.0.key": "center_distance_mm", "axes.0.values": [-10.0]}, "center_distance_mm"),
    ({"axes.0.values": list(range(1000)), "axes.1.values": [0.001] * 1000}, "at most 100000 points"),
    ({"axes.0.values": []}, "values"), ({"task": "fem"}, "task"), ({"axes.1.key": "misalignment.d_gamma_arcmin"}, "key"),
    ({"axes.0.values": [500.0]}, "d_gamma_arcmin"), ({"axes": DELETE}, "axes"), ({"base": "nope.toml"}, "CASE"),
    ({"axes.0.key": "gears.sun.teeth.x"}, "axes.key"), ({"colour": 1}, "colour"),
]

_STRESS_SWEEP = [
    ({"positions.steps": 7}, "positions.steps"), ({"positions.start": 500}, "positions.start"),
    ({"axes.0.values": [78.0, -1.0]}, "torque_nm"), ({"axes.0.key": "fe.youngs_modulus_mpa", "axes.0.values": [206.8]},
                                                     "looks like GPa"),
    ({"positions.phi1_deg": [1.0]}, "positions"), ({"axes.0.key": "mesh.refine", "axes.0.values": [0.05]}, "mesh.refine"),
]

_MESH = [
    ({"mesh.teeth": 0}, "mesh.teeth"), ({"mesh.element_type": "C3D20"}, "mesh.element_type"),
    ({"pair_case": "nope.toml"}, "pair_case"), ({"gear": "moon"}, "gear"), ({"position": "middle"}, "position"),
    ({"mesh.growth": 10.0}, "mesh.growth"), ({"mesh.contact_size_mm": 0.0001}, "mesh.contact_size_mm = 0.0001"),
    ({"mesh.coarse_size_mm": 0.01, "mesh.contact_size_mm": DELETE, "mesh.fillet_size_mm": DELETE},
     "mesh.coarse_size_mm = 0.01"),
    ({"mesh.teeth": 2000}, "mesh.teeth = 2000"), ({"colour": 1}, "colour"), ({"mesh.colour": 1}, "mesh.colour"),
]

_INTERNAL_CLASH = {"gears.sun.teeth": 34, "gears.planet.teeth": 40, "gears.planet.internal": True,
                   "gears.planet.hand": "right", "gears.planet.plunge": DELETE}

_ARGS = [
    ("tca", "part1_sun_planet", ["--out", ""], "--out"),
    ("tca", "part1_sun_planet", ["--out", "{file}"], "--out"),
    ("tca", "part1_sun_planet", ["--out", "{file}/x"], "--out"),
    ("tca", "part1_sun_planet", ["--out", "/proc/gearfe-x"], "--out"),
    ("tca", "part1_sun_planet", ["--out", "{full}"], "--force"),
    ("mesh", "mesh_part1_sun_planet", ["--out", "{full}"], "--force"),
    ("stress", "stress_pair_small", ["--out", "{file}"], "--out"),
    ("run", "stress_pair_small", ["--out", "{out}", "--position", "\u00b2"], "--position"),
    ("run", "stress_pair_small", ["--out", "{out}", "--position", "1e3"], "position"),
    ("run", "stress_pair_small", ["--out", "{out}", "--refine", "nan"], "mesh.refine"),
    ("run", "stress_pair_small", ["--out", "{out}", "--refine", "-1"], "mesh.refine"),
    ("run", "stress_pair_small", ["--out", "{out}", "--phi1-deg", "inf"], "phi1_deg"),
    ("compare", "stress_pair_small", ["--out", "{out}", "--refine", "0"], "mesh.refine"),
    ("sweep", "sweep_part1_misalignment", ["--out", "{out}", "--workers", "-1"], "--workers"),
    ("sweep", "sweep_part1_misalignment", ["--out", "{out}", "--scheduler", "nonsense:"], "--scheduler"),
    ("sweep", "sweep_part1_misalignment", ["--out", "{out}", "--scheduler", "tcp://127.0.0.1:1"], "--scheduler"),
    ("sweep", "sweep_part1_misalignment", ["--out", "{file}"], "--out"),
]

_RAW_COMMANDS = (("tca", "part1_sun_planet"), ("sweep", "sweep_part1_misalignment"), ("mesh", "mesh_part1_sun_planet"),
                 ("stress", "stress_pair_small"), ("run", "stress_pair_small"), ("compare", "stress_pair_small"))


def corpus() -> list[tuple]:
    """All entries (see the module docstring)."""
    out = []
    for key in _PAIR_NUMBERS:
        for i, bad in enumerate(BAD_TYPES):
            out.append((f"type-{key}-{i}", "tca", "part1_sun_planet", {key: bad}, [], None, key))
    for key, bad in _PAIR_RANGES:
        out.append((f"range-{key}={bad!r}", "tca", "part1_sun_planet", {key: bad}, [], None, key.split(".")[-1]))
    for key in _PAIR_MISSING:
        out.append((f"missing-{key}", "tca", "part1_sun_planet", {key: DELETE}, [], None, key.split(".")[-1]))
    for key in _PAIR_UNKNOWN:
        out.append((f"unknown-{key}", "tca", "part1_sun_planet", {key: 1}, [], None, key.split(".")[-1]))
    out.append(("internal-34-40-tip-clash", "tca", "part1_sun_planet", _INTERNAL_CLASH, [], None, "tip clash"))
    for base, rows in (("part1_planetary_regulation", _PLANETARY), ("part3_indexing", _ISOSTATIC),
                       ("part2_reducer", _FACE)):
        for i, (edits, expect) in enumerate(rows):
            out.append((f"{base}-{i}", "tca", base, edits, [], None, expect))
    for cmd in ("stress", "run", "compare"):
        for i, (edits, expect) in enumerate(_STRESS):
            out.append((f"{cmd}-{i}", cmd, "stress_pair_small", edits, [], None, expect))
    for i, (edits, expect) in enumerate(_SWEEP):
        out.append((f"sweep-{i}", "sweep", "sweep_part1_misalignment", edits, [], None, expect))
    for i, (edits, expect) in enumerate(_STRESS_SWEEP):
        out.append((f"sweep-stress-{i}", "sweep", "sweep_stress_positions", edits, [], None, expect))
    for i, (edits, expect) in enumerate(_MESH):
        out.append((f"mesh-{i}", "mesh", "mesh_part1_sun_planet", edits, [], None, expect))
    for i, (cmd, base, args, expect) in enumerate(_ARGS):
        out.append((f"args-{i}-{cmd}", cmd, base, {}, args, None, expect))
    for cmd, base in _RAW_COMMANDS:
        for raw in RAW:
            out.append((f"raw-{cmd}-{raw}", cmd, base, {}, [], raw, "CASE" if raw != "bom_and_unknown_key" else "zz"))
    return out
