"""The end layers' grips option (DeckSpec / RockTest ``grips``): checked, and written into the
deck as fix move (held, clamped) or spring forces (fix addforce)."""

from __future__ import annotations

import pytest
from bonded_lattice.conversion import BondParameters
import math

from bonded_lattice.deck.grips import grip_depth, grip_title, traction_grips
from bonded_lattice.decks import GRIPS, DeckSpec, deck_text
from bonded_lattice.experiment import RockTest, check_grips, traction_rate
from bonded_lattice.experiment import test_lattice as block_lattice
from bonded_lattice.rocks import get_rock
from helpers.materials import D

BOND = BondParameters(6.5e10, 2.4e10, 1.9e-7, 3.7e4, 0.24)


def spec(**options) -> DeckSpec:
    base = dict(test="tension", dim=2, d=D, bond=BOND, data_file="data.lattice", area=7e-3,
                eta=1.0, speed=0.01, steps=10, dt=2e-8)
    return DeckSpec(**{**base, **options})


@pytest.mark.parametrize("bad", ["grip", "", "Springs", "platens"])
def test_an_unknown_grip_is_named_with_the_valid_ones(bad):
    valid = r"use one of held, clamped, springs, traction, wide"
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        check_grips(bad)
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        spec(grips=bad)
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        RockTest(get_rock("quartz"), 2, "tension", 8, "unused", grips=bad)
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        grip_title(bad, 1.0)
    with pytest.raises(ValueError, match=rf"grips = {bad!r}.*{valid}"):
        grip_depth(bad, 2)


@pytest.mark.parametrize("grips", ["clamped", "springs", "traction", "wide"])
def test_grips_need_end_layers(grips):
    # platens press the ends of a compression test: no end layers to grip
    with pytest.raises(ValueError, match=r"grips = .* is for decks that load through the end"):
        spec(test="compression", grips=grips, traction_rate=1e11)
    assert spec(test="compression", ends="layers", grips=grips, traction_rate=1e11).held_ends


def test_spring_grips_have_no_energy_budget():
    with pytest.raises(ValueError, match=r"grips = 'springs'.*not in compute lattice/energy"):
        spec(grips="springs", energy=True)
    with pytest.raises(ValueError, match=r"grips = 'traction'.*not in compute lattice/energy"):
        spec(grips="traction", traction_rate=1e11, energy=True)
    assert "compute         energy all lattice/energy work top bottom" in deck_text(
        spec(grips="wide", energy=True))
    assert "compute         energy all lattice/energy work top bottom" in deck_text(
        spec(grips="clamped", energy=True))


def test_the_deck_writes_each_grip():
    assert GRIPS == ("held", "clamped", "springs", "traction", "wide")
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


def test_the_deck_writes_the_traction_grips():
    # 1e11 Pa/s x 2e-8 s per step; 7e-3 m^2 shared by each end layer's particles
    text = deck_text(spec(grips="traction", traction_rate=1e11))
    assert "fix             ptop" not in text
    # the block starts at the quasi-static rate of end layers moving at 0.01 m/s each; runaway:
    # the end layers' separation rate over 2 x 0.01 m/s; the stress is the traction until it
    # exceeds 1.5
    lines = ["variable        applied equal 2000*(step-v_s0)",
             "variable        ftop equal v_applied*0.007/count(top)",
             "variable        fbot equal -v_applied*0.007/count(bottom)",
             "fix             gtop top addforce 0.0 v_ftop 0.0",
             "fix             gbot bottom addforce 0.0 v_fbot 0.0",
             "variable        vstart atom 0.01*(y-0.5*(v_lo0+v_hi0))/(0.5*v_H0)",
             "variable        runaway equal (c_vtop-c_vbot)/0.02",
             "variable        stress equal v_applied*(v_runaway<=1.5)",
             "fix             tractionlog all ave/time 500 1 500 v_applied v_separation "
             "v_runaway file traction.dat"]
    missing = [line for line in lines if line + "\n" not in text]
    assert missing == []
    assert "fix             integrate all lattice/nve" in text
    # 3D: along z; pushed together with ends = "layers" (negative rate and speed)
    pushed = deck_text(spec(test="compression", ends="layers", dim=3, grips="traction",
                            traction_rate=1e11))
    assert "variable        applied equal -2000*(step-v_s0)\n" in pushed
    assert "fix             gtop top addforce 0.0 0.0 v_ftop\n" in pushed
    assert "variable        runaway equal (c_vtop-c_vbot)/-0.02\n" in pushed


@pytest.mark.parametrize("options, message", [
    ({}, r"traction_rate = 0.0 is out of range"),
    ({"traction_rate": -2.5}, r"traction_rate = -2.5 is out of range"),
    ({"traction_rate": math.inf}, r"traction_rate = inf is out of range"),
    ({"traction_rate": 1e11, "schedule": "stepwise", "step_size": 1e-9, "relax_steps": 100},
     r"schedule must be 'constant'"),
])
def test_traction_grips_need_a_ramp(options, message):
    with pytest.raises(ValueError, match=message):
        spec(grips="traction", **options)


@pytest.mark.parametrize("args, message", [
    (("x", 1e11, 2e-8, 0.01, 1.0, 7e-3, 500), r"axis = 'x' is out of range"),
    (("y", 0.0, 2e-8, 0.01, 1.0, 7e-3, 500), r"rate = 0.0 is out of range"),
    (("y", 1e11, 2e-8, math.nan, 1.0, 7e-3, 500), r"speed = nan is out of range"),
    (("y", 1e11, 2e-8, -0.01, 1.0, 7e-3, 500), r"need the same sign"),
    (("y", 1e11, 2e-8, 0.01, 1.0, 7e-3, 0), r"every = 0 is out of range"),
])
def test_traction_grips_check_their_arguments(args, message):
    with pytest.raises(ValueError, match=message):
        traction_grips(*args)


def test_the_traction_rate_matches_the_displacement_loading():
    # E times the held end layers' strain rate 2 speed / (span of the centres)
    rock, lattice = get_rock("quartz"), block_lattice(2, 8, 1e-3, "tension")
    span = lattice.height
    assert span == pytest.approx(8 * math.sqrt(3) / 2 * 1e-3, rel=1e-12)   # 9 rows, 68 particles
    assert traction_rate(rock, lattice, 0.01) == pytest.approx(rock.E * 0.02 / span,
                                                               rel=1e-12)
    with pytest.raises(ValueError, match=r"speed = 0.0 is out of range"):
        traction_rate(rock, lattice, 0.0)


def test_the_deck_writes_the_wide_grips():
    # the two outermost rows: centres within 0.6 d plus a row spacing of the ends
    assert grip_depth("wide", 2) == pytest.approx(0.6 + math.sqrt(3) / 2, rel=1e-15)
    assert grip_depth("wide", 3) == pytest.approx(0.6 + math.sqrt(2 / 3), rel=1e-15)
    assert grip_depth("held", 3) == 0.6
    with pytest.raises(ValueError, match=r"dim = 1 is out of range"):
        grip_depth("wide", 1)
    text = deck_text(spec(grips="wide"))
    depth = (0.6 + math.sqrt(3) / 2) * D
    assert f"region          toplayer block INF INF $(v_hi0-{depth!r}) INF INF INF units box\n" in text
    assert f"region          botlayer block INF INF INF $(v_lo0+{depth!r}) INF INF units box\n" in text
    # held as 'held' holds one row: axial motion prescribed, free sideways
    assert "fix             ptop top move linear NULL 0.01 NULL\n" in text
    assert "variable        stress equal 0.5*(c_fbot-c_ftop)/0.007\n" in text
