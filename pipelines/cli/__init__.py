"""The ``gearfe`` command line: one module per subcommand, each with ``add_args`` and ``handle``.

The error contract (docs/errors.md):

* any :class:`tca.errors.GearfeError` or :class:`fem.errors.FEError` (bad input, impossible geometry, a solve that does not
  converge, a model too large for the machine) is printed as one line on stderr and gives exit
  status 2, with no result files written; ``--out`` is checked before any work
  (:func:`pipelines.cli.outdir.check_out`), ``--force`` allows a non-empty folder;
* SIGINT (Ctrl-C) and SIGTERM (``timeout``, batch schedulers) stop the run with one line and exit
  status 130 / 143 (:mod:`pipelines.cli.interrupt`: at the next progress line at the latest); staged output folders are removed on the way out (sweeps keep their finished
  points and resume);
* a run whose own accuracy check misses a target (``gearfe ltca`` with ``check_positions``) writes its
  results and exits 3 with one line naming the missed target;
* an unexpected exception (a bug) is one line naming its type and exit status 70; set
  ``GEARFE_TRACEBACK=1`` to see the traceback.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

from pipelines.errors import USER_ERRORS

from pipelines.cli.interrupt import Terminated, check_interrupted, install, restore
from pipelines.render import offscreen
from pipelines.render.settings import picture_settings

__all__ = ["main", "SUBCOMMANDS", "Terminated", "check_interrupted", "EXIT_INPUT", "EXIT_CHECK", "EXIT_BUG", "EXIT_SIGINT",
           "EXIT_SIGTERM"]

EXIT_INPUT = 2  # bad input, impossible geometry, a failed solve, a model too large
EXIT_CHECK = 3  # finished and wrote its results, but its own accuracy check missed a target (gearfe ltca)
EXIT_BUG = 70  # an unexpected exception (EX_SOFTWARE)
EXIT_SIGINT = 130  # 128 + SIGINT
EXIT_SIGTERM = 143  # 128 + SIGTERM
# subcommands whose output folder may be reused without --force when it holds this marker (resume)
RESUMABLE = {"sweep": "sweep.json"}



# subcommand name -> module in pipelines implementing add_args(parser) and handle(args) -> int
SUBCOMMANDS = {
    "tca": "pipelines.cli.tca",
    "sweep": "pipelines.cli.sweep",
    "mesh": "pipelines.cli.mesh",
    "stress": "pipelines.cli.stress",
    "run": "pipelines.cli.run",
    "compare": "pipelines.cli.compare",
    "ltca": "pipelines.cli.ltca",
    "crosscheck": "pipelines.cli.crosscheck",
    "rate": "pipelines.cli.rate",
}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="gearfe",
        description="Tooth contact analysis, meshing and contact FE of high-ratio gear drives.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, modname in SUBCOMMANDS.items():
        mod = importlib.import_module(modname)
        p = sub.add_parser(name, help=mod.__doc__.strip().splitlines()[0], description=mod.__doc__)
        mod.add_args(p)
        if any(a.dest == "out" for a in p._actions):
            p.add_argument("--force", action="store_true",
                           help="write into an existing, non-empty --out folder (same-named files are replaced)")
        p.set_defaults(_handler=mod.handle)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    offscreen()  # images are rendered without a display (EGL), set up here and not at import
    where = f"gearfe {args.command}"
    old = install()
    try:
        picture_settings()  # GEARFE_RENDER_SAMPLES, GEARFE_PLOT_DPI_SCALE, GEARFE_PNG_COMPRESSION: checked before any work
        if hasattr(args, "out"):
            from pipelines.cli.outdir import check_out

            check_out(args.out, getattr(args, "force", False), RESUMABLE.get(args.command))
        return int(args._handler(args) or 0)
    except USER_ERRORS as exc:
        print(f"{where}: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print(f"{where}: interrupted (SIGINT); no partial results left", file=sys.stderr)
        return EXIT_SIGINT
    except Terminated:
        print(f"{where}: terminated (SIGTERM); no partial results left", file=sys.stderr)
        return EXIT_SIGTERM
    except Exception as exc:  # a bug: one line, distinct status, traceback on request
        if os.environ.get("GEARFE_TRACEBACK"):
            raise
        print(f"{where}: internal error: {type(exc).__name__}: {_one_line(exc)} (a bug: please report it with "
              "the case file; GEARFE_TRACEBACK=1 shows the traceback)", file=sys.stderr)
        return EXIT_BUG
    finally:
        restore(old)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
