"""Text tables of numbers whose first line names the columns: ``# name name ...``.

The scene decks write their ``scene.dat`` so (``print "# k step ..." file scene.dat``, then
one ``print ... append`` per output line); :func:`read_table` returns the columns by name.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np


def read_table(path: str | Path, names: Sequence[str] | None = None) -> dict[str, np.ndarray]:
    """The columns of a table, by the names of its ``# name ...`` header line.

    names: the columns the caller expects; a file whose header names others (or is missing)
    raises ``ValueError`` naming the file and both lists.  Lines starting with ``#`` after
    the header are skipped.
    """
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: table is missing")
    with open(path) as f:
        first = f.readline()
    header = first[1:].split() if first.startswith("#") else []
    if not header:
        raise ValueError(f"{path}: the first line is not a '# name name ...' header")
    if names is not None and list(names) != header:
        raise ValueError(f"{path}: the columns are {header}: need {list(names)}")
    return named_columns(path, header)


def named_columns(path: Path, names: Sequence[str]) -> dict[str, np.ndarray]:
    """The numbers of a text file (``#`` lines skipped) as the columns ``names``; a line with
    another count of values raises ``ValueError`` naming the file and the columns."""
    rows = np.loadtxt(path, comments="#", ndmin=2)
    if rows.size and rows.shape[1] != len(names):
        raise ValueError(f"{path}: {rows.shape[1]} values per line for the {len(names)} "
                         f"columns {list(names)}")
    rows = rows.reshape(-1, len(names))
    return {name: rows[:, k] for k, name in enumerate(names)}
