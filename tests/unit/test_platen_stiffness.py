"""The platens' stiffness option: checked, and written into the deck as the wall's Kn."""

from __future__ import annotations

import math

import pytest
from bonded_lattice.cli import main
from bonded_lattice.conversion import rock_to_bond
from bonded_lattice.experiment import MAX_PLATEN_STIFFNESS, check_platen_stiffness
from bonded_lattice.rocks import get_rock


@pytest.mark.parametrize("bad", [0.0, -1.0, MAX_PLATEN_STIFFNESS * 1.01, math.inf, math.nan])
def test_a_bad_stiffness_is_named_with_its_range(bad):
    with pytest.raises(ValueError, match=r"platen_stiffness = .* need 0 < platen_stiffness <= 20"):
        check_platen_stiffness(bad)


@pytest.mark.parametrize("k", [1.0, 2.0, 5.0])
def test_generate_writes_the_platens_at_k_times_kn(tmp_path, k):
    out = tmp_path / "deck"
    assert main(["generate", "--dim", "2", "--test", "compression", "--n", "8", "--out",
                 str(out), "--platen-stiffness", str(k)]) == 0
    walls = [line.split() for line in (out / "in.compression").read_text().splitlines()
             if "lattice/wall" in line and line.startswith("fix")]
    rock = get_rock("quartz")
    kn = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, 1e-3, 2).Kn
    assert len(walls) == 2
    for words in walls:
        # fix ID group lattice/wall face position Kn ...: the deck prints 6 digits
        assert float(words[6]) == pytest.approx(k * kn, rel=1e-5)
