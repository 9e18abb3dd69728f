"""Where a scene run's first breaks occur: at the box's walls or where the disorder puts them.

A run's bond dumps (``--bond-dumps K``: ``bonds.<k>.txt`` every K strain steps) date each
break by the first dump that shows it broken (:func:`bonded_lattice.scene_analysis.break_steps`).
The quasi-static decks also log every break in order (``breaks.txt``,
:func:`bonded_lattice.scene_analysis.break_sequence`); :func:`break_sites` takes the first
K from that log when the run has one.  Without it the breaks are ordered by step alone
(:func:`break_order`, ties in a step kept together and listed by bond id only to be
deterministic), and "the first K breaks" are all the breaks of the strain steps up to the
one in which the count reaches K (:func:`first_breaks`: K or more; a step that breaks many
bonds at once, an avalanche, takes them all).

"Where" in one number (:func:`wall_share`): the share of those breaks whose bond midpoint
lies closer than ``band`` to the box outline (the rectangle of the outermost particle
centres, the wall rows), against the share of all the lattice's bonds that do (the
uniform expectation on this lattice) and of the area (:func:`band_area_share`).  A ratio
near 1 means the first breaks ignore the walls; well above 1, the walls make them.  The
breaks of one crack are not independent draws, so no binomial test is offered.
:func:`break_sites` gathers it all for a run, :func:`first_breaks_png` draws runs side by
side.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .io.dump import read_bond_dump
from .fractures import bond_midpoints
from .scene_analysis import break_sequence, break_steps, outline_distance

Box = tuple[float, float, float, float]   # x0, x1, y0, y1


def break_order(dated: dict[tuple[int, int], int]) -> list[tuple[tuple[int, int], int]]:
    """The breaks ((id1, id2), step) ordered by step; within a step by bond id, which is not
    the order in which they broke (that is not recorded)."""
    return sorted(dated.items(), key=lambda item: (item[1], item[0]))


def first_breaks(dated: dict[tuple[int, int], int], k: int) -> tuple[np.ndarray, np.ndarray]:
    """The first ``k`` breaks of a run, completed to the end of their strain step: all the
    breaks of the steps up to the one in which the count reaches k (all breaks if the run
    broke fewer).  Returns (m, 2) bond ids and (m,) steps, ordered as :func:`break_order`."""
    if k < 1:
        raise ValueError(f"k = {k} is out of range: need k >= 1 breaks")
    order = break_order(dated)
    if not order:
        return np.zeros((0, 2), dtype=np.int64), np.zeros(0, dtype=np.int64)
    last = order[min(k, len(order)) - 1][1]
    chosen = [(pair, step) for pair, step in order if step <= last]
    return (np.array([pair for pair, _ in chosen], dtype=np.int64).reshape(-1, 2),
            np.array([step for _, step in chosen], dtype=np.int64))


def outline(positions: np.ndarray) -> Box:
    """The box outline: the rectangle of the outermost particle centres (x0, x1, y0, y1)."""
    p = np.asarray(positions, dtype=float)[:, :2]
    return (float(p[:, 0].min()), float(p[:, 0].max()), float(p[:, 1].min()),
            float(p[:, 1].max()))


def wall_share(points: np.ndarray, box: Box, band: float) -> float:
    """Share of the points closer than ``band`` to the box outline (NaN for no points)."""
    if not band > 0:
        raise ValueError(f"band = {band} is out of range: need > 0 (a distance)")
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(p) == 0:
        return float("nan")
    x0, x1, y0, y1 = box
    return float((outline_distance(p, (x0, y0), (x1, y1)) < band).mean())


def band_area_share(box: Box, band: float) -> float:
    """Share of the box's area closer than ``band`` to its outline: 1 - (W - 2 band)(H - 2
    band) / (W H), the expectation for points spread uniformly."""
    if not band > 0:
        raise ValueError(f"band = {band} is out of range: need > 0 (a distance)")
    x0, x1, y0, y1 = box
    w, h = x1 - x0, y1 - y0
    if not (w > 0 and h > 0):
        raise ValueError(f"box {box} is empty: need x1 > x0 and y1 > y0")
    return 1.0 - max(w - 2 * band, 0.0) * max(h - 2 * band, 0.0) / (w * h)


@dataclass(frozen=True)
class BreakSites:
    """The first breaks of one run and where they lie (:func:`break_sites`)."""

    label: str
    k: int                  # breaks asked for
    points: np.ndarray      # (m, 2) midpoints of the first m >= k breaks (initial lattice)
    steps: np.ndarray       # (m,) their strain steps
    box: Box                # the box outline
    d: float                # the particle diameter
    band: float             # the distance from the outline that counts as "at a wall"
    share: float            # share of the m breaks within band of the outline
    bond_share: float       # share of all the lattice's bonds within band (uniform expectation)
    area_share: float       # share of the area within band

    @property
    def enrichment(self) -> float:
        """share / bond_share: 1 where the walls do not attract the first breaks."""
        return self.share / self.bond_share if self.bond_share > 0 else float("nan")

    def as_dict(self) -> dict:
        """The numbers, for a summary (JSON)."""
        return {"label": self.label, "k": self.k, "breaks": int(len(self.points)),
                "last_step": int(self.steps.max()) if len(self.steps) else None,
                "band_d": self.band / self.d, "share": self.share, "bond_share": self.bond_share,
                "area_share": self.area_share, "enrichment": self.enrichment}


def break_sites(run_dir: str | Path, positions: np.ndarray, d: float, k: int = 100,
                band: float = 3.0, label: str = "", box: Box | None = None,
                period: tuple[float, float] | None = None) -> BreakSites:
    """The first ``k`` breaks of a finished run (:func:`first_breaks` of its bond dumps) and
    their share within ``band`` diameters of the box outline (``box``, default
    :func:`outline` of the positions), against the share of all bonds (from
    ``bonds.final.txt``) and of the area.  positions: the initial particle centres, ids
    1..n (e.g. ``build_model(scene).lattice.positions``).  period: the box lengths (x, y)
    of a periodic box, where a bond across the seam has its midpoint between the nearest
    images (:func:`bonded_lattice.fractures.bond_midpoints`), at the outline."""
    if not d > 0:
        raise ValueError(f"d = {d} is out of range: need > 0")
    run_dir = Path(run_dir)
    dated = break_steps(run_dir)
    if not dated:
        raise ValueError(f"{run_dir}: no bond dumps with broken bonds (run the scene with "
                         "--bond-dumps K)")
    p = np.asarray(positions, dtype=float)[:, :2]
    box = box or outline(p)
    pairs, steps = first_breaks(dated, k)
    exact = break_sequence(run_dir)[:k]
    if len(exact) == min(k, len(dated)):    # the log of the breaks in order
        pairs = exact
        steps = np.array([dated.get((int(a), int(b)), -1) for a, b in exact], dtype=np.int64)
    points = bond_midpoints(pairs, p, period)
    rows = read_bond_dump(run_dir / "bonds.final.txt")
    bonds = rows[rows[:, 2] != 3][:, :2].astype(np.int64)   # state 3: a contact, never a bond
    mids = bond_midpoints(bonds, p, period)
    return BreakSites(label=label or run_dir.name, k=k, points=points, steps=steps, box=box,
                      d=d, band=band * d, share=wall_share(points, box, band * d),
                      bond_share=wall_share(mids, box, band * d),
                      area_share=band_area_share(box, band * d))


def first_breaks_png(path: str | Path, sites: Sequence[BreakSites], title: str = "",
                     unit: float = 1e3) -> None:
    """Panels side by side, one per run: the box outline, the band along the walls
    (dashed), the first breaks coloured by their strain step, and the shares in the
    panel's title.  unit: factor from metres to the axes' unit (1e3: mm)."""
    from matplotlib.patches import Rectangle

    from .plotting import pyplot

    if not sites or not any(len(s.steps) for s in sites):
        raise ValueError(f"{len(sites)} runs with no breaks to draw: need at least one "
                         "BreakSites with breaks")
    plt = pyplot()
    fig, axes = plt.subplots(1, len(sites), figsize=(4.2 * len(sites) + 0.8, 4.6),
                             squeeze=False)
    lo = min(int(s.steps.min()) for s in sites if len(s.steps))
    hi = max(int(s.steps.max()) for s in sites if len(s.steps))
    for ax, s in zip(axes[0], sites):
        x0, x1, y0, y1 = (unit * v for v in s.box)
        b = unit * s.band
        ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, lw=1.2, color="k"))
        ax.add_patch(Rectangle((x0 + b, y0 + b), x1 - x0 - 2 * b, y1 - y0 - 2 * b, fill=False,
                               lw=0.8, ls="--", color="0.5"))
        order = np.argsort(-s.steps, kind="stable")   # the earliest drawn on top
        sc = ax.scatter(unit * s.points[order, 0], unit * s.points[order, 1], s=10,
                        c=s.steps[order], cmap="viridis", vmin=lo, vmax=max(hi, lo + 1), lw=0)
        pad = 0.03 * max(x1 - x0, y1 - y0)
        ax.set_xlim(x0 - pad, x1 + pad)
        ax.set_ylim(y0 - pad, y1 + pad)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)" if unit == 1e3 else "x")
        ax.set_ylabel("y (mm)" if unit == 1e3 else "y")
        ax.set_title(f"{s.label}: first {len(s.points)} breaks (steps <= {int(s.steps.max())})\n"
                     f"within {s.band / s.d:g} d of a wall: "
                     f"{100 * s.share:.0f} % (bonds {100 * s.bond_share:.0f} %, "
                     f"area {100 * s.area_share:.0f} %)", fontsize=8)
    fig.colorbar(sc, ax=list(axes[0]), label="strain step of the break", shrink=0.8)
    if title:
        fig.suptitle(title, fontsize=9)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)
