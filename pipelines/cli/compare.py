"""Two designs, one load case each, side by side (Numerical Example 1.3, Fig. 1.9).

``gearfe compare NEW.toml CONVENTIONAL.toml --out DIR`` runs both stress cases through
:func:`pipelines.report.run.run_pipeline` into ``DIR/new`` and ``DIR/conventional`` (each a complete
``gearfe run`` folder; the two designs side by side in two processes, :mod:`pipelines.report.designs`,
unless ``--jobs 1``) and writes:

* ``compare_zones.png`` — the contact zones of every mesh (rows: designs; columns: interface and
  member, e.g. the planet members 2a and 2b with the sun and with the ring) coloured by von Mises
  stress on ONE colour range for both designs, as Fig. 1.9 (a) and (b);
  ``compare_pressure.png`` — the same with the contact pressure (each design on its own range:
  an edge contact's peak is singular and would wash out the other design);
  ``compare_overview.png`` — the two whole models;
* ``report.html`` — self-contained page: the table, the finding and every picture of both designs side
  by side (one clipped von Mises range for both), with the case files; each design's folder has its own;
* ``compare.md`` / ``compare.csv`` / ``compare.json`` — per design and interface: load share of
  members a and b, maximum contact pressure, maximum von Mises stress, edge contact (TCA and FE),
  plus the design-level maxima and the torque balance.

Both cases must be of the same model and torque (designs are compared under one load).
The report's finding is evaluated, not assumed: ``finding`` in compare.json says whether the new
design shares the load between the members without edge contact and the conventional one loads
one member with edge contact (a member "shares" when it carries at least ``SHARED`` of the
interface's force).
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import time
from pathlib import Path

from tca.errors import InputError

from pipelines.cases.stress import torque_record
from pipelines.cli.run import add_overrides, progress, read_with_overrides, write_summary
from pipelines.cli.outdir import staged_output
from pipelines.report.figures import picture_range
from pipelines.report.compare import shared_comparison
from pipelines.report.designs import DesignSteps, run_designs
from pipelines.report.html import compare_html, run_html
from pipelines.report.run import add_images, run_pipeline, zone_limits, zone_name

__all__ = ["add_args", "handle", "compare_table", "finding", "SHARED", "LABELS"]

LABELS = ("new", "conventional")
SHARED = 0.2  # a member carrying at least this fraction of an interface's force shares the load


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("new", help="stress case of the new design, e.g. pipelines/cases/stress_part1_new.toml")
    p.add_argument("conventional", help="stress case of the conventional design")
    p.add_argument("--out", required=True, help="output folder")
    add_overrides(p)
    p.add_argument("--edges", action="store_true", help="draw the element edges on the teeth views")
    p.add_argument("--jobs", type=int, default=2, choices=(1, 2),
                   help="2 (default): the two designs run side by side in two processes (both models in memory at "
                        "once); 1: one after the other")


def compare_table(summaries: dict) -> list[dict]:
    """One row per design and interface: load shares, peaks, edge contact."""
    rows = []
    for label, s in summaries.items():
        for itf, d in s["interfaces"].items():
            share = s["load_share"][itf]["members"]
            row = {"design": label, "interface": itf}
            for mem in sorted(share):
                row[f"load_share_{mem}"] = share[mem]
            row.update({
                "max_contact_pressure_mpa": d["max_contact_pressure_mpa"],
                "max_von_mises_mpa": max(m["max_von_mises_mpa"] for m in d["members"].values()),
                "edge_contact_fe": d["edge_contact"],
                "edge_contact_members": ",".join(k for k, m in d["members"].items() if m["edge_contact"]) or "-",
                "tca_kinds": ",".join(f"{k}:{m['tca_kind']}" for k, m in d["members"].items()),
            })
            rows.append(row)
        rows.append({"design": label, "interface": "(model)", "max_contact_pressure_mpa": s["max_contact_pressure_mpa"],
                     "max_von_mises_mpa": s["max_von_mises_mpa"], "edge_contact_fe": s["fe_edge_contact"],
                     "edge_contact_tca": s["edge_contact"], "max_fillet_stress_mpa": s["max_fillet_stress_mpa"],
                     "torque_balance_error": s["torque_balance_error"], "dofs": s["dofs"]})
    return rows


def _sharing(s: dict) -> bool:
    return all(min(sh["members"].values()) >= SHARED and len(sh["members"]) > 1 for sh in s["load_share"].values())


def finding(summaries: dict) -> dict:
    """The report's finding checked on the results (module docstring)."""
    new, conv = (summaries[k] for k in LABELS)
    f = {"new_shares_load": _sharing(new), "new_edge_contact": bool(new["fe_edge_contact"] or new["edge_contact"]),
         "conventional_shares_load": _sharing(conv),
         "conventional_edge_contact": bool(conv["fe_edge_contact"] or conv["edge_contact"]), "shared_threshold": SHARED}
    f["reproduced"] = (f["new_shares_load"] and not f["new_edge_contact"] and not f["conventional_shares_load"]
                       and f["conventional_edge_contact"])
    return f


def _markdown(rows: list[dict], f: dict, summaries: dict) -> str:
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    lines = ["# New vs conventional design (Numerical Example 1.3, Fig. 1.9)" if "reproduced" in f else
             "# Two load cases compared: " + " vs ".join(summaries), ""]
    for label, s in summaries.items():
        lines.append(f"- **{label}**: {s.get('title', '')} (`{s.get('case', '')}`), φ1 = {s['position']['phi1_deg']:.4f} deg, "
                     f"{s['dofs']} DOF, total {s['total_s']:.1f} s")
    lines += ["", "| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    for r in rows:
        lines.append("| " + " | ".join(_cell(r.get(k, "")) for k in keys) + " |")
    if "reproduced" not in f:  # not Part 1's twin drives: what the two cases share
        lines += ["", "## What the two cases share", ""] + [f"- {k}: {v}" for k, v in f.items()]
        return "\n".join(lines) + "\n"
    lines += ["", "## Finding", "",
              f"- new design shares the load between the members (each >= {SHARED:g} of every interface's force): "
              f"{f['new_shares_load']}; edge contact: {f['new_edge_contact']}",
              f"- conventional design shares the load: {f['conventional_shares_load']}; edge contact: "
              f"{f['conventional_edge_contact']}",
              f"- the report's finding (new: shared, no edge contact; conventional: one member, edge contact) "
              f"reproduced: **{f['reproduced']}**", "",
              "von Mises images share one colour range; contact-pressure images have one range per design.", "",
              "![zones](compare_zones.png)", "", "![pressure](compare_pressure.png)", "", "![overview](compare_overview.png)"]
    return "\n".join(lines) + "\n"


def _cell(v) -> str:
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _train_kind(path: str) -> bool:
    from pipelines.cases.reader import load_case

    return load_case(path).data.get("kind") in ("isostatic", "planetary")


def _handle_trains(args) -> int:
    """Two train cases (kind 'isostatic' or 'planetary'): their loaded TCAs side by side (docs/trains.md)."""
    from pipelines.cases.kinds import read_case
    from pipelines.models.trains.ltca import compare_trains
    from pipelines.jsonio import plain

    for p in (args.new, args.conventional):
        if not _train_kind(p):
            raise InputError("kind", str(p), "a train case (kind 'isostatic' or 'planetary') like the other case")
    stems = (Path(args.new).stem, Path(args.conventional).stem)
    labels = stems if stems[0] != stems[1] else ("a", "b")
    cases = {k: read_case(p, "ltca")[1] for k, p in zip(labels, (args.new, args.conventional))}
    with staged_output(args.out) as tmp:
        s = compare_trains(cases, Path(tmp), progress)
        (Path(tmp) / "compare.json").write_text(json.dumps(plain({"rows": s["rows"], "finding": s["finding"],
                                                                  "files": s["files"]}), indent=2) + "\n")
    for r in s["rows"]:
        print(f"  {r['train']}: {r['title']}: K_gamma {r['k_gamma']:.4f}")
    print(f"  {s['finding']}")
    print(f"results in {args.out}/")
    return 0


def handle(args) -> int:
    t0 = time.perf_counter()
    if _train_kind(args.new) or _train_kind(args.conventional):
        return _handle_trains(args)
    cases = {LABELS[0]: read_with_overrides(args.new, args), LABELS[1]: read_with_overrides(args.conventional, args)}
    a, b = cases.values()
    if a.model != b.model:
        raise InputError("model", b.model, f"the model of the new design's case, {a.model!r} (compare like with like)")
    if abs(a.torque - b.torque) > 1e-9 * a.torque:
        raise InputError("torque_nm", b.torque * 1e-3, f"the new design's torque {a.torque * 1e-3:g} N m (one load case)")
    paths = {LABELS[0]: args.new, LABELS[1]: args.conventional}
    with staged_output(args.out) as tmp:
        tmp = Path(tmp)
        jobs = getattr(args, "jobs", 2)

        def say(label):
            return progress if jobs < 2 else (lambda msg: progress(f"({label}) {msg}"))

        def solve(label):
            progress(f"== {label} design: {paths[label]}")
            (tmp / label).mkdir()
            return run_pipeline(cases[label], tmp / label, say(label), images=False)

        def limits(run):
            # one von Mises range for both designs' zone images, one clipped top for their pictures
            return zone_limits(run.summary, run.mesh, run.result)["von_mises"], picture_range(run).hi

        def finish(label, run, vm, top):
            s = add_images(run, tmp / label, {"von_mises": vm}, say(label), top=top,
                           show_edges=getattr(args, "edges", False)).summary
            s = {"kind": "run", "case": str(paths[label]), **s, **torque_record(cases[label])}
            s["files"] = [*s["files"], "report.html"]
            write_summary(s, tmp / label / "summary.json")
            run_html(s, tmp / label, Path(paths[label]).read_text())
            return s

        summaries = run_designs(LABELS, DesignSteps(solve, limits, finish), jobs=jobs)
        zones = [(itf, mem) for itf, d in summaries[LABELS[0]]["interfaces"].items() for mem in d["members"]]
        imgs, pimgs, titles = [], [], []
        for label in LABELS:
            for itf, mem in zones:
                imgs.append(tmp / label / f"{zone_name(itf, mem)}.png")
                pimgs.append(tmp / label / f"{zone_name(itf, mem)}_pressure.png")
                sh = summaries[label]["load_share"][itf]["members"][mem]
                titles.append(f"({'a' if label == LABELS[0] else 'b'}) {label}: {itf}, member {mem}, share {sh:.2f}")
        from pipelines.render.plots import side_by_side  # matplotlib only when there is something to draw (1.5 s at import)

        cols = min(len(zones), 2)  # at most two panels a row: colour-bar ticks legible at page scale
        side_by_side(imgs, titles, tmp / "compare_zones.png", "von Mises stress [MPa] on the loaded flanks", ncols=cols)
        side_by_side(pimgs, titles, tmp / "compare_pressure.png", "contact pressure [MPa]", ncols=cols)
        side_by_side([tmp / k / "overview.png" for k in LABELS], list(LABELS), tmp / "compare_overview.png",
                     "von Mises stress [MPa]")
        rows = compare_table(summaries)
        f = finding(summaries) if a.model == "twin" else shared_comparison(summaries)  # Part 1's finding: twins only
        keys = []
        for r in rows:
            keys += [k for k in r if k not in keys]
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
        (tmp / "compare.csv").write_text(buf.getvalue())
        (tmp / "compare.md").write_text(_markdown(rows, f, summaries))
        compare_html(summaries, {k: tmp / k for k in LABELS}, rows, f, tmp / "report.html",
                     {k: Path(v).read_text() for k, v in paths.items()},
                     [(tmp / "compare_zones.png", "von Mises on the loaded flanks, one range for both designs (Fig. 1.9)"),
                      (tmp / "compare_pressure.png", "contact pressure, one range per design")])
        (tmp / "compare.json").write_text(json.dumps({"rows": rows, "finding": f, "cases": {k: str(v) for k, v in paths.items()},
                                                      "elapsed_s": time.perf_counter() - t0}, indent=2) + "\n")
    print((Path(args.out) / "compare.md").read_text())
    print(f"report: {Path(args.out) / 'report.html'} (self-contained, both designs side by side)")
    print(f"images: {Path(args.out) / 'compare_zones.png'}, {Path(args.out) / 'compare_pressure.png'}, "
          f"{Path(args.out) / 'compare_overview.png'}; each design's run in {args.out}/new and {args.out}/conventional")
    return 0
