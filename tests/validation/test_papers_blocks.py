"""Block-level statements of the papers, checked on the papers' smallest multi-unit blocks.

Liu, Pollard & Shi (2013) section 5 and Liu et al. (2017) section 5.2 state, besides their
numbers (compared in docs/validation.md), how the errors behave with the block size; each test
below checks one such statement on blocks cheap enough for the default suite (2D N = 4, 8, 15;
3D n_y = 4, 6), under the package's defaults.  The numbers themselves, and the differences from
the papers' means, are measured and explained in docs/validation.md ("like for like").
"""

from __future__ import annotations

from pathlib import Path

import pytest
from bonded_lattice.experiment import run_test
from bonded_lattice.rocks import get_rock

SIZES = {2: [4, 8, 15], 3: [4, 6]}
# 3D compression at 1000 wave crossings to failure (the 3D default since docs/speed_error.md,
# part 4, kept explicit here): at the former default 100 the platens' viscous drag read Cu 3-5
# points high on these blocks (docs/validation.md, "3D compression: how slow constant loading
# must be")
SLOW_3D = {"crossings": 1000.0}


@pytest.fixture(scope="module")
def blocks(tmp_path_factory) -> dict:
    """Elastic (strain -1e-6, the papers' small strain), tension and compression runs."""
    rock = get_rock("quartz")
    out: Path = tmp_path_factory.mktemp("papers_blocks")
    runs: dict = {}
    for dim, sizes in SIZES.items():
        for n in sizes:
            for test in ("elastic", "tension", "compression"):
                options = {"elastic_strain": 1e-6} if test == "elastic" else {}
                if dim == 3 and test == "compression":
                    options = SLOW_3D
                runs[dim, n, test] = run_test(rock, dim, test, n, out / f"{dim}d_{n}_{test}",
                                              np_=1, progress=False, **options)
    return runs


@pytest.mark.parametrize("dim", [2, 3])
def test_multi_unit_blocks_are_weaker_in_compression_than_in_tension(blocks, dim):
    # Liu 2013 paras. 51 and 54, Liu 2017 section 5.2: the blocks of many units fail below the
    # formulas, and the compressive deficit is much greater than the tensile one (2013: 22.2%
    # against 4.3%; 2017: 18.51% against 8.89%), because Cu is reached at a strain beyond 1e-3
    for n in SIZES[dim]:
        tu = blocks[dim, n, "tension"]["relative_error"]["Tu"]
        cu = blocks[dim, n, "compression"]["relative_error"]["Cu"]
        assert cu < tu < 0, (n, tu, cu)
        assert cu < 1.5 * tu, (n, tu, cu)   # "much greater": by more than half again


def test_2d_elastic_errors_fall_with_the_block_size(blocks):
    # Liu 2013 para. 45: the 18-particle block (N = 4) has the lowest precision, E below the
    # formula, and E and nu converge to the formulas as the particle number grows
    errs = [blocks[2, n, "elastic"]["relative_error"] for n in SIZES[2]]
    e = [abs(x["E"]) for x in errs]
    nu = [abs(x["nu"]) for x in errs]
    assert errs[0]["E"] < 0
    assert e == sorted(e, reverse=True) and nu == sorted(nu, reverse=True), (e, nu)
    # by N = 15 both are within 1% (the paper's Fig. 6 at small strain), a tenth of N = 4's nu
    assert e[-1] < 0.01 and nu[-1] < 0.01


def test_3d_small_strain_modulus_is_within_the_papers_percent(blocks):
    # Liu 2017 section 5.2: for multi-unit models the elastic properties err by about 0.6% on
    # average at strains from -1e-6 to -1e-3; each block here stays within 1% in E
    for n in SIZES[3]:
        assert abs(blocks[3, n, "elastic"]["relative_error"]["E"]) < 0.01


def test_2d_platens_of_the_bonds_stiffness_lose_the_papers_compressive_strength(tmp_path):
    # Liu 2013 para. 51: the multi-unit blocks' Cu is 22.2% below the formula on average (six
    # sizes, 18 to 16611 particles).  The deficit is the platens' (docs/validation.md, "The
    # platens decide the compressive deficit"): with springs of the bonds' own stiffness Kn
    # our N = 8 and 15 blocks lose that much.  Tolerance 2 points: the paper gives only the
    # six sizes' mean, and our per-size values at Kn spread 1.1 points over N = 8-30; the
    # papers' stepwise schedule reads up to 1 point lower than this constant loading
    rock = get_rock("quartz")
    cu = [run_test(rock, 2, "compression", n, tmp_path / f"n{n}", np_=1, progress=False,
                   crossings=100.0, damping=1.0, platen_stiffness=1.0)["relative_error"]["Cu"]
          for n in (8, 15)]
    assert abs(sum(cu) / len(cu) - (-0.222)) < 0.02, cu
    # and our own 2 Kn platens do not: the choice of platen is what the difference measures
    ours = run_test(rock, 2, "compression", 15, tmp_path / "n15_2kn", np_=1, progress=False,
                    crossings=100.0, damping=1.0)["relative_error"]["Cu"]
    assert ours > -0.18, ours
