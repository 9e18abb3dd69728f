"""The files of LAMMPS' ``fix ave/time ... file`` in scalar mode (one line per output step).

Such a file starts with two comment lines, ``# Time-averaged data for fix ID`` and ``#
TimeStep name name ...``, then one line of numbers per output step.  The energy-budget decks
write ``breaking.dat`` in this format (from a ring buffer, after the run: the step and
:data:`bonded_lattice.decks.BREAKING_COLUMNS` at every step of a window around the failure).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .table import named_columns

HEADER = "# Time-averaged data for fix"


def read_ave_time(path: str | Path) -> dict[str, np.ndarray]:
    """The columns of a ``fix ave/time`` file by the names of its header (``TimeStep`` first).

    A file with the header and no data yet gives empty columns; a file that is not a
    scalar-mode ``fix ave/time`` file raises ``ValueError`` naming the file and what is wrong.
    """
    path = Path(path)
    with open(path) as f:
        first, second, third = f.readline(), f.readline(), f.readline()
    # vector mode adds a third header line, '# Row name ...', and one block of rows per step
    if (not first.startswith(HEADER) or not second.startswith("# TimeStep")
            or third.startswith("# Row")):
        raise ValueError(f"{path}: not a 'fix ave/time' file in scalar mode: the first two "
                         f"lines must be '{HEADER} ID' and '# TimeStep name ...'")
    return named_columns(path, second[1:].split())
