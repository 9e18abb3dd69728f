"""The two stress areas of a block, from a run's compact summary.

Our stress divides the platen force by the area between the centres of the outermost
particles (:meth:`bonded_lattice.lattice.Lattice.loaded_area`); the 2017 paper divides by
"the area of the model cross section", which we read as the outer extent: the centres'
span plus one diameter across each lateral direction.  The papers leave the choice open for
2D; both are shown side by side, and a strength under the outer area is the measured one
times ``centres / section``.
"""

from __future__ import annotations

__all__ = ["section_area", "section_factor"]


def section_area(run: dict) -> float:
    """The outer cross-section of the block of ``run`` (2D: per unit thickness)."""
    d = run["plan"]["d"]
    width = run["lateral_width_m"]
    if run["dim"] == 2:
        return width + d
    depth = run["plan"]["area"] / width
    return (width + d) * (depth + d)


def section_factor(run: dict) -> float:
    """centres area / outer area: multiplies a stress to put it on the outer area."""
    return run["plan"]["area"] / section_area(run)

