"""The end layers' grips option (DeckSpec / RockTest ``grips``): checked, and written into the
deck as fix move (held, clamped) or spring forces (fix addforce)."""

from __future__ import annotations

import pytest
from bonded_lattice.conversion import BondParameters
from bonded_lattice.decks import GRIPS, DeckSpec, deck_text
from bonded_lattice.experiment import RockTest, check_grips
from bonded_lattice.rocks import get_rock
from helpers.materials import D

BOND = BondParameters(6.5e10, 2.4e10, 1.9e-7, 3.7e4, 0.24)


def spec(**options) -> DeckSpec:
    base = dict(test="tension", dim=2, d=D, bond=BOND, data_file="data.lattice", area=7e-3,
                eta=1.0, speed=0.01, steps=10, dt=2e-8)
    return DeckSpec(**{**base, **options})


@pytest.mark.parametrize("bad", ["grip", "", "Springs", "platens"])
def test_an_unknown_grip_is_named_with_the_valid_ones(bad):
    valid = r"use one of held, clamped, springs"
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        check_grips(bad)
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        spec(grips=bad)
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        RockTest(get_rock("quartz"), 2, "tension", 8, "unused", grips=bad)


@pytest.mark.parametrize("grips", ["clamped", "springs"])
def test_grips_need_end_layers(grips):
    # platens press the ends of a compression test: no end layers to grip
    with pytest.raises(ValueError, match=r"grips = .* is for decks that load through the end"):
        spec(test="compression", grips=grips)
    assert spec(test="compression", ends="layers", grips=grips).held_ends


def test_spring_grips_have_no_energy_budget():
    with pytest.raises(ValueError, match=r"grips = 'springs'.*not in compute lattice/energy"):
        spec(grips="springs", energy=True)
    assert "compute         energy all lattice/energy work top bottom" in deck_text(
        spec(grips="clamped", energy=True))


def test_the_deck_writes_each_grip():
    assert GRIPS == ("held", "clamped", "springs")
    held = deck_text(spec())
    assert "fix             ptop top move linear NULL 0.01 NULL\n" in held
    # clamped: no lateral motion of the end layers
    assert "fix             ptop top move linear 0 0.01 0\n" in deck_text(spec(grips="clamped"))
    stepped = deck_text(spec(grips="clamped", schedule="stepwise", step_size=1e-9,
                             relax_steps=100))
    # 2D: fix move takes no z displacement
    assert "fix             ptop top move variable v_zero v_dtop NULL NULL NULL NULL\n" in stepped
    stepped_3d = deck_text(spec(grips="clamped", schedule="stepwise", step_size=1e-9,
                                relax_steps=100, dim=3))
    assert "fix             pbot bottom move variable v_zero v_zero v_dbot NULL NULL NULL\n" in stepped_3d
    # held: free sideways
    assert ("fix             ptop top move variable NULL v_dtop NULL NULL NULL NULL\n"
            in deck_text(spec(schedule="stepwise", step_size=1e-9, relax_steps=100)))
    # springs of wall_kn on every end particle, the plane moving 0.01 m/s x 2e-8 s per step
    springs = deck_text(spec(grips="springs", wall_kn=3e10))
    assert "fix             ptop" not in springs
    assert "variable        dtop equal 2e-10*(step-v_s0)\n" in springs
    assert "variable        gtop atom 3e+10*(v_dtop-c_disp[2])\n" in springs
    assert "fix             gtop top addforce 0.0 v_gtop 0.0\n" in springs
    assert "fix             integrate all lattice/nve" in springs
    # default: the platens' default stiffness, 2 Kn
    assert f"variable        gtop atom {2 * BOND.Kn:.8g}*" in deck_text(spec(grips="springs"))


def test_generate_writes_the_spring_grips(tmp_path):
    from bonded_lattice.cli import main
    from bonded_lattice.conversion import rock_to_bond

    out = tmp_path / "deck"
    assert main(["generate", "--dim", "2", "--test", "tension", "--n", "8", "--out", str(out),
                 "--grips", "springs", "--platen-stiffness", "1"]) == 0
    rock = get_rock("quartz")
    kn = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, 1e-3, 2).Kn
    text = (out / "in.tension").read_text()
    assert f"variable        gtop atom {kn:.8g}*(v_dtop-c_disp[2])\n" in text
    with pytest.raises(SystemExit):
        main(["generate", "--test", "tension", "--out", str(out), "--grips", "glued"])
