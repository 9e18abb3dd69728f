"""The sections of a LAMMPS data file that the package adds (``Grains``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

GRAINS_SECTION = "Grains"   # data-file section of fix property/atom i_grain d_stiffness


def read_grains(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ``Grains`` section of a data file: atom ids, grain ids, stiffness factors.

    Reads the section :func:`bonded_lattice.lattice.write_data` writes (header line, blank line, one
    ``atom-ID grain stiffness`` line per atom, ending at a blank line or the
    end of the file); raises ``ValueError`` naming the line if one is malformed
    and if the file has no such section.
    """
    lines = Path(path).read_text().splitlines()
    try:
        start = next(k for k, line in enumerate(lines)
                     if line.split("#", 1)[0].strip() == GRAINS_SECTION)
    except StopIteration:
        raise ValueError(f"{path}: no {GRAINS_SECTION} section") from None
    ids, grains, factors = [], [], []
    k = start + 2   # skip the blank line after the header
    while k < len(lines) and lines[k].strip():
        tokens = lines[k].split("#", 1)[0].split()
        try:
            if len(tokens) != 3:
                raise ValueError
            ids.append(int(tokens[0]))
            grains.append(int(tokens[1]))
            factors.append(float(tokens[2]))
        except ValueError:
            raise ValueError(f"{path}, line {k + 1}: {lines[k].strip()!r}: need "
                             "'atom-ID grain stiffness'") from None
        k += 1
    return np.array(ids, dtype=np.int64), np.array(grains, dtype=np.int64), np.array(factors)
