"""One complete numerical rock test: lattice -> data file and deck -> run -> measure -> plots.

This is what ``bonded-lattice run`` does; it writes into one output folder:
``data.lattice``, ``in.<test>``, ``log.lammps``, dumps, ``stress_strain.png``,
``broken_bonds.png`` (strength tests) and ``summary.json``.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path

from . import __version__
from .analysis import measure
from .conversion import BondParameters, lattice_mass, paper_damping_2d, paper_damping_3d, rock_to_bond
from .decks import DeckSpec, write_deck
from .lattice import Lattice, close_packed_block_3d, hex_block_2d, write_data
from .plotting import broken_bond_map_png, stress_strain_png
from .rocks import Rock
from .runner import RunResult, run_deck


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


def build_lattice(dim: int, n: int, d: float) -> Lattice:
    """The papers' blocks: n particles across (2D) or n elements along y (3D)."""
    return hex_block_2d(n, d) if dim == 2 else close_packed_block_3d(n, d)


def confined_strength(rock: Rock, confining: float) -> float:
    """Axial stress at failure under confinement: sigma1 = Cu + I sigma3 (Coulomb envelope
    with I = (sqrt(1 + mu_i^2) + mu_i)^2, the factor of the conversion formulas)."""
    big_i = (math.sqrt(1.0 + rock.mu_i**2) + rock.mu_i) ** 2
    return rock.Cu + big_i * confining


def plan_test(rock: Rock, bond: BondParameters, lattice: Lattice, test: str,
              crossings: float = 100.0, speed: float | None = None,
              confining: float = 0.0) -> RunPlan:
    """Choose time step, damping, platen speed and run length.

    - dt = 0.1 sqrt(m/Kn): a tenth of the bond's vibration time scale (the
      papers' 2e-8 s for 1 mm quartz in 2D);
    - eta: the papers' damping (2D sqrt(8 m Kn)/N, 3D d/V^(1/3) sqrt(8 m Kn));
    - speed: slow enough that loading to failure takes ``crossings`` elastic
      wave crossings of the block (quasi-static), unless given;
    - steps: 1.5 times the expected time to failure (or to strain 1e-4 for the
      elastic test).
    """
    dim, d = lattice.dim, lattice.d
    mass = lattice_mass(rock.rho, d, dim)
    dt = 0.1 * math.sqrt(mass / bond.Kn)
    n_across = lattice_n_across(lattice)
    if dim == 2:
        eta = paper_damping_2d(mass, bond.Kn, n_across)
    else:
        volume = lattice.n * math.sqrt(2) * d**3 / 2
        eta = paper_damping_3d(mass, bond.Kn, d, volume)
    area = lattice.loaded_area()
    height = lattice.height
    wave_speed = math.sqrt(rock.E / rock.rho)
    target_strain = {"tension": rock.Tu / rock.E, "compression": rock.Cu / rock.E,
                     "elastic": 1.0e-4,
                     "confined": confined_strength(rock, confining) / rock.E}[test]
    load_time = crossings * height / wave_speed
    if speed is None:
        speed = target_strain * height / (2 * load_time)
    else:
        load_time = target_strain * height / (2 * speed)
    steps = int(math.ceil(1.5 * load_time / dt))
    return RunPlan(n=n_across, particles=lattice.n, d=d, mass=mass, dt=dt,
                    eta=eta, speed=speed, steps=steps, area=area)


def lattice_n_across(lattice: Lattice) -> int:
    """Particles across the block (2D) or elements along y (3D), from its extent."""
    extent = lattice.width if lattice.dim == 2 else float(lattice.bounds[1, 1] - lattice.bounds[1, 0])
    return int(round(extent / lattice.d)) + 1


def run_test(rock: Rock, dim: int, test: str, n: int, out: str | Path, np_: int = 2,
             d: float = 1.0e-3, crossings: float = 100.0, speed: float | None = None,
             progress: bool = True, confining: float = 0.0) -> dict:
    """Run one test end to end and return the summary (also written to summary.json)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, d, dim)
    lattice = build_lattice(dim, n, d)
    plan = plan_test(rock, bond, lattice, test, crossings, speed, confining)
    write_data(lattice, out / "data.lattice", plan.mass)
    spec = DeckSpec(test=test, dim=dim, d=d, bond=bond, data_file="data.lattice", area=plan.area,
                    eta=plan.eta, speed=plan.speed, steps=plan.steps, dt=plan.dt,
                    thermo_every=max(1, plan.steps // 400), confining=confining)
    deck = out / f"in.{test}"
    write_deck(spec, deck)
    result: RunResult = run_deck(deck, out, np_=np_, total_steps=plan.steps, progress=progress)
    if result.returncode != 0:
        raise RuntimeError(f"LAMMPS failed in {out}: {result.error}")
    thermo = result.last_thermo()
    got = measure(thermo, test, dim)

    strength_name = {"tension": "Tu", "compression": "Cu", "confined": "sigma1"}.get(test)
    if test == "confined":
        # the side walls restrain the lateral strain: E and nu are not measured here
        target = {"sigma1": confined_strength(rock, confining)}
        measured = {"sigma1": got.strength}
    else:
        target = {"E": rock.E, "nu": rock.nu}
        measured = {"E": got.E, "nu": got.nu}
        if strength_name:
            target[strength_name] = getattr(rock, strength_name)
            measured[strength_name] = got.strength
    errors = {k: measured[k] / target[k] - 1.0 for k in target}

    title = f"{rock.name}, {dim}D, {test}, {lattice.n} particles"
    stress_strain_png(out / "stress_strain.png", thermo["v_strain"], thermo["v_stress"], test,
                      rock.E, target.get(strength_name) if strength_name else None, title)
    if strength_name:
        broken_bond_map_png(out / "broken_bonds.png", out / "dump.initial", out / "dump.final",
                            dim, title)

    summary = {
        "package": f"bonded-lattice {__version__}",
        "rock": asdict(rock),
        "dim": dim,
        "test": test,
        "particles": lattice.n,
        "n": n,
        "confining_Pa": confining,
        "ranks": np_,
        "plan": asdict(plan),
        "bond": asdict(bond),
        "target": target,
        "measured": measured,
        "relative_error": errors,
        "broken_bonds": {"tension": got.broken_tension, "shear": got.broken_shear},
        "wall_time_s": result.wall_time,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def summary_table(summary: dict) -> str:
    """A short text table: property, target, measured, error."""
    units = {"E": (1e9, "GPa"), "nu": (1.0, ""), "Tu": (1e6, "MPa"), "Cu": (1e6, "MPa"),
             "sigma1": (1e6, "MPa")}
    lines = [f"{summary['rock']['name']}, {summary['dim']}D {summary['test']}, "
             f"{summary['particles']} particles, {summary['ranks']} ranks, "
             f"{summary['wall_time_s']:.1f} s",
             f"{'property':>9s} {'target':>12s} {'measured':>12s} {'error':>9s}"]
    for key, target in summary["target"].items():
        scale, unit = units[key]
        got = summary["measured"][key]
        lines.append(f"{key + (' (' + unit + ')' if unit else ''):>9s} {target / scale:12.5g} "
                     f"{got / scale:12.5g} {100 * summary['relative_error'][key]:+8.2f}%")
    return "\n".join(lines)
