"""The ``gearfe`` command line: one module per subcommand, each with ``add_args`` and ``handle``.

Any :class:`tca.errors.GearfeError` (bad input, impossible geometry, a solve that does not
converge) is printed as one line on stderr and gives exit status 2, with no result files written.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import tomllib

from tca.errors import GearfeError

__all__ = ["main", "SUBCOMMANDS"]

# subcommand name -> module in pipelines implementing add_args(parser) and handle(args) -> int
SUBCOMMANDS = {
    "tca": "pipelines.cli.tca",
    "sweep": "pipelines.cli.sweep",
    "mesh": "pipelines.cli.mesh",
    "stress": "pipelines.cli.stress",
    "run": "pipelines.cli.run",
    "compare": "pipelines.cli.compare",
    "crosscheck": "pipelines.cli.crosscheck",
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
        p.set_defaults(_handler=mod.handle)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args._handler(args) or 0)
    except (GearfeError, tomllib.TOMLDecodeError, FileNotFoundError) as exc:
        print(f"gearfe {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
