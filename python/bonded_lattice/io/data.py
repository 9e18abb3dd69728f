"""The sections of a LAMMPS data file that the package adds (``Grains``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

GRAINS_SECTION = "Grains"   # data-file section of fix property/atom i_grain d_stiffness [d_strength]


def read_grains(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ``Grains`` section of a data file: atom ids, grain ids, stiffness factors.

    Reads the section :func:`bonded_lattice.lattice.write_data` writes (header line, blank line, one
    ``atom-ID grain stiffness [strength]`` line per atom, ending at a blank line or the
    end of the file); raises ``ValueError`` naming the line if one is malformed
    and if the file has no such section.  :func:`read_grain_strengths` gives the
    strength factors.
    """
    ids, grains, stiffness, _ = _grains_table(path)
    return ids, grains, stiffness


def read_grain_strengths(path: str | Path) -> np.ndarray:
    """The per-particle strength factors of a data file's ``Grains`` section, in the order
    of its lines (its fourth column; 1 for every particle if it has three)."""
    return _grains_table(path)[3]


def _grains_table(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """ids, grains, stiffness and strength factors of the ``Grains`` section: every line
    with three columns or every line with four."""
    lines = Path(path).read_text().splitlines()
    try:
        start = next(k for k, line in enumerate(lines)
                     if line.split("#", 1)[0].strip() == GRAINS_SECTION)
    except StopIteration:
        raise ValueError(f"{path}: no {GRAINS_SECTION} section") from None
    ids, grains, factors, strengths = [], [], [], []
    columns = 0     # of the first line: 3 or 4, the same on every line
    k = start + 2   # skip the blank line after the header
    while k < len(lines) and lines[k].strip():
        tokens = lines[k].split("#", 1)[0].split()
        columns = columns or len(tokens)
        try:
            if len(tokens) != columns or columns not in (3, 4):
                raise ValueError
            ids.append(int(tokens[0]))
            grains.append(int(tokens[1]))
            factors.append(float(tokens[2]))
            strengths.append(float(tokens[3]) if columns == 4 else 1.0)
        except ValueError:
            need = ("'atom-ID grain stiffness strength', as the section's first line"
                    if columns == 4 else "'atom-ID grain stiffness' or 'atom-ID grain "
                    "stiffness strength'")
            raise ValueError(f"{path}, line {k + 1}: {lines[k].strip()!r}: need {need}") from None
        k += 1
    return (np.array(ids, dtype=np.int64), np.array(grains, dtype=np.int64), np.array(factors),
            np.array(strengths))
