"""fix lattice/nve: velocity Verlet with the arithmetic of fix nve, compiled for
2D (x and y only: no fix enforce2d) and 3D, with a loop without group test for
group all.  A fracturing scene (random velocities on a simple shear: bonds
break in tension and shear, fragments collide) must end bit for bit where fix
nve (plus fix enforce2d in 2D) takes it, with damping on part of the block."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import INPUTS
from helpers.decks import SHAKE, atoms_at, opening, run_deck, shaken_block
from helpers.materials import D, WEAK_SHEAR, coeffs

COEFFS = {dim: "* * " + coeffs(WEAK_SHEAR[dim]) for dim in (2, 3)}


def run_scene(dim: int, integrator: str, group: str, steps: int = 800,
              extra: str = "", shake: float = 0.3,
              damping: str = "lattice/viscous") -> tuple[np.ndarray, list]:
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(shaken_block(dim) + f"""
pair_style      lattice/bond
pair_coeff      {COEFFS[dim]}
neighbor        {0.1 * D} bin
{extra}
{SHAKE.format(v=shake, rate=300.0, mid=3 * D, vz='v_vz' if dim == 3 else 'NULL')}
compute         b all lattice/bonds
thermo          {steps}
fix             move {group} {integrator}
fix             damp half {damping} 0.5
{"fix plane all enforce2d" if dim == 2 and integrator == "nve" else ""}
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
""")
        ids = lmp.numpy.extract_atom("id")
        order = np.argsort(ids)
        x = np.array(lmp.numpy.extract_atom("x"))[order]
        v = np.array(lmp.numpy.extract_atom("v"))[order]
        counts = [lmp.extract_compute("b", 0, 1)[k] for k in range(4)]
    finally:
        lmp.close()
    return np.hstack([x, v]), counts


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("group", ["all", "half"])
def test_same_trajectory_as_fix_nve(dim, group):
    ref, c_ref = run_scene(dim, "nve", group)
    ours, c_ours = run_scene(dim, "lattice/nve", group)
    intact, tension, shear, contacts = c_ref
    assert tension > 0 and contacts > 0, c_ref    # a violent scene: cracks and collisions
    assert c_ours == c_ref
    assert np.array_equal(ours, ref), np.max(np.abs(ours - ref))
    if dim == 2:
        assert np.all(ours[:, 2] == 0.0) and np.all(ours[:, 5] == 0.0)    # z and vz untouched


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("group", ["all", "half"])
def test_per_atom_masses_match_fix_nve(dim, group):
    """Per-atom masses (atom_style sphere) that change from one atom to the next (three
    values in turn by ID, and the sort reorders them): the quotient dt/2m that the fix
    forms again only when the mass changes must be fix nve's for every atom."""
    masses = ("variable        m atom mass*(1+0.25*(id%3))\n"
              "set             atom * mass v_m\n")
    ref, c_ref = run_scene(dim, "nve", group, extra=masses)
    ours, c_ours = run_scene(dim, "lattice/nve", group, extra=masses)
    assert c_ref[1] > 0 and c_ours == c_ref, (c_ref, c_ours)
    assert np.array_equal(ours, ref), np.max(np.abs(ours - ref))


def test_per_type_mass_matches_fix_nve(lmp_instance):
    """atom_style atomic: masses per type (mass command), particles in free flight
    under gravity reach x = x0 + v0 t + g t^2 / 2 (velocity Verlet is exact for a
    constant force) exactly like fix nve."""
    lmp = lmp_instance
    lmp.commands_string(opening(3, box="0 10 0 10 0 10", types=2, atom_style="atomic")
                        + atoms_at([(1, 1, 5), (5, 5, 8)], types=[1, 2]) + """\
mass            1 2.0
mass            2 3.0
velocity        all set 1.0 -0.5 0.25
pair_style      zero 1.0
pair_coeff      * *
fix             move all lattice/nve
fix             g all gravity 9.81 vector 0 0 -1
timestep        0.01
run             100
""")
    x = np.array(lmp.numpy.extract_atom("x"))
    t = 1.0
    expected_z = np.array([5.0, 8.0]) + 0.25 * t - 0.5 * 9.81 * t ** 2
    assert np.allclose(x[:, 0], np.array([1.0, 5.0]) + t, rtol=0, atol=1e-12)
    assert np.allclose(x[:, 2], expected_z, rtol=0, atol=1e-12)


def test_measured_displacements_give_the_same_bits(tmp_path):
    """fix lattice/nve on every atom measures each step's displacements while it
    moves the atoms, and the record store skips its own pass; any other fix that
    may move them (here a fix wall/reflect at the box edge, which no atom reaches) brings the pass back.  Both
    give the same bits through elastic loading and fracture (2D tension deck)."""
    deck = (INPUTS / "in.tension2d").read_text()
    dump = ("write_dump      all custom final.dump id x y vx vy c_bonds_per_atom "
            "modify sort id format float %.17g\n")
    deck = deck.replace("compute         bonds all lattice/bonds\n",
                        "compute         bonds all lattice/bonds\n"
                        "compute         bonds_per_atom all lattice/bonds\n") + dump
    args = ["-var", "N", "15", "-var", "vpull", "0.02", "-var", "steps", "4600"]
    measured = run_deck(deck, tmp_path / "measured", args=args)
    idle = "fix             idle all wall/reflect xlo EDGE\n"
    passed = run_deck(deck.replace("fix             integrate all lattice/nve\n",
                                   "fix             integrate all lattice/nve\n" + idle),
                      tmp_path / "pass", args=args)
    assert measured.returncode == 0 and passed.returncode == 0, passed.output[-2000:]
    assert "measures the steps" in measured.output
    assert "measures the steps" not in passed.output
    a = (tmp_path / "measured" / "final.dump").read_text()
    b = (tmp_path / "pass" / "final.dump").read_text()
    assert a == b
    broken = measured.thermo[-1]["c_bonds[2]"][-1]
    assert broken > 0, "the run must reach fracture"


def platen_scene(dim: int, integrator: str, platens: str = "before",
                 overlap: bool = False, shear: bool = False, steps: int = 600) -> str:
    """The deck users write for a compression test: the top and bottom layers moved
    toward each other by fix move, the rest integrated by `integrator` and damped; the
    shaken block breaks bonds in tension and shear on the way.  platens: the fix move
    lines "before" or "after" the integrator's; overlap: the upper platen's fix move also
    takes the top layer of the integrated atoms (an error in a deck, but a legal one);
    shear: the block fills a box periodic along x and the platens slide along x at 50 m/s,
    so that their atoms cross the periodic boundary (reneighbouring wraps them)."""
    ax = "y" if dim == 2 else "z"
    vel = {"y": ("0 -0.5 0", "0 0.5 0"), "z": ("0 0 -0.5", "0 0 0.5")}[ax]
    if shear:
        vel = ("50 0 0", "-50 0 0")
    slab = {"y": "INF INF {lo} {hi} INF INF", "z": "INF INF INF INF {lo} {hi}"}[ax]
    top_lo = f"$(bound(all,{ax}max)-{(1.25 if overlap else 0.25) * D})"
    bot_hi = f"$(bound(all,{ax}min)+{0.25 * D})"
    upper = "upper" if overlap else "top"
    move = (f"fix             up {upper} move linear {vel[0]} units box\n"
            f"fix             down bottom move linear {vel[1]} units box\n")
    integrate = f"fix             integrate inner {integrator}\n"
    block = shaken_block(dim)
    if shear:    # the same block, periodic along x (whole lattice cells across the box)
        block = (block.replace("boundary        f f", "boundary        p f")
                 .replace("block -4 16 -4 14", "block 0 12 -4 14")
                 .replace("block -4 10 -4 10 -4 10", "block 0 6 -4 10 -4 10"))
        assert "boundary        p f" in block and "block 0 " in block
    return block + f"""
pair_style      lattice/bond
pair_coeff      {COEFFS[dim]}
neighbor        {0.1 * D} bin
{SHAKE.format(v=0.3, rate=300.0, mid=3 * D, vz='v_vz' if dim == 3 else 'NULL')}
region          toplayer block {slab.format(lo=f"$(bound(all,{ax}max)-{0.25 * D})", hi="INF")} units box
region          upperlayers block {slab.format(lo=top_lo, hi="INF")} units box
region          botlayer block {slab.format(lo="INF", hi=bot_hi)} units box
group           top region toplayer
group           upper region upperlayers
group           bottom region botlayer
group           inner subtract all top bottom
compute         b all lattice/bonds
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4]
thermo          {steps}
{move if platens == "before" else ""}{integrate}{move if platens == "after" else ""}\
fix             damp inner viscous 0.2
{"fix             plane all enforce2d" if dim == 2 and integrator == "nve" else ""}
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
write_dump      all custom final.dump id x y z vx vy vz modify sort id format float %.17g
"""


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("platens", ["before", "after"])
@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("shear", [False, True], ids=["squeeze", "periodic-shear"])
def test_platens_by_fix_move_keep_the_measured_steps(tmp_path, dim, platens, np_, shear):
    """A fix lattice/nve on the atoms between two platens that fix move drives
    measures its atoms' steps; the store forms the platens' steps from their
    positions.  The trajectory must be the one LAMMPS' fix nve (plus fix enforce2d in
    2D) gives, bit for bit, whichever fix comes first and on 1 and 2 ranks (atoms of
    both kinds migrate between ranks).  With a periodic boundary that atoms cross, the
    inner atoms that cross it differ in the last bits: the fix measures x_new - x_old,
    LAMMPS' fix nve leaves the store to form (x_new - L) - x_old + L after the wrap
    (FixLatticeBondStore::pack_exchange); the platens' atoms, whose steps both runs form
    from positions, must then still carry the scene to the same broken bonds and the same
    state within round-off grown over 600 steps of fracture (measured: 3e-14 d in position,
    6e-12 relative in velocity; a platen step off by a period would be a force of
    Kn L / d, far outside)."""
    ref = run_deck(platen_scene(dim, "nve", platens, shear=shear), tmp_path / "nve", np=np_)
    ours = run_deck(platen_scene(dim, "lattice/nve", platens, shear=shear), tmp_path / "ours", np=np_)
    assert ref.returncode == 0 and ours.returncode == 0, (ref.output + ours.output)[-3000:]
    assert "measures the steps of group inner" in ours.output
    last = ref.thermo[-1]
    assert last["c_b[2]"][-1] > 0 and last["c_b[3]"][-1] > 0, last    # broken in tension and shear
    a, b = ((tmp_path / run / "final.dump").read_text() for run in ("ours", "nve"))
    if not shear:
        assert all(np.array_equal(ours.thermo[-1][k], last[k]) for k in last), ours.thermo[-1]
        assert a == b
        return
    assert all(np.array_equal(ours.thermo[-1][k], last[k]) for k in ("c_b[1]", "c_b[2]", "c_b[3]"))
    xa, xb = (np.loadtxt(t.splitlines()[9:]) for t in (a, b))
    assert np.abs(xa[:, 1:4] - xb[:, 1:4]).max() < 1e-9 * D
    assert np.abs(xa[:, 4:] - xb[:, 4:]).max() < 1e-7 * np.abs(xb[:, 4:]).max()


@pytest.mark.parametrize("dim", [2, 3])
def test_a_platen_overlapping_the_group_brings_the_pass_back(tmp_path, dim):
    """A fix move whose group shares atoms with the fix lattice/nve's moves those atoms
    too: the fix cannot measure their steps, so the store's pass forms every step again
    (no message), and the trajectory is still fix nve's under the same two fixes."""
    ref = run_deck(platen_scene(dim, "nve", overlap=True), tmp_path / "nve")
    ours = run_deck(platen_scene(dim, "lattice/nve", overlap=True), tmp_path / "ours")
    assert ref.returncode == 0 and ours.returncode == 0, (ref.output + ours.output)[-3000:]
    assert "measures the steps" not in ours.output
    assert (tmp_path / "ours" / "final.dump").read_text() == (tmp_path / "nve" / "final.dump").read_text()


@pytest.mark.parametrize("dim", [2, 3])
def test_a_deforming_box_brings_the_pass_back(tmp_path, dim):
    """fix deform stretches the periodic box and remaps the atoms, which moves the atoms
    of the fix's group too: the fix cannot measure their steps, so the store forms every
    step (no message), and the trajectory is fix nve's under the same fixes, bit for bit
    (both runs form the steps of the wrapped atoms the same way)."""
    deform = "fix             stretch all deform 1 x erate 2000.0 remap x\n"
    runs = {}
    for integrator in ("nve", "lattice/nve"):
        deck = platen_scene(dim, integrator, shear=True).replace("fix             damp", deform
                                                                  + "fix             damp")
        runs[integrator] = run_deck(deck, tmp_path / integrator.replace("/", "_"))
        assert runs[integrator].returncode == 0, runs[integrator].output[-3000:]
    assert "measures the steps" not in runs["lattice/nve"].output
    a, b = ((tmp_path / run / "final.dump").read_text() for run in ("lattice_nve", "nve"))
    assert a == b


# LAMMPS sorts the atoms in space every 10 steps with bins of a fifth of a diameter, and
# the block is shaken 30 times harder than in the other scenes (10 m/s): the atoms move
# by about a diameter in 800 steps, so each sort reorders them
SORT_OFTEN = f"atom_modify     sort 10 {0.2 * D}\n"


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("group", ["half", "odd"])
def test_group_runs_follow_the_sorting(dim, group):
    """A group that is not all moves in runs of consecutive atoms (the group-all loop
    over each run, formed again whenever LAMMPS may have reordered the atoms) when its
    runs are long ('half', the lower half of the IDs), else with the mask test per atom
    ('odd', every other ID: runs of one atom).  With the atoms sorted every 10 steps, a
    run list not formed again after a sort would move atoms outside the group and leave
    atoms of it behind: the trajectory must stay fix nve's to the last bit.  (In 3D the
    sorts move atoms across the ends of the group's runs: without the new run list after
    each sort, the run stops with an instability; in 2D the group's two runs keep their
    ends, and the case checks the runs' loop against fix nve.)"""
    extra = SORT_OFTEN + ("group           odd id 1:100000:2\n" if group == "odd" else "")
    ref, c_ref = run_scene(dim, "nve", group, extra=extra, shake=10.0)
    ours, c_ours = run_scene(dim, "lattice/nve", group, extra=extra, shake=10.0)
    assert c_ref[1] > 0 and c_ours == c_ref, (c_ref, c_ours)
    assert np.array_equal(ours, ref), np.max(np.abs(ours - ref))


@pytest.mark.parametrize("dim", [2, 3])
def test_damping_runs_follow_the_sorting(dim):
    """fix lattice/viscous on 'half' damps in runs of consecutive atoms too: with the
    atoms sorted every 10 steps it must damp exactly the group's atoms, as LAMMPS' fix
    viscous does (f - eta v and f + (-eta) v are the same number): the same bits."""
    ref, c_ref = run_scene(dim, "nve", "all", extra=SORT_OFTEN, shake=10.0, damping="viscous")
    ours, c_ours = run_scene(dim, "nve", "all", extra=SORT_OFTEN, shake=10.0)
    assert c_ref[1] > 0 and c_ours == c_ref, (c_ref, c_ours)
    assert np.array_equal(ours, ref), np.max(np.abs(ours - ref))


@pytest.mark.parametrize("dim", [2, 3])
def test_group_runs_follow_the_sorting_with_platens(tmp_path, dim):
    """The platen deck (fix lattice/nve measuring the steps of the inner atoms, fix move
    the platens) with the atoms sorted every 10 steps, on 2 ranks (atoms also migrate):
    fix nve's trajectory to the last bit."""
    decks = {i: platen_scene(dim, i).replace("pair_style", SORT_OFTEN + "pair_style", 1)
             for i in ("nve", "lattice/nve")}
    ref = run_deck(decks["nve"], tmp_path / "nve", np=2)
    ours = run_deck(decks["lattice/nve"], tmp_path / "ours", np=2)
    assert ref.returncode == 0 and ours.returncode == 0, (ref.output + ours.output)[-3000:]
    assert "measures the steps of group inner" in ours.output
    assert ref.thermo[-1]["c_b[2]"][-1] > 0
    a, b = ((tmp_path / run / "final.dump").read_text() for run in ("ours", "nve"))
    assert a == b


def test_a_dynamic_group_is_moved_atom_by_atom(tmp_path):
    """A dynamic group changes its members between steps without any reordering: the
    fix must test each atom's mask every step (no runs), as fix nve does.  The group is
    the atoms in the lower half of the box at each step (2D, shaken block)."""
    dyn = ("region          low block INF INF INF $(0.5*(bound(all,ymin)+bound(all,ymax))) "
           "INF INF units box\n"
           "group           half delete\n"
           "group           half dynamic all region low every 1\n")
    ref, c_ref = run_scene(2, "nve", "half", steps=400, extra=dyn)
    ours, c_ours = run_scene(2, "lattice/nve", "half", steps=400, extra=dyn)
    assert c_ours == c_ref, (c_ref, c_ours)
    assert np.array_equal(ours, ref), np.max(np.abs(ours - ref))
