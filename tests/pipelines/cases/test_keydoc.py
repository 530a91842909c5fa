"""docs/cases.md lists every key the readers check (issue 24, item 8): the generated tables must match the readers."""

from pipelines.cases.keydoc import BEGIN, DOC, END, key_specs, markdown


def test_docs_cases_tables_match_the_readers():
    doc = DOC.read_text()
    assert BEGIN in doc and END in doc
    section = BEGIN + doc.split(BEGIN, 1)[1].split(END, 1)[0] + END
    assert section == markdown(), "docs/cases.md drifted from the readers: run python -m pipelines.cases.keydoc --write"


def test_the_tables_hold_the_keys_of_this_issue():
    pair = {s.path: s for s in key_specs("pair")}
    for k in ("driver_torque_nm", "driven_torque_nm", "torque_nm", "center_distance_mm", "ltca.positions",
              "gears.<gear>.tip_relief.start_roll_mm", "gears.<gear>.crowning.c_beta_um", "mesh.teeth"):
        assert k in pair, k
    assert pair["gears.<gear>.teeth"].default == "required" and pair["gears.<gear>.module_mm"].unit == "mm"
