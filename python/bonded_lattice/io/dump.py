"""Text dumps: atoms (``dump custom``, ``write_dump``) and local quantities (``dump local``).

The package's decks write atom dumps with ``modify sort id format float %.17g``, so the
values are the doubles LAMMPS held; the readers return float64 arrays.

A trajectory (several frames) is read with MDAnalysis (:func:`read_frames`).  Its
``positions`` are float32 (about 1e-9 m resolution on 1e-2 m coordinates, i.e.
percent errors on 1e-5 strains) and are shifted so that the box's lower corner is the
origin, so the coordinates are taken from the float64 ``ts.data`` columns
(``additional_columns``, MDAnalysis >= 2.8), which are sorted by id and neither
shifted nor rescaled.  MDAnalysis calls its lengths Angstrom but does not convert dump
values, so they stay in the run's units.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np


def _body(path: str | Path, item: str) -> tuple[list[str], np.ndarray]:
    """Column names of the first ``ITEM: <item>`` line of a one-frame dump and its rows."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: LAMMPS dump is missing")
    lines = path.read_text().splitlines()
    try:
        k = next(i for i, line in enumerate(lines) if line.startswith(f"ITEM: {item}"))
    except StopIteration:
        raise ValueError(f"{path}: no 'ITEM: {item}' line: not a LAMMPS {item.lower()} "
                         "dump") from None
    names = lines[k].split()[2:]
    body = [line.split() for line in lines[k + 1:] if line.strip()]
    if any(line[0] == "ITEM:" for line in body):
        raise ValueError(f"{path}: more than one frame; read trajectories with read_frames")
    try:
        rows = np.array(body, dtype=float).reshape(-1, len(names))
    except ValueError as exc:
        raise ValueError(f"{path}: rows do not match the columns {names} ({exc})") from exc
    return names, rows


def read_atom_dump(path: str | Path) -> tuple[list[str], np.ndarray]:
    """Column names and rows, sorted by the ``id`` column, of a one-frame atom dump
    (``dump custom`` or ``write_dump ... custom``)."""
    names, rows = _body(path, "ATOMS")
    if "id" in names:
        rows = rows[np.argsort(rows[:, names.index("id")], kind="stable")]
    return names, rows


def read_atom_frame(path: str | Path, step: int) -> tuple[list[str], np.ndarray]:
    """Column names and rows, sorted by ``id``, of the frame at time step ``step`` of a text
    atom trajectory (``dump custom``), read line by line without the other frames' rows; a
    ValueError names the file if it has no such frame."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: LAMMPS dump is missing")
    with path.open() as lines:
        for line in lines:
            if not line.startswith("ITEM: TIMESTEP") or int(next(lines)) != step:
                continue
            count = 0
            for line in lines:
                if line.startswith("ITEM: NUMBER OF ATOMS"):
                    count = int(next(lines))
                elif line.startswith("ITEM: ATOMS"):
                    names = line.split()[2:]
                    rows = np.array([next(lines).split() for _ in range(count)], dtype=float)
                    rows = rows.reshape(-1, len(names))
                    if "id" in names:
                        rows = rows[np.argsort(rows[:, names.index("id")], kind="stable")]
                    return names, rows
    raise ValueError(f"{path}: no frame at time step {step}")


def read_local_dump(path: str | Path) -> tuple[list[str], np.ndarray]:
    """Column names and rows of a one-frame ``dump local`` (for example of ``compute
    lattice/bond/local``: one row per bond), in the order LAMMPS wrote them."""
    return _body(path, "ENTRIES")


def read_bond_dump(path: str | Path) -> np.ndarray:
    """Rows of a one-frame bond dump, one per bond: the ``dump local`` of ``compute
    lattice/bond/local id1 id2 state x y z`` that the scene decks write
    (:data:`bonded_lattice.deck.BOND_RECORDS`), columns id1, id2, state (0 intact, 1
    broken in tension, 2 in shear, 3 contact), x, y, z; no bonds: a (0, 6) array."""
    rows = read_local_dump(path)[1]
    return rows if len(rows) else np.zeros((0, 6))


_COLUMNS = ["id", "x", "y", "z"]


def read_frames(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Timesteps ``(n_frames,)`` and positions ``(n_frames, n_atoms, 3)`` in metres, sorted by id.

    Raises ValueError naming the file if it is missing, empty or unreadable,
    or if the atoms (count or ids) change between frames.
    """
    import MDAnalysis as mda  # slow to import: only when a dump is read

    path = Path(path)
    if not path.is_file() or path.stat().st_size == 0:
        raise ValueError(f"{path}: LAMMPS dump is missing or empty")
    steps, frames, id_sets = [], [], []
    try:
        with warnings.catch_warnings():
            # masses and time step are guessed for the topology: irrelevant here
            warnings.simplefilter("ignore", UserWarning)
            u = mda.Universe(str(path), format="LAMMPSDUMP",
                             lammps_coordinate_convention="unscaled",
                             additional_columns=_COLUMNS)
            for ts in u.trajectory:
                steps.append(int(ts.data["step"]))
                id_sets.append(ts.data["id"].astype(np.int64))
                frames.append(np.column_stack([ts.data[c] for c in "xyz"]))
    except (ValueError, EOFError, IndexError, KeyError, OSError) as exc:
        raise ValueError(f"{path}: cannot read LAMMPS dump ({exc})") from exc
    # MDAnalysis assumes a fixed number of lines per frame and silently drops
    # a last frame that is shorter (fewer atoms, or cut off mid-write)
    with open(path) as f:
        n_headers = sum(line.startswith("ITEM: TIMESTEP") for line in f)
    if n_headers != len(steps):
        raise ValueError(f"{path}: {n_headers} frames but {len(steps)} of {u.atoms.n_atoms} "
                         "atoms each: the number of atoms changes or a frame is incomplete")
    for step, ids in zip(steps, id_sets):
        if not np.array_equal(ids, id_sets[0]):
            raise ValueError(f"{path}: the atoms at step {step} differ from those at step {steps[0]}")
    return np.array(steps, dtype=np.int64), np.array(frames, dtype=float)


