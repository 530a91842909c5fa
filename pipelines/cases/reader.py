"""Reading gear data from case files (TOML): keys carry their units, every value is range-checked.

A gear table (``[gears.<name>]``)::

    teeth = 34
    module_mm = 2.0                  # normal module
    pressure_angle_deg = 20.0        # normal pressure angle
    face_width_mm = 30.0
    helix_deg = 10.0                 # helix angle at the pitch cylinder (sets the screw parameter)
    hand = "left"                    # "right" | "left"
    reference_helix_deg = 10.0       # optional: helix of the rack (transverse geometry); default helix_deg
    internal = false
    profile_shift = 0.0              # x, positive thickens the tooth
    addendum = 1.0                   # h_a / m
    tool_addendum = 1.25             # h_a0 / m
    tool_tip_radius = 0.25           # rho_f / m
    parabola_drive_per_mm = 0.008    # a_c of the driving (+y) flank's rack, Eq. (1.5)
    parabola_coast_per_mm = 0.005    # a_c of the coast (-y) flank's rack
    parabola_apex_mm = 0.0           # apex of the rack parabola from the pitch point
    runout_um = 0.0                  # eccentricity of the toothed body, Eqs. (3.5)-(3.6); <= 0.1 module
    runout_phase_deg = 0.0
    [gears.<name>.plunge]            # longitudinal crowning by a plunging disk, Eq. (1.6)
    disk_radius_mm = 100.0
    parabola_per_mm = 0.002

A misalignment table: ``d_gamma_arcmin`` (change of shaft angle), ``d_gamma_v_arcmin``,
``d_center_um`` (centre distance), ``d_ex_um`` (perpendicular to the centre line),
``d_axial_mm``. A ``[tca]`` table: ``cycles``, ``steps_per_cycle``, ``elastic_approach_mm``.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

from tca.crowning import DiskPlunge
from tca.errors import GearfeError, InputError
from tca.gear import Gear
from tca.pair import GearPair, Misalignment
from tca.pair_tca import TCAOptions
from tca.units import ARCMIN

from pipelines.cases.schema import Table

__all__ = ["load_case", "parse_case_text", "MAX_CASE_BYTES", "read_gear", "read_gears", "read_pair", "read_misalignment", "read_tca_options", "CASES_DIR"]

CASES_DIR = Path(__file__).parent  # the shipped case files sit beside this module


MAX_CASE_BYTES = 1 << 20  # a case file is a few kB; anything above 1 MiB is not a case file


def load_case(path: str | Path) -> Table:
    """Parse a TOML case file (UTF-8, an optional UTF-8 byte-order mark is skipped) into a strict :class:`Table`.

    Every failure (missing, unreadable, too large, not UTF-8, not TOML) is an
    :class:`~tca.errors.InputError` naming the file.
    """
    path = Path(path)
    name = str(path)
    try:
        if not path.is_file():
            raise InputError("CASE", name, "an existing TOML file")
        if path.stat().st_size > MAX_CASE_BYTES:
            raise InputError("CASE", name, f"a TOML case file of at most {MAX_CASE_BYTES} bytes",
                             f"{path.stat().st_size} bytes")
        raw = path.read_bytes()
    except OSError as e:
        raise InputError("CASE", name, "a readable TOML file", e.strerror or type(e).__name__) from None
    return Table(parse_case_text(raw, name), "")


def parse_case_text(raw: bytes, name: str = "CASE") -> dict:
    """TOML bytes -> dict, with encoding and syntax errors as one-line InputErrors naming `name`."""
    if raw.startswith(b"\xef\xbb\xbf"):  # UTF-8 byte-order mark (Windows editors): accepted and skipped
        raw = raw[3:]
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")) or (len(raw) > 1 and b"\x00" in raw[:2]):
        raise InputError("CASE", name, "a UTF-8 text file", "it is UTF-16: save it as UTF-8")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        line = raw[:e.start].count(b"\n") + 1
        raise InputError("CASE", name, "a UTF-8 text file",
                         f"byte 0x{raw[e.start]:02x} on line {line} is not UTF-8: save the file as UTF-8") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise InputError("CASE", name, "a TOML file", f"TOML syntax: {e}") from None


def read_gear(t: Table, name: str) -> Gear:
    """A :class:`tca.gear.Gear` from its case table (see the module docstring for keys)."""
    hand = t.get("hand", str, "right", choices=("right", "left"))
    plunge = None
    p = t.table("plunge", required=False)
    if p is not None:
        plunge = DiskPlunge(p.get("disk_radius_mm", float, lo=0.0, lo_open=True),
                            p.get("parabola_per_mm", float, lo=0.0, hi=0.1, hi_open=True))
        p.done()
    ref = t.get("reference_helix_deg", float, None, lo=0.0, hi=45.0, hi_open=True)
    try:
        g = Gear(
            name=name,
            teeth=t.get("teeth", int, lo=3, hi=2000),
            module=t.get("module_mm", float, lo=0.0, lo_open=True, hi=100.0),
            pressure_angle=math.radians(t.get("pressure_angle_deg", float, 20.0, lo=0.0, lo_open=True, hi=45.0, hi_open=True)),
            face_width=t.get("face_width_mm", float, lo=0.0, lo_open=True, hi=2000.0),
            helix=math.radians(t.get("helix_deg", float, 0.0, lo=0.0, hi=45.0, hi_open=True)),
            hand=1 if hand == "right" else -1,
            reference_helix=None if ref is None else math.radians(ref),
            internal=t.get("internal", bool, False),
            profile_shift=t.get("profile_shift", float, 0.0, lo=-1.5, hi=1.5),
            addendum=t.get("addendum", float, 1.0, lo=0.0, lo_open=True, hi=2.0),
            tool_addendum=t.get("tool_addendum", float, 1.25, lo=0.0, lo_open=True, hi=3.0),
            tool_tip_radius=t.get("tool_tip_radius", float, 0.25, lo=0.0, lo_open=True, hi=1.0, hi_open=True),
            parabola_pos=t.get("parabola_drive_per_mm", float, 0.0, lo=0.0, hi=0.5, hi_open=True),
            parabola_neg=t.get("parabola_coast_per_mm", float, 0.0, lo=0.0, hi=0.5, hi_open=True),
            parabola_apex=t.get("parabola_apex_mm", float, 0.0, lo=-50.0, hi=50.0),
            plunge=plunge,
            runout=t.get("runout_um", float, 0.0, lo=0.0, hi=1000.0) * 1e-3,
            runout_phase=math.radians(t.get("runout_phase_deg", float, 0.0)),
        )
    except InputError as e:  # name the key as it appears in the case file
        field = e.field if e.field.startswith(t.path) else f"{t.path}.{e.field.split('.', 1)[-1]}"
        raise InputError(field, e.value, e.valid) from None
    t.done()
    return g


def read_gears(case: Table, key: str = "gears") -> dict[str, Gear]:
    """All gears of ``[gears.*]``; geometry errors keep their gear name."""
    gt = case.table(key)
    gears = {}
    for name in list(gt.data):
        gears[name] = read_gear(gt.table(name), name)
    gt.done()
    return gears


def read_misalignment(t: Table | None) -> Misalignment:
    """A :class:`tca.pair.Misalignment` from a ``[misalignment]`` table (or none)."""
    if t is None:
        return Misalignment()
    m = Misalignment(
        d_gamma=t.get("d_gamma_arcmin", float, 0.0, lo=-120.0, hi=120.0) * ARCMIN,
        d_gamma_v=t.get("d_gamma_v_arcmin", float, 0.0, lo=-120.0, hi=120.0) * ARCMIN,
        d_center=t.get("d_center_um", float, 0.0, lo=-10000.0, hi=10000.0) * 1e-3,
        d_ex=t.get("d_ex_um", float, 0.0, lo=-10000.0, hi=10000.0) * 1e-3,
        d_axial=t.get("d_axial_mm", float, 0.0, lo=-10.0, hi=10.0),
    )
    t.done()
    return m


def read_tca_options(t: Table | None) -> TCAOptions:
    """A :class:`tca.pair_tca.TCAOptions` from a ``[tca]`` table (or the defaults)."""
    if t is None:
        return TCAOptions()
    o = TCAOptions(
        cycles=t.get("cycles", int, 2, lo=1, hi=50),
        steps_per_cycle=t.get("steps_per_cycle", int, 40, lo=4, hi=2000),
        elastic_approach=t.get("elastic_approach_mm", float, 0.0065, lo=0.0, lo_open=True, hi=1.0, hi_open=True),
    )
    t.done()
    return o


def read_pair(case: Table, gears: dict[str, Gear]) -> tuple[GearPair, str, str]:
    """The pair named by ``driver``/``driven`` with its ``[misalignment]`` and ``center_distance_mm``."""
    names = tuple(gears)
    driver = case.get("driver", str, choices=names)
    driven = case.get("driven", str, choices=names)
    if driver == driven:
        raise InputError("driven", driven, f"a gear other than the driver {driver!r}")
    cd = case.get("center_distance_mm", float, None, lo=0.0, lo_open=True)
    pair = GearPair(gears[driver], gears[driven], read_misalignment(case.table("misalignment", required=False)),
                    center_distance=cd)
    return pair, driver, driven


def gear_ref(case: Table, gears: dict[str, Gear], key: str) -> Gear:
    """The gear named by ``case[key]``."""
    name = case.get(key, str, choices=tuple(gears))
    return gears[name]


_ = GearfeError  # re-exported for handlers that catch broadly
