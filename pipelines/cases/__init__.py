"""Case files (TOML): the strict reader, the gear/pair/train readers, and the shipped cases (``*.toml`` here)."""

from pipelines.cases.reader import (ARCMIN, CASES_DIR, load_case, read_gear, read_gears, read_misalignment, read_pair,
                                    read_tca_options)
from pipelines.cases.schema import Table

__all__ = ["ARCMIN", "CASES_DIR", "Table", "load_case", "read_gear", "read_gears", "read_misalignment", "read_pair",
           "read_tca_options"]
