"""The feature detector of the compressive curves (bonded_lattice.validation.curve_features) on
synthetic curves whose drops, peak and bond counts are known exactly.

The synthetic curve is a straight line of slope E with instantaneous drops (one row each):
the stress at row i is E eps_i minus the drops whose row is <= i, so a drop of D at row j
has its top at row j - 1, its bottom at row j and a size D - E (eps_j - eps_{j-1}), exactly.
Every asserted number is therefore exact up to floating-point rounding (rel 1e-9).
"""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.validation.curve_features import (curve_features, keep_rows,
                                                      zigzag_drops)

E = 90.0e9
DEPS = 1.0e-6                   # strain per row
ROWS = 4001
INTACT0 = 1000.0                # 1% of them: 10 bonds open the block
LAG = 20                        # rows of a wave crossing: bonds counted from LAG rows before a top


def synthetic() -> dict:
    """The curve of the module docstring with: two drops with tension breaks before A (rows
    300 and 450, 3 and 4 bonds), A at row 600 (6 MPa, the tension breaks jump over 1% of the
    bonds), the tension breaks then rising linearly to 400 by row 700 with one more drop (row
    650), a drop without broken bonds (row 1500: ringing), a drop with 12 shear breaks (row
    2800) before the peak, the peak at row 3000, then a fall to 1 MPa over 100 rows."""
    eps = DEPS * np.arange(ROWS)
    sig = E * eps
    bt, bs = np.zeros(ROWS), np.zeros(ROWS)
    drops = {300: 0.5e6, 450: 0.8e6, 600: 6.0e6, 650: 1.0e6, 1500: 0.5e6, 2800: 2.0e6}
    for row, size in drops.items():
        sig[row:] -= size
    bt[300:] += 3
    bt[450:] += 4
    bt[600:] += 20                                      # 27 > 1% of INTACT0
    bt[601:701] += np.linspace(373 / 100, 373, 100)     # to 400 at row 700
    bt[701:] = 400
    bs[2800:] += 12
    peak = sig[3000]
    sig[3001:3101] = np.linspace(peak, 1.0e6, 101)[1:]
    sig[3101:] = 1.0e6
    bs[3001:3101] += np.arange(1, 101)
    bs[3101:] = bs[3100]
    return {"eps": eps, "sig": sig, "bt": bt, "bs": bs, "drops": drops, "peak": peak}


def features(c: dict, **kw) -> dict:
    return curve_features(c["eps"], c["sig"], c["bt"], c["bs"], INTACT0, LAG, **kw)


def test_zigzag_on_a_small_sequence():
    s = [0, 1, 2, 1.5, 3, 2, 2.5, 0.5, 4, 0]
    # drop_min 0.6: falls 3 -> 2 and 2.5 -> 0.5 merge (2 -> 2.5 is no reversal), 4 -> 0
    assert zigzag_drops(s, 0.6) == [(0, 4, 7), (7, 8, 9)]
    # drop_min 0.4: 2 -> 1.5 counts, and 3 -> 2 ends at the 0.5 climb to 2.5
    assert zigzag_drops(s, 0.4) == [(0, 2, 3), (3, 4, 5), (5, 6, 7), (7, 8, 9)]
    with pytest.raises(ValueError, match="drop_min"):
        zigzag_drops(s, 0.0)


def test_features_of_the_synthetic_curve():
    c = synthetic()
    f = features(c)
    rise = E * DEPS                      # the line's rise per row, inside each one-row drop
    assert f["drop_min"] == pytest.approx(1e-3 * c["peak"], rel=1e-12)
    # every drop is found, at its row, with its exact size
    tops = [dr["top"]["row"] for dr in f["drops"]]
    assert tops == [r - 1 for r in sorted(c["drops"])] + [3000]
    for dr in f["drops"][:-1]:
        j = dr["bottom"]["row"]
        assert dr["size"] == pytest.approx(c["drops"][j] - rise, rel=1e-9)
    # the two early drops with their bonds (the papers' boundary bonds, before A)
    assert [(dr["bottom"]["row"], dr["tension"], dr["shear"]) for dr in f["before_A"]] == \
        [(300, 3, 0), (450, 4, 0)]
    # A: the first drop once 1% of the bonds are broken in tension
    assert f["A"]["top"]["row"] == 599 and f["A"]["tension"] == 20
    assert f["A"]["top"]["stress"] == pytest.approx(E * 599 * DEPS - 1.3e6, rel=1e-9)
    # the opening: A and the drop at row 650, until 95% of the 400 tension breaks (row 696)
    assert [dr["bottom"]["row"] for dr in f["opening"]] == [600, 650]
    assert f["opened"]["row"] == int(np.argmax(c["bt"] >= 0.95 * 400))
    # the ringing drop has no broken bonds: found as a drop, in no feature list
    ringing = next(dr for dr in f["drops"] if dr["bottom"]["row"] == 1500)
    assert ringing["tension"] == ringing["shear"] == 0
    assert [dr["bottom"]["row"] for dr in f["before_B"]] == [2800]
    assert f["before_B"][0]["shear"] == 12
    # B, C and the first break
    assert f["B"]["row"] == 3000 and f["B"]["stress"] == pytest.approx(c["peak"], rel=1e-12)
    low = 1.0e6
    c_row = 3000 + int(np.argmax(c["sig"][3000:] <= low + 0.1 * (c["peak"] - low)))
    assert f["C"]["row"] == c_row
    assert f["first_break"]["row"] == 300 and f["first_break_bonds"] == 3
    # O-A: the line's slope
    assert f["E_OA"] == pytest.approx(E, rel=1e-9)


def test_bonds_within_a_crossing_before_the_top_count():
    """A break LAG - 5 rows before a drop's top belongs to it; one LAG + 5 rows before, not."""
    c = synthetic()
    c["bs"][2799 - (LAG - 5):] += 1
    c["bs"][1499 - (LAG + 5):] += 1
    f = features(c)
    shear = {dr["bottom"]["row"]: dr["shear"] for dr in f["drops"]}
    assert shear[2800] == 13 and shear[1500] == 0


def test_a_coarser_threshold_misses_the_small_drops():
    """With a reversal amplitude above the early drops (0.5 and 0.8 MPa, minus the line's rise),
    they merge into the rise: none before A."""
    c = synthetic()
    f = features(c, drop_fraction=1.0e6 / c["peak"])
    assert f["before_A"] == []
    assert f["A"]["bottom"]["row"] == 600


def test_no_breaks_no_A():
    c = synthetic()
    f = curve_features(c["eps"], c["sig"], np.zeros(ROWS), np.zeros(ROWS), INTACT0, LAG)
    assert f["A"] is None and f["first_break"] is None and f["before_A"] == []
    assert f["B"]["row"] == 3000


def test_bad_input():
    c = synthetic()
    with pytest.raises(ValueError, match="intact0"):
        curve_features(c["eps"], c["sig"], c["bt"], c["bs"], 0.0, LAG)
    with pytest.raises(ValueError, match="same length"):
        curve_features(c["eps"][:-1], c["sig"], c["bt"], c["bs"], INTACT0, LAG)
    with pytest.raises(ValueError, match="lag"):
        curve_features(c["eps"], c["sig"], c["bt"], c["bs"], INTACT0, -1)
    with pytest.raises(ValueError, match="c_fraction"):
        features(c, c_fraction=1.5)


def test_keep_rows():
    rows = keep_rows(1000, [500], points=10, around=3)
    assert set(range(0, 1000, 100)) | {999} | set(range(497, 504)) == set(rows.tolist())
    assert keep_rows(5, [0, 4], points=100, around=10).tolist() == [0, 1, 2, 3, 4]
    with pytest.raises(ValueError, match="points"):
        keep_rows(10, [], points=1)
