"""Elle files (the microstructure format of Elle): the grains (flynns) as polygons, and the
periodic unit cell (:func:`read_elle`, :func:`read_elle_cell`)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .polygons import Polygon
from .tokens import is_number, line_error, parse_integers, parse_numbers


@dataclass
class _ElleFile:
    cell_lo: np.ndarray
    cell_hi: np.ndarray
    flynns: list[tuple[int, list[int], int]]   # (flynn id, node ids, line)
    nodes: dict[int, tuple[float, float]]


def _parse_elle(path: str | Path) -> _ElleFile:
    """Read the OPTIONS CellBoundingBox, FLYNNS and LOCATION sections of an Elle file."""
    section = None
    flynns: list[tuple[int, list[int], int]] = []
    nodes: dict[int, tuple[float, float]] = {}
    seen: set[str] = set()
    bbox: list[float] = []
    bbox_line = 0
    in_bbox = False
    for number, raw in enumerate(Path(path).read_text().splitlines(), start=1):
        tokens = raw.split("#", 1)[0].split()
        if not tokens:
            continue
        head = tokens[0]
        if head[0].isalpha() and not any(is_number(t) for t in tokens[1:]):
            # a section keyword (alone or followed by names, e.g. "STRESS TAU_XX")
            section = head
            in_bbox = False
            if head == "REGIONS":
                raise line_error(path, number, "the old REGIONS format is not supported: "
                            "convert the file to FLYNNS with a current Elle")
            if head in seen and head in ("FLYNNS", "LOCATION"):
                raise line_error(path, number, f"a second {head} section")
            seen.add(head)
            continue
        if section == "OPTIONS":
            if head == "CellBoundingBox":
                bbox, bbox_line, in_bbox = [], number, True
                bbox += parse_numbers(tokens[1:], path, number, "CellBoundingBox")
            elif head[0].isalpha():
                in_bbox = False      # another option: ignored
            elif in_bbox:            # the corners continue on the next lines
                bbox += parse_numbers(tokens, path, number, "CellBoundingBox")
            else:
                raise line_error(path, number, f"unexpected numbers {raw.strip()!r} in OPTIONS")
        elif section == "FLYNNS":
            if head[0].isalpha():
                raise line_error(path, number, f"unexpected entry {head!r} in FLYNNS: need "
                            "'flynn-id number-of-nodes node-id ...'")
            values = parse_integers(tokens, path, number, "flynn record")
            if len(values) < 2:
                raise line_error(path, number, "flynn record: need 'flynn-id number-of-nodes "
                            "node-id ...'")
            flynn, count, ids = values[0], values[1], values[2:]
            if count < 3:
                raise line_error(path, number, f"flynn {flynn} has {count} nodes: need at least 3")
            if len(ids) != count:
                raise line_error(path, number, f"flynn {flynn} declares {count} nodes but lists "
                            f"{len(ids)} (one flynn per line)")
            if any(f[0] == flynn for f in flynns):
                raise line_error(path, number, f"flynn {flynn} is defined twice")
            flynns.append((flynn, ids, number))
        elif section == "LOCATION":
            if len(tokens) != 3:
                raise line_error(path, number, f"location record {raw.strip()!r}: need "
                            "'node-id x y'")
            node = parse_integers(tokens[:1], path, number, "node id")[0]
            x, y = parse_numbers(tokens[1:], path, number, f"node {node} position")
            if node in nodes:
                raise line_error(path, number, f"node {node} is located twice")
            nodes[node] = (x, y)
        # every other section (UNODES, attributes, PARENTS, ...) is skipped
    if "FLYNNS" not in seen or not flynns:
        raise ValueError(f"{path}: no FLYNNS section with flynns (is it an Elle file?)")
    if "LOCATION" not in seen:
        raise ValueError(f"{path}: no LOCATION section (node positions)")
    cell_lo, cell_hi = np.zeros(2), np.ones(2)
    if bbox_line:
        if len(bbox) != 8:
            raise line_error(path, bbox_line, f"CellBoundingBox has {len(bbox)} numbers: need "
                        "the x y of its 4 corners")
        c = np.array(bbox).reshape(4, 2)   # base left, base right, top right, top left
        rectangle = (c[0, 1] == c[1, 1] and c[2, 1] == c[3, 1] and c[0, 0] == c[3, 0]
                     and c[1, 0] == c[2, 0] and c[1, 0] > c[0, 0] and c[3, 1] > c[0, 1])
        if not rectangle:
            raise line_error(path, bbox_line, f"CellBoundingBox {bbox} is not an upright "
                        "rectangle (base left, base right, top right, top left): sheared "
                        "unit cells are not supported")
        cell_lo, cell_hi = c[0].copy(), c[2].copy()
    return _ElleFile(cell_lo, cell_hi, flynns, nodes)


def read_elle_cell(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper corners of an Elle file's periodic unit cell.

    From ``CellBoundingBox`` in OPTIONS (an upright rectangle; sheared cells
    raise), else Elle's default, the unit square.
    """
    elle = _parse_elle(path)
    return elle.cell_lo, elle.cell_hi


def read_elle(path: str | Path) -> list[Polygon]:
    """The grain polygons (flynns) of an Elle file, one :class:`Polygon` per flynn.

    Supported: sections separated by keyword lines; ``#`` comments;
    ``FLYNNS`` with one flynn per line, ``flynn-id number-of-nodes node-id ...``
    (nodes in order around the flynn); ``LOCATION`` with ``node-id x y``;
    ``OPTIONS`` ``CellBoundingBox`` (an upright rectangle, default the unit
    square).  Other sections (UNODES, attributes, PARENTS) are skipped.

    Elle's unit cell is periodic and stores node positions wrapped into it: a
    flynn that straddles the cell boundary has nodes on both sides.  As Elle
    itself does when it draws a flynn, each node is moved by whole cell lengths
    to lie within half a cell of the previous node; a flynn can therefore stick
    out of the cell by up to half a cell (:func:`polygon_grains` with
    ``periodic`` wraps it back).  A flynn that wraps all the way around the cell
    (a band across the periodic box) raises ``ValueError``, as do a malformed
    line (named by its number), a missing section and a flynn whose node has no
    location.
    """
    elle = _parse_elle(path)
    length = elle.cell_hi - elle.cell_lo
    polygons = []
    for flynn, ids, line in elle.flynns:
        missing = [n for n in ids if n not in elle.nodes]
        if missing:
            raise line_error(path, line, f"flynn {flynn}: node {missing[0]} has no position in "
                        "LOCATION")
        xy = np.array([elle.nodes[n] for n in ids])
        out = np.empty_like(xy)
        out[0] = xy[0]
        for k in range(1, len(xy)):
            step = xy[k] - out[k - 1]
            out[k] = out[k - 1] + step - length * np.round(step / length)
        closing = xy[0] - out[-1]
        closing_image = closing - length * np.round(closing / length)
        if not np.allclose(closing, closing_image, rtol=0, atol=1e-12 * length.max()):
            raise line_error(path, line, f"flynn {flynn} wraps around the periodic unit cell "
                        "(a band across the cell): not supported")
        polygons.append(Polygon(flynn, out, line))
    return polygons
