"""Thermo tables of a LAMMPS screen output or log file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

Thermo = dict[str, np.ndarray]


def parse_thermo(text: str) -> list[Thermo]:
    """Thermo tables of a LAMMPS screen or log output, one dict per run.

    A table starts at a header line whose first word is ``Step`` and ends at
    ``Loop time``; rows with another number of values than the header (warnings
    printed between rows) and rows that are not numbers are passed over.
    """
    runs: list[Thermo] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].split()[:1] == ["Step"]:
            header = lines[i].split()
            rows = []
            i += 1
            while i < len(lines) and not lines[i].startswith("Loop time"):
                parts = lines[i].split()
                if len(parts) == len(header):
                    try:
                        rows.append([float(p) for p in parts])
                    except ValueError:
                        pass
                i += 1
            table = np.array(rows, dtype=float).reshape(-1, len(header))
            runs.append({h: table[:, k] for k, h in enumerate(header)})
        i += 1
    return runs


def read_thermo(path: str | Path) -> list[Thermo]:
    """The thermo tables of a log file (:func:`parse_thermo` of its text)."""
    return parse_thermo(Path(path).read_text())
