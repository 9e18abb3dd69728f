"""What a finished Mike/Elle scene shows: its broken bonds, when they broke, which way.

Reads the scene decks' bond dumps (:func:`bonded_lattice.io.read_bond_dump`): the broken
bonds of a dump (:func:`broken_bonds`), the strain step of each break from the dumps
written every few steps (:func:`break_steps`), the bonds' orientations in the initial
lattice (:func:`bond_angles`) and their statistics (:func:`crack_normal_stats`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .io.dump import read_bond_dump


def broken_bonds(path: str | Path) -> np.ndarray:
    """(id1, id2, state, x, y) of the broken bonds (state 1 tension, 2 shear) in a dump."""
    rows = read_bond_dump(path)
    rows = rows[(rows[:, 2] == 1) | (rows[:, 2] == 2)]
    return rows[:, :5]


def break_steps(run_dir: str | Path) -> dict[tuple[int, int], int]:
    """Strain step (k of the dump's name) at which each bond was first seen broken,
    from the ``bonds.<k>.txt`` dumps (quasi-static: k is the strain step; dynamic:
    the time step)."""
    found: dict[tuple[int, int], int] = {}
    files = sorted(Path(run_dir).glob("bonds.*.txt"),
                   key=lambda p: int(p.name.split(".")[1]) if p.name.split(".")[1].isdigit()
                   else 1 << 62)
    for f in files:
        tag = f.name.split(".")[1]
        k = int(tag) if tag.isdigit() else -1
        for i, j, *_ in broken_bonds(f).tolist():
            found.setdefault((int(i), int(j)), k)
    return found


def bond_angles(pairs: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Orientation (degrees, 0-180 from the x axis) of bonds (id1, id2) in the initial lattice."""
    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    v = positions[pairs[:, 1] - 1, :2] - positions[pairs[:, 0] - 1, :2]
    return np.degrees(np.arctan2(v[:, 1], v[:, 0])) % 180.0


def crack_normal_stats(angles: np.ndarray) -> dict[str, float]:
    """Statistics of broken-bond orientations (degrees from x, i.e. from the extension axis).

    A tensile break of a central spring opens a crack normal to the bond.
    mean: the axial (mod 180) mean bond orientation, from the doubled-angle
    resultant; fraction_0: share of bonds at 0 degrees (parallel to x, the
    extension of the pure-shear scenes), fraction_60: at 60 or 120.
    """
    a = np.asarray(angles, dtype=float)
    if len(a) == 0:
        return {"n": 0, "mean": float("nan"), "resultant": 0.0, "fraction_0": float("nan"),
                "fraction_60": float("nan")}
    z = np.exp(2j * np.radians(a)).mean()
    mean = (np.degrees(np.angle(z)) / 2.0) % 180.0
    if mean > 90:
        mean -= 180.0
    horizontal = np.minimum(a, 180.0 - a) < 15.0
    return {"n": int(len(a)), "mean": float(mean), "resultant": float(abs(z)),
            "fraction_0": float(horizontal.mean()), "fraction_60": float((~horizontal).mean())}
