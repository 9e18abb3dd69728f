"""The command line's options, declared once and shared by the subcommands of ``bonded-lattice``.

Every option that more than one subcommand takes (``--rock``, ``--rock-file``, ``--d``, ``--n``,
``--crossings``, ``--damping``, ``--grains``, ``--stiffness-sd``, ``--strength``,
``--boundary-strength``, ``--grain-seed``, ``--atom-style``, ``--out``, ``--np``,
``--quiet``) has one entry in :data:`OPTIONS`: its flag, type and help.  A subcommand adds
it with :func:`add` and its default, which is stated once, where the library states it:

- the rock tests (``generate``, ``run``, ``envelope``, ``calibrate``): the keyword defaults
  of :func:`bonded_lattice.experiment.run_test` and :func:`~bonded_lattice.experiment.plan_test`
  (``crossings`` and ``damping``: :func:`bonded_lattice.schedules.default_loading`), and
  :data:`TEST_DEFAULTS` for what only the command line chooses;
- the heterogeneous block (``generate``): the fields of
  :class:`~bonded_lattice.grains.GrainModel` and :class:`~bonded_lattice.grains.GrainPairOptions`;
- ``scene``: the fields of :class:`bonded_lattice.scenes.Scene`.

The schedules' names are those of :mod:`bonded_lattice.schedules`: ``--schedule constant``
or ``--schedule stepwise``; ``--schedule paper`` is accepted as an alias of ``stepwise``.
"""

from __future__ import annotations

import argparse
import inspect
from dataclasses import MISSING, dataclass, field, fields
from typing import Any, Callable

from .decks import ELASTIC_LOADS, GRIPS, SHEAR_FRAMES, TESTS
from .experiment import END_CHOICES, plan_test, run_test
from .grains import GrainModel, GrainPairOptions
from .lattice import ATOM_STYLES
from .scenes import BOUNDARIES, DEFORMATIONS, KINDS, MODES, RELAXATIONS, Scene
from .schedules import DEFAULT_CROSSINGS_BY_TEST, DEFAULT_LOADING, SCHEDULE_ALIASES, SCHEDULES

__all__ = ["OPTIONS", "TEST_DEFAULTS", "add", "heterogeneity_options", "plan_options",
           "rock_options", "running_options", "scene_options", "test_options"]


@dataclass(frozen=True)
class Option:
    """One command-line option: its flags, its help (``%(default)s`` names the
    subcommand's default) and the other ``add_argument`` keywords (type, nargs ...)."""

    flags: tuple[str, ...]
    help: str
    kwargs: dict[str, Any] = field(default_factory=dict)


def _option(*flags: str, help: str, **kwargs: Any) -> Option:
    return Option(flags, help, kwargs)


def _loading_default(name: str) -> str:
    """The default of ``crossings`` or ``damping`` per dimension, with the per-test crossings
    (:data:`~bonded_lattice.schedules.DEFAULT_CROSSINGS_BY_TEST`) in brackets."""
    parts = []
    for dim, values in DEFAULT_LOADING.items():
        text = f"{values[name]:g} in {dim}D"
        per_test = DEFAULT_CROSSINGS_BY_TEST[dim] if name == "crossings" else {}
        if per_test:
            text += " except " + ", ".join(f"{t} {c:g}" for t, c in per_test.items())
        parts.append(text)
    return ", ".join(parts)


OPTIONS: dict[str, Option] = {
    "rock": _option("--rock", help="rock from the library or the --rock-file (default: the "
                    "rock file's rock if it holds one, else quartz; `bonded-lattice rocks` lists "
                    "them)"),
    "rock_file": _option("--rock-file", metavar="PATH",
                         help="your own rocks: a TOML or JSON file of entries with E, nu, Tu, "
                         "Cu (Pa), mu_i, rho (kg/m^3) and source, checked like the library's "
                         "(docs/python.md, 'Your own rocks')"),
    "d": _option("--d", type=float, help="particle diameter in m (default %(default)g)"),
    # (the subcommands give these their own help: the same option means a little more there)
    "n": _option("--n", type=int, help=""),
    "crossings": _option("--crossings", type=float, help=""),
    "damping": _option("--damping", type=float, help=""),
    "grains": _option("--grains", type=int, metavar="N", help=""),
    "stiffness_sd": _option("--stiffness-sd", type=float,
                            help="standard deviation of the grains' stiffness factors (mean 1; "
                            "default %(default)s)"),
    "strength": _option("--strength", type=float, nargs=2, metavar=("MIN", "MAX"),
                        help="bond strength factors drawn uniformly in [MIN, MAX] "
                        "(default %(default)s)"),
    "boundary_strength": _option("--boundary-strength", type=float,
                                 help="strength factor of bonds across grain boundaries "
                                 "(default %(default)s)"),
    "grain_seed": _option("--grain-seed", type=int,
                          help="seed of the grains, their stiffness and the bond strengths "
                          "(default %(default)s)"),
    "atom_style": _option("--atom-style", choices=ATOM_STYLES,
                          help="atomic (equal particles, per-type mass, pair_style lattice/bond "
                          "diameter D; 64 bytes less per particle) or sphere (per-particle "
                          "diameter and mass); default %(default)s"),
    "out": _option("--out", help="output folder (default %(default)s)"),
    "np": _option("--np", type=int, help="MPI ranks (default %(default)s)"),
    "quiet": _option("--quiet", action="store_true", help="no progress output"),
}

# what only the command line chooses for the rock tests
TEST_DEFAULTS = {"rock": "quartz", "dim": 2, "test": "compression", "n": 30,
                 "out": "bonded-lattice-run", "np": 2}


def add(p: argparse.ArgumentParser | argparse._ActionsContainer, name: str, default: Any,
        help: str | None = None) -> None:
    """Add :data:`OPTIONS` ``[name]`` to ``p`` with this subcommand's default (and, where
    the option means something more specific there, its own help: needed where
    :data:`OPTIONS` has none)."""
    opt = OPTIONS[name]
    if not (help or opt.help):
        raise ValueError(f"option {name!r} needs the subcommand's help text")
    kwargs = dict(opt.kwargs)
    if kwargs.get("action") != "store_true":
        kwargs["default"] = default
    p.add_argument(*opt.flags, help=help or opt.help, **kwargs)


def _keyword_defaults(*functions: Callable) -> dict[str, Any]:
    """The keyword defaults of functions (the first one that names a keyword wins)."""
    out: dict[str, Any] = {}
    for function in functions:
        for name, par in inspect.signature(function).parameters.items():
            if par.default is not inspect.Parameter.empty:
                out.setdefault(name, par.default)
    return out


def _field_defaults(cls: type) -> dict[str, Any]:
    """The defaults of a dataclass's fields."""
    out: dict[str, Any] = {}
    for f in fields(cls):
        if f.default is not MISSING:
            out[f.name] = f.default
        elif f.default_factory is not MISSING:
            out[f.name] = f.default_factory()
    return out


def rock_options(p: argparse.ArgumentParser, help: str | None = None) -> None:
    """``--rock`` and ``--rock-file``; ``--rock`` defaults to None, which
    :func:`bonded_lattice.rock_file.choose_rock` reads as the rock file's only rock or
    :data:`TEST_DEFAULTS` ``["rock"]``."""
    add(p, "rock", None, help=help)
    add(p, "rock_file", None)


def running_options(p: argparse.ArgumentParser) -> None:
    """Options of the subcommands that run LAMMPS."""
    add(p, "np", TEST_DEFAULTS["np"])
    add(p, "quiet", False)


def test_options(p: argparse.ArgumentParser, test: bool = True, choose_test: bool = True) -> None:
    """Options of the rock tests; ``test`` adds the block and its loading, ``choose_test``
    also --test and --confining."""
    lib = _keyword_defaults(run_test, plan_test)
    rock_options(p)
    p.add_argument("--dim", type=int, choices=(2, 3), default=TEST_DEFAULTS["dim"])
    add(p, "d", lib["d"])
    if test and choose_test:
        p.add_argument("--test", choices=TESTS, default=TEST_DEFAULTS["test"],
                       help="periodic: uniaxial tension of a periodic cell (fix deform, lateral "
                       "faces at zero stress): E, nu and Tu with no platens and no boundary layer")
        p.add_argument("--confining", type=float, default=lib["confining"],
                       help="confining stress of --test confined, Pa (compression positive)")
        p.add_argument("--ends", choices=END_CHOICES, default=lib["ends"],
                       help="how compression, elastic and confined tests load the block's ends: "
                       "platens (the papers'), layers (the end layers held and pushed, for "
                       "stepped ends) or auto (default: platens for flat ends, layers for the "
                       "stepped ends of a turned lattice)")
        p.add_argument("--platen-stiffness", type=float, default=lib["platen_stiffness"],
                       help="the platens' springs as a multiple of the bonds' Kn (default "
                       "%(default)g; 0 < value <= 20): a block's compressive deficit grows as "
                       "they soften (docs/validation.md, 'The platens decide the compressive "
                       "deficit')")
        p.add_argument("--grips", choices=GRIPS, default=lib["grips"],
                       help="how a test that loads through the end layers (tension, --ends "
                       "layers) grips them: held (default: axial motion prescribed, free "
                       "sideways), clamped (lateral motion fixed too), springs (tied to moving "
                       "smooth planes by axial springs of --platen-stiffness x Kn), traction "
                       "(every end particle pulled by the same force, ramped at a constant "
                       "rate) or wide (the two outermost rows or layers held)")
    if not test:
        return
    add(p, "n", TEST_DEFAULTS["n"], help="particles across (2D) or elements along y (3D); "
        "default %(default)s")
    add(p, "crossings", lib["crossings"],
        help="elastic-wave crossings of the block during the loading (quasi-static control; "
        f"default {_loading_default('crossings')}: docs/speed_error.md)")
    p.add_argument("--speed", type=float, default=lib["speed"],
                   help="platen speed in m/s (overrides --crossings)")
    aliases = ", ".join(f"{a} (an alias of {n})" for a, n in SCHEDULE_ALIASES.items())
    p.add_argument("--schedule", choices=SCHEDULES + tuple(SCHEDULE_ALIASES),
                   default=lib["schedule"],
                   help="constant: platens at constant speed (default, fast); stepwise: the "
                   "papers' loading, platen jumps with relaxation steps (slow reference); "
                   f"{aliases}")
    p.add_argument("--step-size", type=float, default=lib["step_size"],
                   help="stepwise schedule: platen displacement per loading step, m")
    p.add_argument("--relax-steps", type=int, default=lib["relax_steps"],
                   help="stepwise schedule: time steps after each loading step")
    add(p, "damping", lib["damping"],
        help="viscous damping as a multiple of the papers' eta (default "
        f"{_loading_default('damping')}: docs/speed_error.md)")
    p.add_argument("--elastic-strain", type=float, default=lib["elastic_strain"],
                   help="axial strain reached by --test elastic (default %(default)g)")
    p.add_argument("--elastic-load", choices=ELASTIC_LOADS, default=lib["elastic_load"],
                   help="--test elastic: compression between the platens (default) or "
                   "tension, the end layers pulled apart; bonds unbreakable either way")
    p.add_argument("--orientation", type=float, default=lib["orientation"],
                   help="2D: degrees from the x axis to the close-packed rows (default "
                   "%(default)g, the papers' set-up; 30 puts one bond family along the load); "
                   "3D: 0 (the paper's, layers across the load) or 90 (rows along the load)")
    p.add_argument("--energy", action="store_true",
                   help="energy budget (compute lattice/energy) in the output, energy.png")
    p.add_argument("--shear-frame", choices=SHEAR_FRAMES, default=lib["shear_frame"],
                   help="pair_style lattice/bond shear_frame: fixed (the papers', default) "
                   "or corotational (shear relative to the local rigid rotation)")
    add(p, "atom_style", lib["atom_style"])
    p.add_argument("--dump-every", type=int, default=lib["dump_every"],
                   help="write dump.lammpstrj every this many steps (0: only the first "
                   "and last configurations)")
    add(p, "out", TEST_DEFAULTS["out"])


def heterogeneity_options(p: argparse.ArgumentParser) -> None:
    """Options of a heterogeneous block (generate)."""
    model, pair = _field_defaults(GrainModel), _field_defaults(GrainPairOptions)
    g = p.add_argument_group("heterogeneous rock (grains.py; needs pair_style lattice/bond's "
                             "grain keywords)")
    source = g.add_mutually_exclusive_group()
    add(source, "grains", None,
        help="N grains from a seeded Voronoi tessellation of the block")
    source.add_argument("--grain-file", default=None, metavar="PATH",
                        help="grain polygons: an Elle file (*.elle: its unit cell mapped onto "
                        "the block, periodic) or a plain file of lines 'grain x1 y1 x2 y2 ...' "
                        "in metres")
    source.add_argument("--layer", type=float, nargs=2, default=None,
                        metavar=("THICKNESS", "CONTRAST"),
                        help="a competent layer of THICKNESS m across the middle of the block, "
                        "CONTRAST times stiffer than the matrix")
    g.add_argument("--layer-normal", choices=("x", "y"), default="x",
                   help="axis normal to the layer (default x: the layer is parallel to the load)")
    g.add_argument("--periodic-grains", action="store_true",
                   help="--grains: Voronoi cells periodic across the block's sides")
    g.add_argument("--outside", choices=("error", "nearest"), default=model["outside"],
                   help="--grain-file: particles in no polygon are an error (default) or join "
                   "the nearest polygon")
    add(g, "stiffness_sd", model["stiffness_sd"])
    add(g, "strength", (pair["strength_min"], pair["strength_max"]))
    add(g, "boundary_strength", pair["boundary_strength"])
    add(g, "grain_seed", model["seed"])


# the options only ``scene`` takes that set one number of the Scene, by the group in which
# ``scene --help`` lists them: {group: {field: (flag, help)}}; the type and the default are
# the field's
SCENE_NUMBERS = {
    "box and loading": {
        "n_y": ("--ny", "rows (default: a square box)"),
        "n_steps": ("--steps", "strain steps (default %(default)s)"),
        "strain_step": ("--strain-step", "strain (or grain growth) per step (default "
                        "%(default)g)"),
        "ftol": ("--ftol", "relaxation tolerance, fraction of Kn Xb (default: 1e-4 with "
                 "--relax local or direct, 1e-3 with --relax fire)"),
        "dt_fraction": ("--dt-fraction", "dynamic: time step as a fraction of the critical "
                        "one (default %(default)s, at most 0.5)"),
    },
    "layer and growing grains": {
        "layer_thickness": ("--layer-thickness", "layer thickness, fraction of the box "
                            "height (default %(default)s)"),
        "layer_contrast": ("--contrast", "layer stiffness / matrix stiffness (default "
                           "%(default)s)"),
        "matrix_strength": ("--matrix-strength", "the matrix's strength factor, the "
                            "layer's 1: its bonds' breaking force x this (an interface "
                            "bond's x the mean; default %(default)s)"),
        "n_expanding": ("--expanding", "growing grains (default %(default)s)"),
    },
    "output": {
        "output_every": ("--output-every", "strain steps between lines of scene.dat "
                         "(dynamic; default %(default)s)"),
        "bond_dumps": ("--bond-dumps", "dump the bond records every this many strain steps "
                       "(0: only at the end)"),
        "break_order": ("--break-order", "quasi-static: dump the bond records after each of "
                        "the first this many breaks (break.<n>.txt: their exact order)"),
        "restart_every": ("--restart", "quasi-static: write restart.scene every this many "
                          "strain steps (0: never), for --resume"),
    },
}


def relax_option(p: argparse.ArgumentParser, default: str, why: str = "") -> None:
    """``--relax``: how a quasi-static scene relaxes (:data:`bonded_lattice.scenes.RELAXATIONS`);
    ``why``: the reason for a default other than the scenes' (for the help)."""
    p.add_argument("--relax", choices=RELAXATIONS, default=default,
                   help="quasistatic: relax by lattice/quasistatic relax local, where the "
                   "forces exceed the tolerance, relax direct, Newton steps with a sparse "
                   "Cholesky factor, or FIRE over the whole box (default "
                   f"{default}{': ' + why if why else ''})")


def scene_options(p: argparse.ArgumentParser) -> None:
    """Options of ``scene``: the shared ones with the defaults of :class:`Scene`'s fields."""
    s = _field_defaults(Scene)
    p.add_argument("kind", choices=KINDS)
    p.add_argument("--mode", choices=MODES, default=s["mode"])
    relax_option(p, s["relax"])
    p.add_argument("--threads", type=int, default=s["threads"],
                   help="quasistatic, --relax direct: threads of its factor and solves on rank "
                   "0 (default %(default)s; results identical for any number)")
    p.add_argument("--deformation", choices=DEFORMATIONS, default=s["deformation"],
                   help="pure shear (default: the other axis keeps the area) or uniaxial (the "
                   "walls across the other axis held)")
    p.add_argument("--boundary", choices=BOUNDARIES, default=s["boundary"],
                   help="walls (default: a row of wall particles on each side) or periodic "
                   "(a box periodic in x and y, no walls; quasi-static only)")
    add(p, "n", s["n_x"], help="particles per row (default %(default)s)")
    add(p, "d", s["d"])
    rock_options(p, help="rock whose E and Tu give Kn and Xb, from the library or the "
                 "--rock-file (default: the rock file's rock if it holds one, else quartz)")
    p.add_argument("--bond", type=float, nargs=2, metavar=("Kn", "Xb"),
                   help="central-spring parameters directly (Ks = mu_p = 0)")
    for title, numbers in SCENE_NUMBERS.items():
        group = p.add_argument_group(title)
        for name, (flag, text) in numbers.items():
            # a field whose default is None (chosen later) takes a number
            kind = float if s[name] is None else type(s[name])
            group.add_argument(flag, type=kind, default=s[name], help=text)
    add(p, "crossings", s["crossings"],
        help="dynamic: P-wave crossings of the box over the whole loading (default %(default)g)")
    add(p, "damping", s["damping"], help="dynamic: factor on the papers' damping "
        "sqrt(8 m Kn)/N (default %(default)s)")
    add(p, "grains", s["n_grains"], help="Voronoi grains (default %(default)s)")
    add(p, "stiffness_sd", s["stiffness_sd"])
    add(p, "strength", [s["strength_min"], s["strength_max"]])
    add(p, "boundary_strength", s["boundary_strength"],
        help="strength factor across grain boundaries (default 0.5; 1 for the layer's "
        "interfaces)")
    add(p, "grain_seed", s["seed"])
    add(p, "atom_style", None, help="atomic (equal particles, per-type mass; default) or "
        "sphere (default and required for expanding, whose grains change their diameters)")
    p.add_argument("--run", action="store_true", help="run it, measure and plot")
    p.add_argument("--resume", action="store_true", help="with --run: go on with the run in "
                   "--out from its last restart file (written with --restart; give the same "
                   "options as the first run)")
    add(p, "out", "scene")


def plan_options(args: argparse.Namespace) -> dict:
    """The loading options of a test, as keyword arguments of experiment.plan_test."""
    return {"crossings": args.crossings, "speed": args.speed,
            "confining": getattr(args, "confining", 0.0),
            "schedule": args.schedule, "damping": args.damping,
            "elastic_strain": args.elastic_strain,
            "elastic_load": args.elastic_load,
            "step_size": args.step_size,
            "relax_steps": args.relax_steps}
