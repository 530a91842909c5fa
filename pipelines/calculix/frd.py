"""Strict reader of CalculiX result files: nodal blocks of the ASCII ``.frd`` file and the ``.dat`` totals.

The ``.frd`` format (CalculiX GraphiX manual, "Result Format"): a result block starts with a
``  100CL`` line (step time in columns 13-24, number of nodes in 25-36), then ``-4  NAME  ncomp``,
one ``-5`` line per component, then one ``-1`` record per node (node id in columns 4-13, then
values of 12 characters, at most six per line, continued on ``-2`` lines), closed by ``-3``.
CalculiX writes one block per requested field and increment; :func:`read_frd` keeps the last
block of each name (the end of the step). Names used here: ``DISP`` (U: D1..D3 [mm]), ``STRESS``
(S: SXX SYY SZZ SXY SYZ SZX [MPa], extrapolated to the nodes and averaged by CalculiX), ``FORC``
(RF [N]), ``CONTACT`` (CDIS and CSTR of the slave nodes: COPEN CSLIP1 CSLIP2 [mm], CPRESS
CSHEAR1 CSHEAR2 [MPa]; CPRESS > 0 in contact).

Nothing here is guessed: an unknown record, a short line or a count that does not match raises
:class:`tca.errors.GearfeError` naming the line.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tca.errors import GearfeError

__all__ = ["FrdBlock", "read_frd", "read_dat_totals", "read_dat_contact"]


@dataclass(frozen=True, eq=False)
class FrdBlock:
    """One nodal result block: name, step time, component names, node ids (1-based), values (k, ncomp)."""

    name: str
    time: float
    components: tuple[str, ...]
    nodes: np.ndarray
    values: np.ndarray

    def field(self, n_nodes: int, fill: float = 0.0) -> np.ndarray:
        """Values on nodes 1..n_nodes as an (n_nodes, ncomp) array (``fill`` where absent)."""
        out = np.full((n_nodes, len(self.components)), fill)
        keep = self.nodes <= n_nodes
        out[self.nodes[keep] - 1] = self.values[keep]
        return out


def _values(line: str, lineno: int) -> list[float]:
    body = line[13:].rstrip("\n")
    if len(body) % 12:
        raise GearfeError(f"frd line {lineno}: values are not 12 characters wide: {line.rstrip()!r}")
    return [float(body[i:i + 12]) for i in range(0, len(body), 12)]


def read_frd(path: str | Path) -> dict[str, FrdBlock]:
    """Last nodal block of each result name in an ASCII ``.frd`` file."""
    blocks: dict[str, FrdBlock] = {}
    with open(path) as fh:
        lines = fh.readlines()
    i, n = 0, len(lines)
    while i < n:
        line = lines[i]
        if not line.startswith("  100C"):
            i += 1
            continue
        try:
            time = float(line[12:24])
            count = int(line[24:36])
        except ValueError:
            raise GearfeError(f"frd line {i + 1}: bad result header {line.rstrip()!r}") from None
        head = lines[i + 1]
        if not head.startswith(" -4"):
            raise GearfeError(f"frd line {i + 2}: expected ' -4' after a 100C header, got {head.rstrip()!r}")
        name = head[5:13].strip()
        ncomp = int(head[13:18])
        comps = []
        j = i + 2
        while j < n and lines[j].startswith(" -5"):
            comps.append(lines[j][5:13].strip())
            j += 1
        values = [c for c in comps if c != "ALL"]  # 'ALL' (a vector's magnitude) is counted, not written
        if ncomp != len(comps) or not values:
            raise GearfeError(f"frd line {i + 2}: block {name} announces {ncomp} components, lists {comps}")
        comps, ncomp = values, len(values)
        ids = np.empty(count, np.int64)
        vals = np.empty((count, ncomp))
        k = 0
        while j < n and not lines[j].startswith(" -3"):
            rec = lines[j]
            if not rec.startswith(" -1"):
                raise GearfeError(f"frd line {j + 1}: expected a ' -1' node record in block {name}, got {rec.rstrip()!r}")
            row = _values(rec, j + 1)
            node = int(rec[3:13])
            j += 1
            while len(row) < ncomp and j < n and lines[j].startswith(" -2"):
                row += _values(lines[j], j + 1)
                j += 1
            if len(row) != ncomp or k >= count:
                raise GearfeError(f"frd line {j}: node {node} of block {name}: {len(row)} values for {ncomp} components"
                                  f" (record {k + 1} of {count})")
            ids[k], vals[k] = node, row
            k += 1
        if k != count:
            raise GearfeError(f"frd block {name} at line {i + 1}: {k} node records, header says {count}")
        blocks[name] = FrdBlock(name, time, tuple(comps), ids, vals)
        i = j + 1
    return blocks


def read_dat_totals(path: str | Path) -> dict[str, np.ndarray]:
    """From a ``.dat`` file: the last ``*NODE PRINT`` RF block of each node set, summed (N; N mm on rotation nodes).

    Handles both ``total force ... for set X`` (TOTALS=ONLY) and ``forces ... for set X`` (per node).
    """
    text = Path(path).read_text().splitlines()
    out: dict[str, np.ndarray] = {}
    i = 0
    while i < len(text):
        s = text[i].strip()
        if (s.startswith("total force") or s.startswith("forces")) and " for set " in s:
            name = s.split(" for set ")[1].split()[0]
            rows = []
            j = i + 2
            while j < len(text) and text[j].strip():
                parts = text[j].split()
                rows.append([float(x) for x in (parts if s.startswith("total") else parts[1:])])
                j += 1
            if not rows or any(len(r) != 3 for r in rows):
                raise GearfeError(f"dat line {i + 1}: expected rows of 3 forces after {s!r}")
            out[name] = np.sum(rows, axis=0)
            i = j
        else:
            i += 1
    return out


def read_dat_contact(path: str | Path) -> dict[tuple[str, str], dict]:
    """From a ``.dat`` file: the last ``*CONTACT PRINT`` CF statistics of each (slave, master) pair.

    Returns per pair ``force`` (total force on the slave surface [N], 3), ``normal_force`` (compressive
    normal force [N], > 0 in contact; CalculiX prints it with + = tension) and ``area`` [mm^2].
    """
    text = Path(path).read_text().splitlines()
    out: dict[tuple[str, str], dict] = {}
    for i, line in enumerate(text):
        s = line.strip()
        if not s.startswith("statistics for slave set"):
            continue
        words = s.replace(",", " ").split()
        slave, master = words[4], words[7]

        def numbers_after(header: str, start: int) -> tuple[list[float], int]:
            for j in range(start, min(start + 40, len(text))):
                if text[j].strip().startswith(header):
                    return [float(x) for x in text[j + 2].split()], j + 2
            raise GearfeError(f"dat line {start}: no {header!r} after the statistics of {slave}/{master}")

        force, j = numbers_after("total surface force", i)
        normal, _ = numbers_after("area,  normal force", j)
        if len(force) != 6 or len(normal) != 3:
            raise GearfeError(f"dat line {i + 1}: unexpected contact statistics of {slave}/{master}")
        out[(slave, master)] = {"force": np.array(force[:3]), "normal_force": -normal[1], "area": normal[0]}
    return out
