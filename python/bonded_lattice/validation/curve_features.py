"""The features of a compressive stress-strain curve, found from the curve and the broken-bond
counts the decks print (Liu 2013, para. 49 and Fig. 7a; Liu 2017, section 5.2 and Fig. 5).

The papers describe the curve of a compressive strength test by its points: O-A linear; A
(2013; A1 in 2017) where the opening micro-cracks form (C_open) and the stress drops a bit;
small drops before A where boundary bonds break (2013: A2, A3; 2017: A3); a drop before the
peak (2017); the peak B (2013; A2 in 2017), the compressive strength Cu; and C, after the
stress has fallen to almost zero.  :func:`curve_features` finds them:

- drops: the falls of a zig-zag of the stress with reversal amplitude ``drop_min`` (a fall
  counts once the stress has come down by ``drop_min`` from its highest value since the last
  trough; it ends at the lowest value before the stress climbs ``drop_min`` back), each with
  the bonds broken, in tension and in shear, from ``lag`` rows before its top (but not before
  the trough before it) to its bottom: a bond's unloading reaches the platens up to a wave
  crossing after it broke;
- A: the first drop that ends once the bonds broken in tension exceed ``open_fraction`` of
  the initial bonds (the definition of C_open in :mod:`bonded_lattice.analysis`, which keeps
  the few early boundary breaks out of it);
- the opening: the drops from A until the bonds broken in tension reach ``opened_fraction``
  of their number at the peak (the opening micro-cracks of the whole block);
- the drops with broken bonds before A (the papers' boundary bonds), and those after the
  opening and before the peak;
- B: the highest stress; C: the first row after B whose stress is within ``c_fraction`` of
  the fall from B to the lowest stress after it (the end of the drop: "almost zero" in the
  2013 paper, the crushed block's residual stress in ours).
"""

from __future__ import annotations

import numpy as np

from ..analysis import C_OPEN_FRACTION

__all__ = ["C_FRACTION", "DROP_FRACTION", "OPENED_FRACTION", "curve_features", "keep_rows",
           "zigzag_drops"]

# reversal amplitude of the zig-zag as a fraction of the peak stress: above the ringing of a
# constant-loading run at the papers' damping (measured: up to 0.05% of the peak between the
# bond breaks of the 1033-particle block)
DROP_FRACTION = 1.0e-3
# C: the stress has come within this fraction of the fall from the peak to its lowest value
C_FRACTION = 0.1
# the opening is over once this fraction of the bonds broken in tension at the peak have broken
OPENED_FRACTION = 0.95


def zigzag_drops(stress: np.ndarray, drop_min: float) -> list[tuple[int, int, int]]:
    """The falls of ``stress`` by at least ``drop_min`` as (trough before, top, bottom) row
    indices, in order: from its top (the highest row since the trough before) the stress
    falls by ``drop_min`` or more to its bottom (the lowest row before it climbs ``drop_min``
    above that)."""
    if not drop_min > 0:
        raise ValueError(f"drop_min = {drop_min} is out of range: need drop_min > 0")
    s = np.asarray(stress, dtype=float)
    drops: list[tuple[int, int, int]] = []
    trough, top, bottom = 0, 0, None      # bottom: row of the current fall's lowest value
    for i in range(1, len(s)):
        if bottom is None:
            if s[i] > s[top]:
                top = i
            elif s[top] - s[i] >= drop_min:
                bottom = i
        else:
            if s[i] < s[bottom]:
                bottom = i
            elif s[i] - s[bottom] >= drop_min:
                drops.append((trough, top, bottom))
                trough, top, bottom = bottom, i, None
    if bottom is not None:
        drops.append((trough, top, bottom))
    return drops


def _point(strain: np.ndarray, stress: np.ndarray, i: int) -> dict:
    return {"row": int(i), "strain": float(strain[i]), "stress": float(stress[i])}


def curve_features(strain: np.ndarray, stress: np.ndarray, broken_tension: np.ndarray,
                   broken_shear: np.ndarray, intact0: float, lag: int,
                   drop_fraction: float = DROP_FRACTION,
                   open_fraction: float = C_OPEN_FRACTION,
                   opened_fraction: float = OPENED_FRACTION,
                   c_fraction: float = C_FRACTION) -> dict:
    """The features of a compressive curve (module docstring).

    strain, stress: magnitudes (compression positive), one value per thermo row;
    broken_tension, broken_shear: bonds broken so far; intact0: bonds at the start; lag:
    thermo rows in one elastic-wave crossing of the block (a drop's bonds are counted from
    that many rows before its top).
    Returns {"first_break", "opened", "B", "C": point or None, "first_break_bonds", "A": drop
    or None, "before_A", "opening", "before_B", "drops": lists of drops, "E_OA": slope of O-A
    (a least-squares line over the rows before the first break with a tenth to nine tenths
    of its stress),
    "drop_min"}; a point is {"row", "strain", "stress"}, a drop is {"top": point, "bottom":
    point, "size", "tension", "shear"} (bonds broken in it).
    """
    eps, sig = np.asarray(strain, dtype=float), np.asarray(stress, dtype=float)
    bt, bs = np.asarray(broken_tension, dtype=float), np.asarray(broken_shear, dtype=float)
    if not (len(eps) == len(sig) == len(bt) == len(bs) >= 3):
        raise ValueError("strain, stress and the broken-bond counts need the same length >= 3")
    if not intact0 > 0:
        raise ValueError(f"intact0 = {intact0} is out of range: need intact0 > 0")
    if lag < 0:
        raise ValueError(f"lag = {lag} is out of range: need lag >= 0 (thermo rows)")
    for name, value in (("drop_fraction", drop_fraction), ("open_fraction", open_fraction),
                        ("opened_fraction", opened_fraction), ("c_fraction", c_fraction)):
        if not 0 < value < 1:
            raise ValueError(f"{name} = {value} is out of range: need 0 < {name} < 1")
    ib = int(np.argmax(sig))
    drop_min = drop_fraction * float(sig[ib])
    broken = bt + bs
    drops = []
    for trough, top, bottom in zigzag_drops(sig, drop_min):
        start = max(trough, top - lag)
        drops.append({"top": _point(eps, sig, top), "bottom": _point(eps, sig, bottom),
                      "size": float(sig[top] - sig[bottom]),
                      "tension": int(bt[bottom] - bt[start]),
                      "shear": int(bs[bottom] - bs[start])})
    breaking = [dr for dr in drops if dr["tension"] + dr["shear"] > 0]
    opened = np.nonzero(bt > open_fraction * intact0)[0]
    a_drop = None
    if len(opened):
        a_drop = next((dr for dr in breaking if dr["bottom"]["row"] >= opened[0]), None)
    a_row = a_drop["top"]["row"] if a_drop is not None else ib
    done = np.nonzero(bt >= opened_fraction * bt[ib])[0] if bt[ib] > 0 else np.zeros(0, int)
    open_end = int(done[0]) if len(done) else a_row
    before_a = [dr for dr in breaking if dr["bottom"]["row"] < a_row]
    opening = [dr for dr in drops if a_row <= dr["top"]["row"] <= open_end]
    before_b = [dr for dr in breaking if open_end < dr["top"]["row"] < ib]
    first = int(np.argmax(broken > 0)) if broken.max(initial=0) > 0 else None
    # O-A: a line through the rows between a tenth and nine tenths of the stress at the first
    # break (the loading's start-up transient stays out of it)
    top = sig[first] if first is not None else sig[ib]
    line = (np.arange(len(sig)) < (first if first is not None else ib)) \
        & (sig >= 0.1 * top) & (sig <= 0.9 * top)
    e_oa = float(np.polyfit(eps[line], sig[line], 1)[0]) if line.sum() >= 3 else None
    low = float(sig[ib:].min())
    c_row = None
    if sig[ib] - low >= drop_min:
        c_row = ib + int(np.argmax(sig[ib:] <= low + c_fraction * (sig[ib] - low)))
    return {"first_break": None if first is None else _point(eps, sig, first),
            "first_break_bonds": None if first is None else int(broken[first]),
            "A": a_drop, "opened": _point(eps, sig, open_end), "B": _point(eps, sig, ib),
            "C": None if c_row is None else _point(eps, sig, c_row),
            "before_A": before_a, "opening": opening, "before_B": before_b, "drops": drops,
            "E_OA": e_oa, "drop_min": drop_min}


def keep_rows(rows: int, features: list[int], points: int = 400, around: int = 15) -> np.ndarray:
    """Row indices of a thinned curve: every k-th of ``rows`` (about ``points``), the last,
    and ``around`` rows on either side of each row in ``features``."""
    if rows < 1 or points < 2 or around < 0:
        raise ValueError(f"rows = {rows}, points = {points}, around = {around}: need rows >= 1, "
                         "points >= 2, around >= 0")
    keep = set(range(0, rows, max(1, rows // points))) | {rows - 1}
    for i in features:
        keep |= set(range(max(0, i - around), min(rows, i + around + 1)))
    return np.array(sorted(keep))
