"""One complete numerical rock test: lattice -> data file and deck -> run -> measure -> plots.

This is what ``bonded-lattice run`` does (:class:`RockTest`, a
:class:`bonded_lattice.study.Study`); it writes into one output folder:
``data.lattice``, ``in.<test>``, ``log.lammps``, dumps, ``stress_strain.png``,
``broken_bonds.png`` (strength tests) and ``summary.json``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from . import __version__
from .analysis import elastic_from_dump, measure
from .conversion import (
    BondParameters,
    c_open,
    lattice_mass,
    paper_damping_2d,
    paper_damping_3d,
    rock_to_bond,
)
from .deck.grips import check_grips
from .decks import BREAKING_COLUMNS, BREAKING_LOG, ELASTIC_LOADS, ENDS, DeckSpec, write_deck
from .grains import GrainPairOptions
from .io.ave_time import read_ave_time
from .lattice import (Lattice, close_packed_block_3d, hex_block_2d, turned_block_3d,
                      write_data)
from .periodic import paper_cell, periodic_cell
from .plotting import broken_bond_map_png, energy_png, stress_strain_png
from .rocks import Rock
from .runner import RunResult
from .schedules import DEFAULT_DT_FRACTION, PAPER_SCHEDULES, default_loading, schedule_name
from .study import Study


@dataclass(frozen=True)
class RunPlan:
    """The numbers chosen for a run, with the reason for each in the docstring of plan_test."""

    n: int
    particles: int
    d: float
    mass: float
    dt: float
    eta: float
    speed: float
    steps: int
    area: float
    schedule: str = "constant"
    step_size: float = 0.0
    relax_steps: int = 0
    thermo_every: int = 1
    strain_rate: float = 0.0     # periodic test: axial strain rate of the box (1/s)
    modulus: float = 0.0         # periodic test: stiffness estimate for its barostat (Pa)
    elastic_load: str = "compression"  # elastic test: one of ELASTIC_LOADS


def build_lattice(dim: int, n: int, d: float, orientation: float = 0.0) -> Lattice:
    """The papers' blocks: n particles across (2D) or n elements along y (3D).

    orientation: 2D: angle in degrees from the x axis to the close-packed rows (0: the
    papers' set-up, rows perpendicular to the load; 30: one bond family along the load),
    see :func:`bonded_lattice.lattice.block_2d`; 3D: 0 (the paper's set-up, close-packed
    layers across the load) or 90 (the block turned about x: close-packed rows along the
    load), see :func:`bonded_lattice.lattice.turned_block_3d`.
    """
    if dim == 2:
        return hex_block_2d(n, d, orientation=orientation)
    return turned_block_3d(close_packed_block_3d(n, d), orientation)


def test_lattice(dim: int, n: int, d: float, test: str, orientation: float = 0.0) -> Lattice:
    """The lattice of a test: the papers' block (:func:`build_lattice`), or for the
    periodic test a periodic cell of about n particles across in the papers'
    orientation (:func:`bonded_lattice.periodic.paper_cell`)."""
    if test != "periodic":
        return build_lattice(dim, n, d, orientation)
    if orientation != 0.0:
        raise ValueError(f"orientation = {orientation}: the periodic test's cell has the "
                         "papers' orientation (0)")
    return periodic_cell(dim, d, paper_cell(dim, n)).lattice


RUN_MARGIN = {"elastic": 1.5, "tension": 2.5, "compression": 2.5, "confined": 2.5,
              "periodic": 1.5}
# periodic test: time steps to the failure strain.  The cell deforms homogeneously
# (no wave has to cross it), so the rate is limited only by the lateral barostat's
# lag and by how finely the peak is resolved (1/PERIODIC_STEPS)
PERIODIC_STEPS = 10000
# thermo rows per run: the peak stress is sampled on them, so a strength run with
# margin 2.5 resolves its peak to about 2.5/THERMO_LINES (0.17%), at a cost of a few
# per cent (each row reduces over all particles); the stepwise schedule prints at
# the end of relaxation periods only
THERMO_LINES = 1500
THERMO_LINES_STEPWISE = 4000
# the platens' spring stiffness as a multiple of Kn: 2 by default; stiffer platens (closer to
# the papers' rigid planes) raise the contact frequency by sqrt(stiffness) at the same time
# step, so 20 (omega dt = 0.48 at the stepwise schedule's 0.107 sqrt(m/Kn)) is the limit
MAX_PLATEN_STIFFNESS = 20.0


def confined_strength(rock: Rock, confining: float) -> float:
    """Axial stress at failure under confinement: sigma1 = Cu + I sigma3 (Coulomb envelope
    with I = (sqrt(1 + mu_i^2) + mu_i)^2, the factor of the conversion formulas)."""
    big_i = (math.sqrt(1.0 + rock.mu_i**2) + rock.mu_i) ** 2
    return rock.Cu + big_i * confining


def target_strain(rock: Rock, test: str, confining: float = 0.0,
                  elastic_strain: float = 1.0e-4) -> float:
    """Axial strain magnitude the test must reach: failure strain or the elastic test's strain."""
    return {"tension": rock.Tu / rock.E, "compression": rock.Cu / rock.E,
            "elastic": elastic_strain, "periodic": rock.Tu / rock.E,
            "confined": confined_strength(rock, confining) / rock.E}[test]


def plan_changes(stored: dict, now: dict, rel: float = 1e-9) -> str:
    """How a stored run's plan (``summary.json``'s ``plan``) differs from ``now``: the keys
    whose values differ (numbers beyond ``rel``), as 'key stored -> now', comma-separated;
    '' if none does.  Keys the stored plan lacks (older summaries) are not compared."""
    diffs = []
    for key, value in now.items():
        if key not in stored:
            continue
        old = stored[key]
        if isinstance(value, (int, float)) and isinstance(old, (int, float)):
            same = math.isclose(old, value, rel_tol=rel, abs_tol=0.0)
        else:
            same = old == value
        if not same:
            diffs.append(f"{key} {old!r} -> {value!r}")
    return ", ".join(diffs)


def plan_test(rock: Rock, bond: BondParameters, lattice: Lattice, test: str,
              crossings: float | None = None, speed: float | None = None,
              confining: float = 0.0, schedule: str = "constant",
              damping: float | None = None, elastic_strain: float = 1.0e-4,
              step_size: float | None = None, relax_steps: int | None = None,
              dt_scale: float = 1.0, elastic_load: str = "compression",
              thermo_every: int | None = None) -> RunPlan:
    """Choose time step, damping, loading and run length.

    - eta: ``damping`` times the papers' damping (2D sqrt(8 m Kn)/N,
      3D d/V^(1/3) sqrt(8 m Kn)); ``crossings`` and ``damping`` default to
      :func:`bonded_lattice.schedules.default_loading` of the lattice's dimension and the
      test (2D 50 and 0.25; 3D 1000 and 1, elastic 30 and tension 100 crossings);
    - schedule ``constant`` (ours): dt = 0.1 sqrt(m/Kn) (the papers' 2e-8 s for
      1 mm quartz in 2D); platens move at a speed slow enough that loading to
      failure takes ``crossings`` elastic wave crossings of the block, unless
      ``speed`` is given;
    - schedule ``stepwise`` (alias ``paper``, :mod:`bonded_lattice.schedules`): the
      papers' time step, platen displacement per loading
      step (scaled with d / 1 mm) and relaxation steps after each
      (PAPER_SCHEDULES), unless ``step_size`` or ``relax_steps`` are given;
    - dt_scale: multiplies the time step of either schedule (convergence studies);
    - elastic_load (elastic test only): ``compression`` between the platens or ``tension``,
      the end layers pulled apart as in the tension test (ELASTIC_LOADS); the strain
      magnitude is ``elastic_strain`` either way;
    - thermo_every: time steps between thermo rows, instead of about THERMO_LINES rows per
      run (THERMO_LINES_STEPWISE loading steps' ends with the stepwise schedule); a
      stepwise run prints at the end of relaxation periods, so it is rounded up to a
      multiple of the relaxation steps;
    - steps: RUN_MARGIN times the time to reach the failure strain Cu/E or Tu/E
      (or ``elastic_strain``), counting the platens' spring overlap; strength
      decks stop by themselves once the block has failed (fix halt), and a
      single unit softens after its bonds open (3D: fails at 1.75 Cu/E).
    """
    schedule = schedule_name(schedule)
    defaults = default_loading(lattice.dim, test)
    crossings = defaults["crossings"] if crossings is None else crossings
    damping = defaults["damping"] if damping is None else damping
    if not damping >= 0:
        raise ValueError(f"damping = {damping} is out of range: need damping >= 0 "
                         "(a multiple of the papers' eta)")
    if not 0 < dt_scale <= 2:
        raise ValueError(f"dt_scale = {dt_scale} is out of range: need 0 < dt_scale <= 2")
    if not 0 < elastic_strain < 0.01:
        raise ValueError(f"elastic_strain = {elastic_strain} is out of range: need "
                         "0 < elastic_strain < 0.01 (small strain)")
    if elastic_load not in ELASTIC_LOADS:
        raise ValueError(f"elastic_load = {elastic_load!r} is not known: use one of "
                         f"{', '.join(ELASTIC_LOADS)}")
    if elastic_load != "compression" and test != "elastic":
        raise ValueError(f"elastic_load = {elastic_load!r} is for the elastic test only "
                         f"(test = {test!r})")
    if thermo_every is not None and thermo_every < 1:
        raise ValueError(f"thermo_every = {thermo_every} is out of range: need "
                         "thermo_every >= 1 (time steps)")
    dim, d = lattice.dim, lattice.d
    mass = lattice_mass(rock.rho, d, dim)
    n_across = lattice_n_across(lattice)
    if dim == 2:
        eta = paper_damping_2d(mass, bond.Kn, n_across)
    else:
        volume = lattice.n * math.sqrt(2) * d**3 / 2
        eta = paper_damping_3d(mass, bond.Kn, d, volume)
    eta *= damping
    area = lattice.loaded_area()
    height = lattice.height
    strain = target_strain(rock, test, confining, elastic_strain)
    # travel of each platen: the block's share plus the platen springs' overlap,
    # which matters for small blocks (a single unit rests on one or two particles)
    travel = strain * height / 2 + strain * rock.E * area / (end_particles(lattice) * 2 * bond.Kn)
    margin = RUN_MARGIN[test]
    if test == "periodic":
        if schedule != "constant":
            raise ValueError("the periodic test strains its box at a constant rate: use the "
                             "constant schedule")
        dt = dt_scale * DEFAULT_DT_FRACTION * math.sqrt(mass / bond.Kn)
        strain_rate = strain / (PERIODIC_STEPS * dt)
        steps = int(math.ceil(margin * PERIODIC_STEPS))
        return RunPlan(n=n_across, particles=lattice.n, d=d, mass=mass, dt=dt, eta=eta,
                       speed=0.5 * strain_rate * height, steps=steps, area=area,
                       thermo_every=max(1, steps // THERMO_LINES), strain_rate=strain_rate,
                       modulus=2.0 * rock.E)
    if schedule == "stepwise":
        paper = PAPER_SCHEDULES[dim]
        dt = dt_scale * paper["dt_fraction"] * math.sqrt(mass / bond.Kn)
        step_size = step_size if step_size is not None else paper["step_size"][test] * d / 1.0e-3
        relax_steps = relax_steps if relax_steps is not None else paper["relax_steps"]
        if not step_size > 0 or relax_steps < 1:
            raise ValueError(f"step_size = {step_size}, relax_steps = {relax_steps}: need "
                             "step_size > 0 and relax_steps >= 1")
        loading_steps = int(math.ceil(margin * travel / step_size))
        steps = loading_steps * relax_steps
        speed = step_size / (relax_steps * dt)     # the mean platen speed
        # thermo at the end of relaxation periods only
        every = (relax_steps * max(1, loading_steps // THERMO_LINES_STEPWISE)
                 if thermo_every is None else relax_steps * -(-thermo_every // relax_steps))
        return RunPlan(n=n_across, particles=lattice.n, d=d, mass=mass, dt=dt, eta=eta,
                       speed=speed, steps=steps, area=area, schedule="stepwise",
                       step_size=step_size, relax_steps=relax_steps, thermo_every=every,
                       elastic_load=elastic_load)
    dt = dt_scale * DEFAULT_DT_FRACTION * math.sqrt(mass / bond.Kn)
    wave_speed = math.sqrt(rock.E / rock.rho)
    load_time = crossings * height / wave_speed
    if speed is None:
        speed = travel / load_time
    else:
        load_time = travel / speed
    steps = int(math.ceil(margin * load_time / dt))
    return RunPlan(n=n_across, particles=lattice.n, d=d, mass=mass, dt=dt,
                   eta=eta, speed=speed, steps=steps, area=area,
                   thermo_every=max(1, steps // THERMO_LINES) if thermo_every is None
                   else thermo_every, elastic_load=elastic_load)


# energy decks run this long (s) after the failure halt's condition is first met: the
# kinetic energy of the 2166-element tension block peaks about 2 us after its stress has
# dropped below 30% of the peak, and the papers' damping takes 2 m/eta (about 1.6 us) to
# halve it; 20 us shows the peak and its decay into viscous heat (Liu 2017 Fig. 6b, B1 to B2)
ENERGY_AFTERMATH = 2.0e-5
# the longest aftermath: a tenth of a second is 1e6 steps of the papers' 3D time step
AFTERMATH_MAX = 0.1


def check_aftermath(aftermath: float) -> float:
    """``aftermath`` (s) if 0 < aftermath <= :data:`AFTERMATH_MAX`; a ValueError naming the
    value and the range otherwise."""
    if not 0.0 < aftermath <= AFTERMATH_MAX:
        raise ValueError(f"aftermath = {aftermath!r} s is out of range: need 0 < aftermath <= "
                         f"{AFTERMATH_MAX:g} s (the energy decks' run after the failure)")
    return float(aftermath)


def end_particles(lattice: Lattice) -> int:
    """Particles in the bottom layer: those touching a platen."""
    h = lattice.positions[:, lattice.axis]
    return int(np.count_nonzero(h <= h.min() + 0.1 * lattice.d))


def end_band_particles(lattice: Lattice) -> int:
    """Particles whose centres lie within 0.6 d of either end: those the end layers of a
    deck hold (:func:`bonded_lattice.decks.DeckSpec` ``ends``)."""
    h = lattice.positions[:, lattice.axis]
    return int(np.count_nonzero((h <= h.min() + 0.6 * lattice.d)
                                | (h >= h.max() - 0.6 * lattice.d)))


def end_contacts(lattice: Lattice) -> int:
    """Particles a flat platen touches at either end (centres within 0.1 d of the end)."""
    h = lattice.positions[:, lattice.axis]
    return int(np.count_nonzero((h <= h.min() + 0.1 * lattice.d)
                                | (h >= h.max() - 0.1 * lattice.d)))


END_CHOICES = ("auto",) + ENDS


def check_ends(ends: str) -> str:
    """``ends`` if one of :data:`END_CHOICES`; else a ValueError naming it."""
    if ends not in END_CHOICES:
        raise ValueError(f"ends = {ends!r} is not known: use one of {', '.join(END_CHOICES)}")
    return ends


def choose_ends(lattice: Lattice, test: str, ends: str = "auto") -> str:
    """How a test loads its block's ends (:data:`bonded_lattice.decks.ENDS`).

    ``auto``: the papers' smooth platens when the ends are flat (every particle of the end
    bands touches a platen: the papers' blocks), else ``layers``: the end bands held and
    moved, because platens on a stepped end (a rotated 2D lattice, a 3D block with its
    rows along the load) would touch only the few lowest particles and load the block
    through them.  Tension always holds the end layers; the periodic test has no ends.
    """
    check_ends(ends)
    if test in ("tension", "periodic"):
        return "platens"
    if ends != "auto":
        return ends
    return "platens" if end_contacts(lattice) == end_band_particles(lattice) else "layers"


def check_platen_stiffness(value: float) -> float:
    """``value`` if it is a valid platen stiffness (a multiple of Kn, 0 < value <=
    :data:`MAX_PLATEN_STIFFNESS`); a ValueError naming it and the range otherwise."""
    if not (math.isfinite(value) and 0 < value <= MAX_PLATEN_STIFFNESS):
        raise ValueError(f"platen_stiffness = {value} is out of range: need 0 < "
                         f"platen_stiffness <= {MAX_PLATEN_STIFFNESS:g} (a multiple of Kn; "
                         "stiffer platens need a smaller time step)")
    return value


def traction_rate(rock: Rock, lattice: Lattice, speed: float) -> float:
    """The traction grips' rate (Pa/s) that loads the block as fast as end layers moving apart
    at ``speed`` (m/s each) would: the rock's modulus times their strain rate 2 speed over the
    centres' span, so that the traction reaches Tu after as many wave crossings as the
    displacement loading reaches Tu / E."""
    if not (speed > 0 and math.isfinite(speed)):
        raise ValueError(f"speed = {speed} is out of range: need 0 < speed < inf (m/s)")
    return rock.E * 2.0 * speed / lattice.height


def has_mid_height(lattice: Lattice) -> bool:
    """Whether particles lie in the middle half of the height (for the lateral gauges)."""
    h = lattice.positions[:, lattice.axis]
    lo, hi = h.min(), h.max()
    return bool(np.any(np.abs(h - 0.5 * (lo + hi)) <= 0.25 * (hi - lo)) and lattice.n > 4)


def deck_spec(plan: RunPlan, test: str, dim: int, bond: BondParameters,
              confining: float = 0.0, dump_every: int = 0, gauges: bool = True,
              energy: bool = False, shear_frame: str = "fixed",
              grains: GrainPairOptions | None = None,
              atom_style: str = "atomic", ends: str = "platens",
              wall_kn: float | None = None, halt_fraction: float | None = None,
              grips: str = "held", traction_rate: float = 0.0,
              aftermath: float = ENERGY_AFTERMATH) -> DeckSpec:
    """The deck of a planned run (reads ``data.lattice`` beside it).

    grains: the pair style's grain keywords of a heterogeneous block, whose
    data file has a Grains section (:func:`bonded_lattice.grains.grain_arrays`).
    atom_style: that of the data file (:func:`bonded_lattice.lattice.write_data`).
    ends: ``platens`` or ``layers`` (:func:`choose_ends`).
    wall_kn: the platens' spring stiffness, or the grip springs' (N/m; default 2 Kn).
    grips: how the end layers are gripped when the test loads through them
    (:data:`bonded_lattice.decks.GRIPS`); traction_rate: the traction grips' rate (Pa/s,
    :func:`traction_rate`).
    halt_fraction: a strength test stops once |stress| falls below this fraction of its
    peak (0: never; None: DeckSpec's default).
    aftermath: energy decks run on this long (s) after the failure halt's condition is
    first met (:data:`ENERGY_AFTERMATH`; :func:`check_aftermath`).
    """
    halt = {} if halt_fraction is None else {"halt_fraction": halt_fraction}
    return DeckSpec(gauges=gauges, energy=energy, shear_frame=shear_frame, grains=grains,
                    halt_delay=int(math.ceil(check_aftermath(aftermath) / plan.dt))
                    if energy else 0,
                    atom_style=atom_style, ends=ends, wall_kn=wall_kn, grips=grips,
                    traction_rate=traction_rate,
                    test=test, dim=dim, d=plan.d, bond=bond, data_file="data.lattice",
                    area=plan.area, eta=plan.eta, speed=plan.speed, steps=plan.steps,
                    dt=plan.dt, thermo_every=plan.thermo_every, confining=confining,
                    schedule=plan.schedule, step_size=plan.step_size,
                    relax_steps=plan.relax_steps, dump_every=dump_every,
                    strain_rate=plan.strain_rate, modulus=plan.modulus,
                    elastic_load=plan.elastic_load, **halt)


def lattice_n_across(lattice: Lattice) -> int:
    """Particles across the block (2D) or elements along y (3D), from its extent."""
    extent = lattice.width if lattice.dim == 2 else float(lattice.bounds[1, 1] - lattice.bounds[1, 0])
    return int(round(extent / lattice.d)) + 1


class RockTest(Study):
    """One rock-mechanics test of a block, end to end (what ``bonded-lattice run`` does).

    plan: the test's lattice (:func:`test_lattice`) and :func:`plan_test`; write:
    ``data.lattice`` and ``in.<test>``; execute: LAMMPS on ``np_`` ranks; measure: E, nu,
    the strength (:func:`bonded_lattice.analysis.measure`) against the rock's values, and
    with a trajectory the same E and nu from it; plot: ``stress_strain.png``,
    ``energy.png`` (with ``energy``), ``broken_bonds.png`` (strength tests); summary:
    ``summary.json``.  The arguments are those of :func:`run_test`.
    """

    def __init__(self, rock: Rock, dim: int, test: str, n: int, out: str | Path, np_: int = 2,
                 d: float = 1.0e-3, progress: bool = True, bond: BondParameters | None = None,
                 dump_every: int = 0, orientation: float = 0.0, energy: bool = False,
                 shear_frame: str = "fixed", atom_style: str = "atomic",
                 pictures: bool = True, ends: str = "auto", platen_stiffness: float = 2.0,
                 halt_fraction: float | None = None, grips: str = "held",
                 aftermath: float = ENERGY_AFTERMATH, **plan_options) -> None:
        super().__init__(out, np_=np_, progress=progress, pictures=pictures)
        self.aftermath = check_aftermath(aftermath)
        self.platen_stiffness = check_platen_stiffness(platen_stiffness)
        self.grips = check_grips(grips)
        self.rock, self.dim, self.test, self.n, self.d = rock, dim, test, n, d
        self.bond = bond
        self.dump_every = dump_every
        self.orientation = orientation
        self.energy = energy
        self.shear_frame = shear_frame
        self.atom_style = atom_style
        self.ends_choice = check_ends(ends)
        self.plan_options = plan_options
        self.halt_fraction = halt_fraction
        self.confining = plan_options.get("confining", 0.0)
        # the periodic test is a tension test without platens
        self.kind = "tension" if test == "periodic" else test
        self.strength_name = {"tension": "Tu", "compression": "Cu",
                              "confined": "sigma1"}.get(self.kind)

    def _plan(self) -> None:
        if self.bond is None:
            r = self.rock
            self.bond = rock_to_bond(r.E, r.nu, r.Tu, r.Cu, r.mu_i, self.d, self.dim)
        self.lattice = test_lattice(self.dim, self.n, self.d, self.test, self.orientation)
        self.plan = plan_test(self.rock, self.bond, self.lattice, self.test, **self.plan_options)
        self.ends = choose_ends(self.lattice, self.test, self.ends_choice)

    def _accept_stored(self, stored: dict) -> dict | None:
        """The stored summary if it was made with the plan this test makes now (loading,
        damping, time step, steps); None, so that the test runs again, if its options or the
        package's defaults have changed since (a reused run must not carry old settings into
        new results)."""
        self._plan()
        changed = plan_changes(stored.get("plan", {}), asdict(self.plan))
        if changed:
            if self.progress:
                print(f"{self.out}: stored run made with another plan ({changed}); running "
                      "it again", flush=True)
            return None
        return stored

    def _write(self) -> Path:
        plan = self.plan
        write_data(self.lattice, self.out / "data.lattice", plan.mass, atom_style=self.atom_style)
        if self.dump_every > 0:   # frames on thermo rows, so each frame has its stress
            self.dump_every = plan.thermo_every * max(1, round(self.dump_every /
                                                               plan.thermo_every))
        deck = self.out / f"in.{self.test}"
        self.spec = deck_spec(plan, self.test, self.dim, self.bond, self.confining,
                              self.dump_every, has_mid_height(self.lattice), self.energy,
                              self.shear_frame, atom_style=self.atom_style, ends=self.ends,
                              wall_kn=self.platen_stiffness * self.bond.Kn,
                              halt_fraction=self.halt_fraction, grips=self.grips,
                              traction_rate=(traction_rate(self.rock, self.lattice, plan.speed)
                                             if self.grips == "traction" else 0.0),
                              aftermath=self.aftermath)
        write_deck(self.spec, deck)
        return deck

    def _total_steps(self) -> int | None:
        return self.plan.steps

    def _measure(self, result: RunResult) -> None:
        rock, test, dim, out = self.rock, self.test, self.dim, self.out
        self.thermo = thermo = result.last_thermo()
        self.got = got = measure(thermo, self.kind, dim)
        strength_name = self.strength_name
        if test == "confined":
            # the side walls restrain the lateral strain: E and nu are not measured here
            target = {"sigma1": confined_strength(rock, self.confining)}
            measured = {"sigma1": got.strength}
        else:
            target = {"E": rock.E, "nu": rock.nu}
            measured = {"E": got.E, "nu": got.nu}
            if strength_name:
                target[strength_name] = getattr(rock, strength_name)
                measured[strength_name] = got.strength
            if test == "compression" and got.c_open is not None and rock.nu > 0:
                target["C_open"] = c_open(rock.Tu, rock.nu, dim)
                measured["C_open"] = got.c_open
        self.target, self.measured = target, measured
        self.errors = {k: measured[k] / target[k] - 1.0 for k in target}
        self.from_dump = None
        if self.dump_every > 0 and test != "confined":
            # the same E and nu from the trajectory, read with MDAnalysis (a cross-check)
            E_dump, nu_dump = elastic_from_dump(out / "dump.lammpstrj", thermo, test, dim)
            self.from_dump = {"E": E_dump, "nu": nu_dump}

    def _plot(self) -> None:
        out, thermo, name = self.out, self.thermo, self.strength_name
        title = f"{self.rock.name}, {self.dim}D, {self.test}, {self.lattice.n} particles"
        # an elastic test that pulls its block plots as a tension test
        kind = "tension" if self.plan.elastic_load == "tension" else self.kind
        stress_strain_png(out / "stress_strain.png", thermo["v_strain"], thermo["v_stress"],
                          kind, self.rock.E, self.target.get(name) if name else None, title)
        if self.energy:
            energy_png(out / "energy.png", thermo, title)
        if name:
            broken_bond_map_png(out / "broken_bonds.png", out / "dump.initial",
                                out / "dump.final", self.dim, title)

    def _summary(self) -> dict:
        got, plan, result = self.got, self.plan, self.result
        assert result is not None and self.bond is not None
        return {
            "package": f"bonded-lattice {__version__}",
            "rock": asdict(self.rock),
            "dim": self.dim,
            "test": self.test,
            "particles": self.lattice.n,
            "n": self.n,
            "confining_Pa": self.confining,
            "orientation_deg": self.orientation,
            "ends": (None if self.test == "periodic" else
                     "layers" if self.spec.pulls else self.ends),
            "platen_stiffness": self.platen_stiffness,
            "grips": self.grips if self.spec.held_ends else None,
            "ranks": self.np_,
            "plan": asdict(plan),
            "bond": asdict(self.bond),
            "target": self.target,
            "measured": self.measured,
            "relative_error": self.errors,
            "broken_bonds": {"tension": got.broken_tension, "shear": got.broken_shear},
            "first_break_stress": got.first_break,
            "nu_all_particles": got.nu_all,
            "measured_from_dump": self.from_dump,
            "energy": energy_summary(self.thermo, self.out / BREAKING_LOG, plan.dt)
            if self.energy else None,
            "lateral_width_m": self.lattice.width,
            "wall_time_s": result.wall_time,
        }


def run_test(rock: Rock, dim: int, test: str, n: int, out: str | Path, np_: int = 2,
             d: float = 1.0e-3, progress: bool = True, bond: BondParameters | None = None,
             dump_every: int = 0, orientation: float = 0.0, energy: bool = False,
             shear_frame: str = "fixed", atom_style: str = "atomic", ends: str = "auto",
             platen_stiffness: float = 2.0, halt_fraction: float | None = None,
             grips: str = "held", aftermath: float = ENERGY_AFTERMATH,
             **plan_options) -> dict:
    """Run one test end to end (:class:`RockTest`) and return the summary (also written to
    summary.json).

    shear_frame: ``fixed`` (the papers') or ``corotational`` (shear measured relative to
        each particle's local rigid rotation; pair_style lattice/bond keyword shear_frame).
    atom_style: ``atomic`` (equal particles: per-type mass, the pair style's diameter;
        the default, 64 bytes less per particle than ``sphere``) or ``sphere``.
    ends: how compression, elastic and confined tests load the ends: ``auto`` (the
        default: the papers' platens for flat ends, held end layers for stepped ones),
        ``platens`` or ``layers`` (:func:`choose_ends`).

    bond: bond parameters to use instead of the rock's converted ones (calibration);
        the targets stay the rock's properties.
    platen_stiffness: the platens' springs as a multiple of Kn (0 < value <= 20); with
        ``grips="springs"`` the grip springs'.
    grips: how a test loading through its end layers grips them: ``held`` (axial motion
        prescribed, free sideways), ``clamped`` (lateral motion fixed too) or ``springs``
        (tied to moving planes by axial springs; :data:`bonded_lattice.decks.GRIPS`).
    halt_fraction: a strength test stops once |stress| falls below this fraction of its
        peak (0: runs its planned steps; None: the decks' default,
        :class:`bonded_lattice.decks.DeckSpec`).
    aftermath: with ``energy``, how long (s) the run goes on after that (default
        :data:`ENERGY_AFTERMATH`; :func:`check_aftermath`).
    plan_options: passed to :func:`plan_test` (crossings, speed, confining,
        schedule, damping, elastic_strain, elastic_load, step_size, relax_steps,
        thermo_every).
    """
    return RockTest(rock, dim, test, n, out, np_=np_, d=d, progress=progress, bond=bond,
                    dump_every=dump_every, orientation=orientation, energy=energy,
                    shear_frame=shear_frame, atom_style=atom_style, ends=ends,
                    platen_stiffness=platen_stiffness, halt_fraction=halt_fraction,
                    grips=grips, aftermath=aftermath, **plan_options).run()


ENERGY_NAMES = ("elastic", "kinetic", "gravitational", "viscous_heat", "breaking_heat_normal",
                "breaking_heat_shear", "frictional_heat", "external_work", "total", "balance_error")


def breaking_duration(path: str | Path, dt: float, fraction: float = 0.02) -> float | None:
    """Time from ``fraction`` to ``1 - fraction`` of the final breaking heat, in s, from the
    per-step log ``breaking.dat`` of a deck with the energy budget
    (:data:`bonded_lattice.decks.BREAKING_COLUMNS`); None without the file or any heat."""
    path = Path(path)
    return breaking_window(read_ave_time(path), dt, fraction) if path.exists() else None


def breaking_window(log: dict[str, np.ndarray], dt: float, fraction: float = 0.02) -> float | None:
    """:func:`breaking_duration` of the columns of a ``breaking.dat`` already read.

    ``fraction = 0`` is the 2017 paper's definition: from the first step with breaking heat to
    the step the heat reaches its final value.
    """
    if not 0.0 <= fraction < 0.5:
        raise ValueError(f"fraction = {fraction} is out of range: need 0 <= fraction < 0.5")
    step = log["TimeStep"]
    if len(step) == 0:
        return None
    heat = log[BREAKING_COLUMNS[0]] + log[BREAKING_COLUMNS[1]]
    if heat[-1] <= 0:
        return None
    onset = step[int(np.argmax(heat > fraction * heat[-1]))]
    end = step[int(np.argmax(heat >= (1 - fraction) * heat[-1]))]
    return float((end - onset) * dt)


def peak_work_fraction(values: np.ndarray, work: np.ndarray) -> float:
    """The largest |value| / |external work| once the work exceeds 1% of its final value
    (before that the ratio of two small numbers carries the start-up transient)."""
    work = np.abs(np.asarray(work, dtype=float))
    rows = work > 0.01 * work[-1] if len(work) else np.zeros(0, dtype=bool)
    return float((np.abs(np.asarray(values))[rows] / work[rows]).max()) if rows.any() else 0.0


def energy_summary(thermo: dict, breaking_log: str | Path, dt: float) -> dict:
    """Final energy budget (J; per metre of thickness in 2D) and the balance quality.

    max_balance_ratio and peak_kinetic_fraction: the largest |balance error| and kinetic
    energy over the external work at the thermo rows (:func:`peak_work_fraction`); from the
    per-step log ``breaking_log`` (strength decks write it), the peak kinetic fraction at
    every step and the time the bonds take to break, from 2% to 98% of the breaking heat and
    from its start to its end.
    """
    final = {name: float(thermo[f"c_energy[{k + 1}]"][-1]) for k, name in enumerate(ENERGY_NAMES)}
    work = thermo["c_energy[8]"]
    final["max_balance_ratio"] = peak_work_fraction(thermo["c_energy[10]"], work)
    final["peak_kinetic_fraction"] = peak_work_fraction(thermo["c_energy[2]"], work)
    log = read_ave_time(breaking_log) if Path(breaking_log).exists() else None
    per_step = log is not None and "c_energy[8]" in log and len(log["TimeStep"]) > 0
    final["peak_kinetic_fraction_every_step"] = (
        peak_work_fraction(log["c_energy[2]"], log["c_energy[8]"]) if per_step else None)
    for key, fraction in (("breaking_duration_s", 0.02), ("breaking_duration_full_s", 0.0)):
        final[key] = breaking_window(log, dt, fraction) if log is not None else None
    return final


def summary_table(summary: dict) -> str:
    """A short text table: property, target, measured, error."""
    units = {"E": (1e9, "GPa"), "nu": (1.0, ""), "Tu": (1e6, "MPa"), "Cu": (1e6, "MPa"),
             "sigma1": (1e6, "MPa"), "C_open": (1e6, "MPa")}
    lines = [f"{summary['rock']['name']}, {summary['dim']}D {summary['test']}, "
             f"{summary['particles']} particles, {summary['ranks']} ranks, "
             f"{summary['wall_time_s']:.1f} s",
             f"{'property':>13s} {'target':>12s} {'measured':>12s} {'error':>9s}"]
    for key, target in summary["target"].items():
        scale, unit = units[key]
        got = summary["measured"][key]
        lines.append(f"{key + (' (' + unit + ')' if unit else ''):>13s} {target / scale:12.5g} "
                     f"{got / scale:12.5g} {100 * summary['relative_error'][key]:+8.2f}%")
    return "\n".join(lines)
