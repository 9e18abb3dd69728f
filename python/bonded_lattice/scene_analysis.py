"""What a finished Mike/Elle scene shows: its broken bonds, when they broke, which way.

Reads the scene decks' bond dumps (:func:`bonded_lattice.io.read_bond_dump`): the broken
bonds of a dump (:func:`broken_bonds`), the strain step of each break from the dumps
written every few steps (:func:`break_steps`) or their exact order from the dumps after
each of the first breaks (:func:`break_sequence`), the bonds' orientations in the initial
lattice (:func:`bond_angles`) and their statistics (:func:`crack_normal_stats`), and how
many of the first breaks lie near the box's edges, the walls or where they would be in a
periodic box (:func:`first_breaks_near_edges`).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .fractures import bond_midpoints
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


SEQUENCE_SOURCES = ("auto", "log", "dumps")


def break_sequence(run_dir: str | Path, source: str = "auto") -> np.ndarray:
    """(id1, id2) of the breaks in their exact order: from ``breaks.txt`` (source "log"),
    where the quasi-static decks' ``lattice/quasistatic ... breaks breaks.txt`` appends every
    break (time step, id1, id2, mode, ratio), or from the dumps ``break.<n>.txt`` (source
    "dumps") that a quasi-static deck with ``break_order`` writes after its n-th break (each
    holds one broken bond more than the one before); "auto": the log if the run has one.
    Empty if the run has neither."""
    if source not in SEQUENCE_SOURCES:
        raise ValueError(f"source = {source!r} is not known: use one of "
                         f"{', '.join(SEQUENCE_SOURCES)}")
    run_dir = Path(run_dir)
    log = run_dir / "breaks.txt"
    if source == "log" or (source == "auto" and log.exists()):
        if not log.exists():
            return np.zeros((0, 2), dtype=np.int64)
        rows = [line.split()[1:3] for line in log.read_text().splitlines() if line.strip()]
        return np.array(rows, dtype=np.int64).reshape(-1, 2)
    seen: set[tuple[int, int]] = set()
    order: list[tuple[int, int]] = []
    n = 1
    while (run_dir / f"break.{n}.txt").exists():
        broken = broken_bonds(run_dir / f"break.{n}.txt")[:, :2].astype(np.int64)
        new = [pair for pair in map(tuple, broken.tolist()) if pair not in seen]
        if len(new) != 1:
            raise ValueError(f"{run_dir / f'break.{n}.txt'}: {len(new)} new broken bonds, "
                             "need exactly 1 (a dump per break)")
        seen.add(new[0])
        order.append(new[0])
        n += 1
    return np.array(order, dtype=np.int64).reshape(-1, 2)


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


def outline_distance(points: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Distance of each point (x, y) to the nearest side of the rectangle ``lo``-``hi``
    (x0, y0)-(x1, y1); 0 for a point outside it."""
    q = np.asarray(points, dtype=float).reshape(-1, 2)
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    return np.maximum(np.minimum(q - lo, hi - q).min(axis=1), 0.0)


def edge_distance(pairs: np.ndarray, positions: np.ndarray,
                  period: tuple[float, float] | None = None) -> np.ndarray:
    """Distance of each bond (id1, id2) from the edges of the lattice: from its midpoint in
    the initial lattice (:func:`bonded_lattice.fractures.bond_midpoints`) to the nearest of
    the outermost rows and columns of particle centres (:func:`outline_distance`; the wall
    rows; in a periodic box the rows on either side of the seam, where the walls would
    be).  period: the box lengths (x, y) of a periodic box: a bond across the seam has its
    midpoint between the two images, outside the rows: distance 0."""
    p = np.asarray(positions, dtype=float)[:, :2]
    return outline_distance(bond_midpoints(pairs, p, period), p.min(axis=0), p.max(axis=0))


def first_breaks_near_edges(run_dir: str | Path, positions: np.ndarray, bonds: np.ndarray,
                            d: float, count: int = 100, strip: float = 3.0,
                            period: tuple[float, float] | None = None) -> dict:
    """Where the first breaks of a run lie: the share within ``strip`` d of the edges
    (:func:`edge_distance`) of the first ``count`` broken bonds, against the share of all
    the lattice's ``bonds`` (pairs of ids, every bond of the initial lattice) in that strip:
    breaks spread uniformly over the bonds would give the latter.

    With the dumps of each break (:func:`break_sequence`, ``order`` "break") the first
    ``count`` are exact (``n`` = count, or all of them if fewer were dumped), and
    ``first_d`` is the first break's distance from the edges in d.  Otherwise (``order``
    "step") they are dated by the bond dumps (:func:`break_steps`; the order within a
    strain step is not known), so the first ``count`` are all those of the first strain
    steps up to the one at which the count reaches ``count`` (or all breaks if fewer):
    ``n`` of them, the last at strain step ``step`` (breaks seen first in
    ``bonds.final.txt`` count as the last ones, step -1 if one of them is among the
    first)."""
    if count < 1:
        raise ValueError(f"count = {count} is out of range: need count >= 1")
    if not (strip > 0 and d > 0):
        raise ValueError(f"strip = {strip}, d = {d} are out of range: need both > 0")
    near_all = edge_distance(bonds, positions, period) <= strip * d
    expected = float(near_all.mean()) if len(near_all) else float("nan")
    sequence = break_sequence(run_dir)[:count]
    if len(sequence):
        dist = edge_distance(sequence, positions, period)
        return {"order": "break", "n": int(len(sequence)), "near": float((dist <= strip * d).mean()),
                "expected": expected, "strip_d": strip, "first_d": float(dist[0] / d)}
    late = 1 << 62
    dated = {key: (k if k >= 0 else late) for key, k in break_steps(run_dir).items()}
    if not dated:
        return {"order": "step", "n": 0, "step": -1, "near": float("nan"),
                "expected": expected, "strip_d": strip}
    steps = np.array(sorted(dated.values()))
    last = int(steps[min(count, len(steps)) - 1])
    first = np.array([key for key, k in dated.items() if k <= last], dtype=np.int64)
    near = edge_distance(first, positions, period) <= strip * d
    return {"order": "step", "n": int(len(first)), "step": last if last != late else -1,
            "near": float(near.mean()), "expected": expected, "strip_d": strip}


# the summary line lattice/quasistatic prints at the end of every call
RELAX_SUMMARY = re.compile(r"lattice/quasistatic: (\d+) bonds broke .*? in (\d+) relaxations "
                           r"\((\d+) (minimiser iterations|time steps|sweeps, (\d+) particle "
                           r"moves|solves, (\d+) factorisations)\)")


def relaxation_costs(log: str | Path, particles: int) -> dict[str, int]:
    """What the quasi-static calls of a run cost, summed over its strain steps (the summary
    lines of ``lattice/quasistatic`` in its log): bonds broken, relaxations, minimiser
    iterations, time steps, sweeps or solves (``iterations``), particle updates (``updates``:
    the particle moves of relax local; FIRE and damped dynamics evaluate every particle's
    force each iteration or step, iterations x particles; a solve of relax direct updates
    every particle) and the factorisations of relax direct (``factorisations``)."""
    out = {"breaks": 0, "relaxations": 0, "iterations": 0, "updates": 0, "factorisations": 0}
    for m in RELAX_SUMMARY.finditer(Path(log).read_text()):
        out["breaks"] += int(m.group(1))
        out["relaxations"] += int(m.group(2))
        out["iterations"] += int(m.group(3))
        out["updates"] += int(m.group(5)) if m.group(5) else int(m.group(3)) * particles
        out["factorisations"] += int(m.group(6)) if m.group(6) else 0
    return out
