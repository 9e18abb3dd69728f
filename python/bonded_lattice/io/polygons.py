"""Grain polygons (:class:`Polygon`) and the plain polygon file: one polygon per line,
``grain x1 y1 x2 y2 x3 y3 ...`` (:func:`read_polygons`)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .tokens import line_error, parse_integers, parse_numbers


@dataclass(frozen=True)
class Polygon:
    """One grain's outline.

    grain: the grain id its particles get (Elle: the flynn number).
    vertices: (k, 2) corners in order around the polygon (either sense), the
        first not repeated at the end; from an Elle file unwrapped across the
        periodic cell, so that consecutive corners are neighbours.
    line: the line of the source file that defines it (0: none), for messages.
    """

    grain: int
    vertices: np.ndarray
    line: int = 0


def read_polygons(path: str | Path) -> list[Polygon]:
    """Grain polygons from a plain text file: one per line, ``grain x1 y1 x2 y2 x3 y3 ...``.

    At least three corners, in order around the polygon; ``#`` starts a
    comment.  Malformed lines raise ``ValueError`` naming the line.
    """
    polygons = []
    for number, raw in enumerate(Path(path).read_text().splitlines(), start=1):
        tokens = raw.split("#", 1)[0].split()
        if not tokens:
            continue
        grain = parse_integers(tokens[:1], path, number, "grain id")[0]
        xy = parse_numbers(tokens[1:], path, number, f"grain {grain} corners")
        if len(xy) % 2 or len(xy) < 6:
            raise line_error(path, number, f"grain {grain} has {len(xy)} coordinates: need "
                        "x y pairs of at least 3 corners")
        polygons.append(Polygon(grain, np.array(xy).reshape(-1, 2), number))
    if not polygons:
        raise ValueError(f"{path}: no polygons")
    return polygons
