"""The 2D lattice's orientation against what symmetry and closed forms fix (Liu 2013 para. 55;
the section ``anisotropy`` of docs/validation.md measures the whole dependence).

Three elastic tests of the papers' N = 15 block (about 230 particles, a few seconds each),
loaded through held end bands (``ends="layers"``) as the anisotropy section does:

- orientation 0 (the paper's set-up, load at 90 degrees to the rows) gives the formula's E;
- orientation 40 is the mirror image of 20 (the lattice repeats every 60 degrees and is
  symmetric about 0 and 30), cut differently: the same E within the cut's effect;
- orientation 30 (a bond along the load) has straight columns of particles along its sides,
  so the stress area between the outer centres misses half a column spacing on each side:
  E measured on it is high by sqrt(3)/2 d over that width (the hexagonal lattice is
  elastically isotropic, so nothing else changes E).
"""

from __future__ import annotations

import math

import pytest
from bonded_lattice.experiment import build_lattice, run_test
from helpers.materials import D, QUARTZ_ROCK

N = 15


@pytest.fixture(scope="module")
def elastic(tmp_path_factory):
    """E's relative error per orientation (a dict filled as the tests ask)."""
    root = tmp_path_factory.mktemp("anisotropy")
    cache: dict[float, float] = {}

    def run(orientation: float) -> float:
        if orientation not in cache:
            s = run_test(QUARTZ_ROCK, 2, "elastic", N, root / f"o{orientation:g}", np_=1,
                         progress=False, orientation=orientation, ends="layers",
                         crossings=100.0, damping=1.0)
            cache[orientation] = s["relative_error"]["E"]
        return cache[orientation]

    return run


def test_papers_orientation_gives_the_formula(elastic):
    # the papers' N = 15 block is 0.14% low with platens (the series section; E's size
    # deficit falls as 1/N) and held ends change that by under 0.1 point: 0.5% leaves room
    # for the loading rate without admitting a missed factor (the next size down, N = 8, is
    # already 0.54% low)
    assert abs(elastic(0.0)) < 5.0e-3


def test_mirror_angle_repeats_e(elastic):
    # 40 degrees is the mirror image of 20, cut with one particle fewer: the cut acts on E
    # through the stepped edges, whose deficit at N = 15 changes by up to 2 points between
    # neighbouring stepped angles (the anisotropy section); a mirror image must not differ
    # by more than neighbouring angles do.  (20 and 0 differ by over 3 points.)
    assert abs(elastic(40.0) - elastic(20.0)) < 0.02


def test_bond_along_load_area_convention(elastic):
    lattice = build_lattice(2, N, D, 30.0)
    predicted = 0.5 * math.sqrt(3.0) * D / lattice.loaded_area()
    # the size deficit of E at N = 15 is under 0.2% (orientation 0): 0.5 point
    assert elastic(30.0) == pytest.approx(predicted, abs=5.0e-3)
