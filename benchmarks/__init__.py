"""`make bench`: every area's speed-vs-error benchmark, one subprocess each, gathered in one report.

Each ``benchmarks.<area>`` module writes its markdown report (and plots) into
``<out>/<area>/``; this runner writes ``<out>/REPORT.md`` linking them. TCA runs on one core (the target is per core); the FE
benchmarks (``fem``, ``stress``: the speed-vs-error report of the sun–planet contact model) use both cores.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import subprocess
import sys
import time
from pathlib import Path

__all__ = ["main", "AREAS"]

# area -> (module, environment overrides)
ONE_CORE = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
AREAS = {
    "tca": ("benchmarks.tca", ONE_CORE),
    "fem": ("benchmarks.fem", {}),
    "mesher": ("benchmarks.mesher", {}),
    "part1": ("benchmarks.part1", {}),
    "part2": ("benchmarks.part2", {}),
    "part3": ("benchmarks.part3", {}),
    "stress": ("benchmarks.stress", {}),
    "reliability": ("benchmarks.reliability", ONE_CORE),
    "standard": ("benchmarks.standard", {}),
    "end_relief": ("benchmarks.end_relief", {}),
    "ltca": ("benchmarks.ltca", {}),
    "peer": ("benchmarks.peer", {}),
    "trains": ("benchmarks.trains", {}),
    "sizing": ("benchmarks.sizing", {}),
}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default="out/bench")
    ap.add_argument("--only", nargs="*", help="areas to run (default: all)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    report = ["# gearfe benchmarks", "", f"Started {time.strftime('%Y-%m-%d %H:%M:%S')}, "
              f"load {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores.", ""]
    status = 0
    t_all = time.perf_counter()
    for area, (mod, env) in AREAS.items():
        if args.only and area not in args.only:
            continue
        if importlib.util.find_spec(mod) is None:
            raise SystemExit(f"benchmark module {mod} is missing")
        t0 = time.perf_counter()
        sub = out / area
        p = subprocess.run([sys.executable, "-m", mod, "--out", str(sub)], env={**os.environ, **env})
        mds = sorted(sub.glob("*.md"))
        link = f"[{area}]({area}/{mds[0].name})" if mds else area
        report.append(f"- {link}: {'ok' if p.returncode == 0 else f'FAILED ({p.returncode})'}, "
                      f"{time.perf_counter() - t0:.0f} s")
        status |= p.returncode != 0
    report += ["", f"Total {time.perf_counter() - t_all:.0f} s, load at the end {os.getloadavg()[0]:.2f}."]
    (out / "REPORT.md").write_text("\n".join(report) + "\n")
    print(f"wrote {out / 'REPORT.md'}")
    return int(status)


if __name__ == "__main__":
    raise SystemExit(main())
