"""Command-line tool ``bonded-lattice``: convert, generate, run, envelope, calibrate.

    bonded-lattice convert --rock quartz --dim 2
    bonded-lattice convert --dim 3 --bond 4.6794e7 8.0679e6 1.7037e-7 18.452 0.39645
    bonded-lattice generate --rock quartz --dim 2 --test tension --n 30 --out tension2d
    bonded-lattice generate --dim 2 --n 60 --grains 40 --stiffness-sd 0.2 --strength 0.5 1.5
    bonded-lattice run --rock quartz --dim 2 --test compression --n 30 --np 2 --out run2d
    bonded-lattice calibrate --rock quartz --dim 2 --n 15 --out cal2d
    bonded-lattice validate [--slow]      # rewrites docs/validation.md
    bonded-lattice scene polycrystal --n 40 --steps 20 --run --np 1 --out poly
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from . import __version__


def _rock(args: argparse.Namespace):
    from .rocks import get_rock

    return get_rock(args.rock)


def cmd_convert(args: argparse.Namespace) -> int:
    from .conversion import bond_to_rock, rock_to_bond

    if args.bond:
        kn, ks, xb, fs0, mup = args.bond
        props = bond_to_rock(kn, ks, xb, fs0, mup, args.d, args.dim)
        print(f"E = {props.E:.6g} Pa, nu = {props.nu:.6g}, Tu = {props.Tu:.6g} Pa, "
              f"Cu = {props.Cu:.6g} Pa, mu_i = {props.mu_i:.6g}")
        return 0
    rock = _rock(args)
    bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, args.d, args.dim)
    print(f"# {rock.name} ({rock.source}), d = {args.d} m, {args.dim}D")
    print(f"Kn = {bond.Kn:.6g}, Ks = {bond.Ks:.6g}, Xb = {bond.Xb:.6g}, Fs0 = {bond.Fs0:.6g}, "
          f"mu_p = {bond.mu_p:.6g}")
    print(bond.pair_coeff())
    return 0


def cmd_generate(args: argparse.Namespace) -> int:
    from .conversion import rock_to_bond
    from .decks import write_deck
    from .experiment import deck_spec, has_mid_height, plan_test, test_lattice
    from .lattice import write_data

    rock = _rock(args)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, args.d, args.dim)
    lattice = test_lattice(args.dim, args.n, args.d, args.test, args.orientation)
    plan = plan_test(rock, bond, lattice, args.test, **_plan_options(args))
    model, pair = _grain_model(args)
    grain = stiffness = None
    if model is not None:
        from .grains import grain_arrays

        grain, stiffness = grain_arrays(lattice.positions, lattice.d, model)
    write_data(lattice, out / "data.lattice", plan.mass, grain=grain, stiffness=stiffness,
               atom_style=args.atom_style)
    write_deck(deck_spec(plan, args.test, args.dim, bond, args.confining, args.dump_every,
                         has_mid_height(lattice), args.energy, args.shear_frame, pair,
                         atom_style=args.atom_style),
               out / f"in.{args.test}")
    print(f"wrote {out / 'data.lattice'} ({lattice.n} particles) and {out / ('in.' + args.test)}")
    if grain is not None:
        sizes = np.bincount(grain)
        sizes = sizes[sizes > 0]
        print(f"{len(sizes)} grains of {sizes.min()} to {sizes.max()} particles; stiffness "
              f"factors {stiffness.min():.4g} to {stiffness.max():.4g}")
    print(f"run it with: cd {out} && mpirun -np 2 lmp -in in.{args.test}")
    return 0


def cmd_run(args: argparse.Namespace) -> int:
    from .experiment import run_test, summary_table

    summary = run_test(_rock(args), args.dim, args.test, args.n, args.out, np_=args.np,
                       d=args.d, progress=not args.quiet, dump_every=args.dump_every,
                       orientation=args.orientation, energy=args.energy,
                       shear_frame=args.shear_frame, atom_style=args.atom_style,
                       **_plan_options(args))
    print(summary_table(summary))
    if summary["energy"]:
        e = summary["energy"]
        print(f"energy: external work {e['external_work']:.4g} J, balance error "
              f"{e['balance_error']:.3g} J (at most {e['max_balance_ratio']:.2g} of the work), "
              f"peak kinetic energy {100 * e['peak_kinetic_fraction']:.1f}% of the work")
        duration = e["breaking_duration_s"]
        if duration:
            speed = summary["lateral_width_m"] / duration
            print(f"bonds broke within {1e6 * duration:.3g} us (2% to 98% of the breaking heat, "
                  f"every step); block width / duration = {speed:.3g} m/s")
    print(f"results in {args.out}: summary.json, stress_strain.png"
          + (", broken_bonds.png" if args.test != "elastic" else "")
          + (", energy.png" if args.energy else ""))
    return 0


def cmd_envelope(args: argparse.Namespace) -> int:
    from .analysis import coulomb_envelope
    from .experiment import run_test

    rock = _rock(args)
    peaks = []
    for p in args.pressures:
        options = {**_plan_options(args), "confining": p}
        summary = run_test(rock, args.dim, "confined", args.n, Path(args.out) / f"confined_{p:g}",
                           np_=args.np, d=args.d, progress=not args.quiet,
                           orientation=args.orientation, atom_style=args.atom_style, **options)
        peaks.append(summary["measured"]["sigma1"])
        print(f"sigma3 = {p / 1e6:8.3f} MPa   sigma1 = {peaks[-1] / 1e6:9.3f} MPa "
              f"(Coulomb target {summary['target']['sigma1'] / 1e6:9.3f} MPa)")
    cu, mu_i = coulomb_envelope(args.pressures, peaks)
    print(f"envelope: Cu = {cu / 1e6:.4g} MPa (target {rock.Cu / 1e6:.4g}), "
          f"mu_i = {mu_i:.4g} (target {rock.mu_i:.4g})")
    return 0


def cmd_calibrate(args: argparse.Namespace) -> int:
    from .calibration import calibrate, calibration_table

    result = calibrate(_rock(args), args.dim, args.n, args.out, np_=args.np, d=args.d,
                       tol=args.tol, max_runs=args.max_runs, progress=not args.quiet,
                       orientation=args.orientation, atom_style=args.atom_style,
                       **{k: v for k, v in _plan_options(args).items() if k != "confining"})
    print(calibration_table(result))
    print(f"details in {Path(args.out) / 'calibration.json'}")
    return 0 if result.converged else 1


def cmd_validate(args: argparse.Namespace) -> int:
    from .validation import validate

    doc = validate(args.out, args.doc, np_=args.np, slow=args.slow, reuse=args.reuse,
                   progress=not args.quiet)
    print(f"wrote {doc}")
    return 0


def _scene(args: argparse.Namespace):
    from .conversion import BondParameters
    from .scenes import Scene, central_spring_bond

    if args.bond:
        kn, xb = args.bond
        bond = BondParameters(kn, 0.0, xb, 1.0, 0.0)
    else:
        rock = _rock(args)
        bond = central_spring_bond(rock.E, rock.Tu, args.d)
    return Scene(args.kind, n_x=args.n, n_y=args.ny, d=args.d, bond=bond,
                 layer_thickness=args.layer_thickness, layer_contrast=args.contrast,
                 n_grains=args.grains, stiffness_sd=args.stiffness_sd,
                 strength_min=args.strength[0], strength_max=args.strength[1],
                 boundary_strength=args.boundary_strength, seed=args.grain_seed,
                 n_expanding=args.expanding, mode=args.mode, strain_step=args.strain_step,
                 n_steps=args.steps, ftol=args.ftol, crossings=args.crossings,
                 damping=args.damping, output_every=args.output_every,
                 bond_dumps=args.bond_dumps, dt_fraction=args.dt_fraction,
                 deformation=args.deformation,
                 atom_style=args.atom_style or ("sphere" if args.kind == "expanding" else "atomic"))


def cmd_scene(args: argparse.Namespace) -> int:
    from .scene_study import run_scene
    from .scenes import expected_memory, write_scene

    scene = _scene(args)
    out = Path(args.out)
    if not args.run:
        info = write_scene(scene, out)
        print(f"wrote {info['data']} ({info['particles']} particles, "
              f"{info['data_bytes'] / 1e6:.3g} MB) and {info['deck']}")
        if scene.mode == "dynamic":
            print(f"{scene.dynamic_steps()} time steps of {scene.dt():.4g} s")
        print(f"expected memory of the run: {info['memory_bytes'] / 1e6:.0f} MB on 1 rank, "
              f"{expected_memory(scene.n, 2, scene.atom_style) / 1e6:.0f} MB on 2")
        if info["expanding"]:
            print(f"expanding grains: {info['expanding']}")
        print(f"run it with: cd {out} && mpirun -np 2 lmp -in {Path(info['deck']).name}")
        return 0
    summary = run_scene(scene, out, np_=args.np, progress=not args.quiet)
    o = summary["orientation"]
    orientation = (f"mean broken-bond orientation {o['mean']:.3g} deg from x"
                   if summary["broken"] else "no broken bond to orient")
    print(f"{summary['kind']} ({summary['mode']}, {summary['particles']} particles): "
          f"{summary['broken']} broken bonds ({summary['broken_tension']} tension, "
          f"{summary['broken_shear']} shear) at strain {summary['strain']:.4g}; peak "
          f"stress {summary['peak_stress'] / 1e6:.4g} MPa; {orientation}; "
          f"{summary['steps']} steps or iterations; {summary['wall_time_s']} s")
    print(f"wrote {out}/summary.json, broken_bonds.png, stress_strain.png")
    return 0


def cmd_info(args: argparse.Namespace) -> int:
    from .plugin import plugin_path

    print(f"bonded-lattice {__version__}")
    print(f"plugin: {plugin_path()}")
    return 0


def _grain_model(args: argparse.Namespace):
    """The heterogeneous model the options ask for, and its pair style keywords (or None, None)."""
    from .grains import GrainModel, GrainPairOptions

    if args.grains is not None:
        model = GrainModel("voronoi", n_grains=args.grains, periodic=(args.periodic_grains,) * 2,
                           stiffness_sd=args.stiffness_sd, seed=args.grain_seed)
    elif args.grain_file is not None:
        source = "elle" if Path(args.grain_file).suffix == ".elle" else "polygons"
        model = GrainModel(source, path=args.grain_file, stiffness_sd=args.stiffness_sd,
                           seed=args.grain_seed, outside=args.outside)
    elif args.layer is not None:
        model = GrainModel("layer", layer_thickness=args.layer[0], layer_contrast=args.layer[1],
                           layer_axis=args.layer_normal, stiffness_sd=args.stiffness_sd,
                           seed=args.grain_seed)
    else:
        return None, None
    pair = GrainPairOptions(args.strength[0], args.strength[1], args.grain_seed,
                            args.boundary_strength)
    return model, pair


def _heterogeneity(p: argparse.ArgumentParser) -> None:
    """Options of a heterogeneous block (generate)."""
    g = p.add_argument_group("heterogeneous rock (grains.py; needs pair_style lattice/bond's "
                             "grain keywords)")
    source = g.add_mutually_exclusive_group()
    source.add_argument("--grains", type=int, default=None, metavar="N",
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
    g.add_argument("--outside", choices=("error", "nearest"), default="error",
                   help="--grain-file: particles in no polygon are an error (default) or join "
                   "the nearest polygon")
    g.add_argument("--stiffness-sd", type=float, default=0.0,
                   help="standard deviation of the grains' stiffness factors (mean 1; default 0)")
    g.add_argument("--strength", type=float, nargs=2, default=(1.0, 1.0), metavar=("MIN", "MAX"),
                   help="bond strength factors drawn uniformly in [MIN, MAX] (default 1 1)")
    g.add_argument("--boundary-strength", type=float, default=0.5,
                   help="strength factor of bonds across grain boundaries (default 0.5)")
    g.add_argument("--grain-seed", type=int, default=1,
                   help="seed of the grains, their stiffness and the bond strengths (default 1)")


def _plan_options(args: argparse.Namespace) -> dict:
    """The loading options of a test, as keyword arguments of experiment.plan_test."""
    return {"crossings": args.crossings, "speed": args.speed,
            "confining": getattr(args, "confining", 0.0),
            "schedule": args.schedule, "damping": args.damping,
            "elastic_strain": args.elastic_strain, "step_size": args.step_size,
            "relax_steps": args.relax_steps}


def _common(p: argparse.ArgumentParser, test: bool = True, choose_test: bool = True) -> None:
    """Options shared by the subcommands; ``choose_test`` adds --test and --confining."""
    p.add_argument("--rock", default="quartz", help="rock from the library (default quartz)")
    p.add_argument("--dim", type=int, choices=(2, 3), default=2)
    p.add_argument("--d", type=float, default=1.0e-3, help="particle diameter in m (default 1e-3)")
    if test and choose_test:
        p.add_argument("--test", choices=("tension", "compression", "elastic", "confined",
                                          "periodic"),
                       default="compression",
                       help="periodic: uniaxial tension of a periodic cell (fix deform, lateral "
                       "faces at zero stress): E, nu and Tu with no platens and no boundary layer")
        p.add_argument("--confining", type=float, default=0.0,
                       help="confining stress of --test confined, Pa (compression positive)")
    if test:
        p.add_argument("--n", type=int, default=30,
                       help="particles across (2D) or elements along y (3D); default 30")
        p.add_argument("--crossings", type=float, default=None,
                       help="elastic wave crossings during loading (quasi-static control; "
                       "default 50 in 2D, 100 in 3D: docs/speed_error.md)")
        p.add_argument("--speed", type=float, default=None, help="platen speed in m/s (overrides --crossings)")
        p.add_argument("--schedule", choices=("constant", "paper"), default="constant",
                       help="constant: platens at constant speed (default, fast); paper: the "
                       "papers' stepwise loading with relaxation steps (slow reference)")
        p.add_argument("--step-size", type=float, default=None,
                       help="paper schedule: platen displacement per loading step, m")
        p.add_argument("--relax-steps", type=int, default=None,
                       help="paper schedule: time steps after each loading step")
        p.add_argument("--damping", type=float, default=None,
                       help="viscous damping as a multiple of the papers' eta (default 0.25 "
                       "in 2D, 1 in 3D: docs/speed_error.md)")
        p.add_argument("--elastic-strain", type=float, default=1.0e-4,
                       help="axial strain reached by --test elastic (default 1e-4)")
        p.add_argument("--orientation", type=float, default=0.0,
                       help="2D: degrees from the x axis to the close-packed rows (default 0, "
                       "the papers' set-up; 30 puts one bond family along the load)")
        p.add_argument("--energy", action="store_true",
                       help="energy budget (compute lattice/energy) in the output, energy.png")
        p.add_argument("--shear-frame", choices=("fixed", "corotational"), default="fixed",
                       help="pair_style lattice/bond shear_frame: fixed (the papers', default) "
                       "or corotational (shear relative to the local rigid rotation)")
        p.add_argument("--atom-style", choices=("atomic", "sphere"), default="atomic",
                       help="atomic (default: equal particles, per-type mass, pair_style "
                       "lattice/bond diameter D; 64 bytes less per particle) or sphere "
                       "(per-particle diameter and mass)")
        p.add_argument("--dump-every", type=int, default=0,
                       help="write dump.lammpstrj every this many steps (0: only the first "
                       "and last configurations)")
        p.add_argument("--out", default="bonded-lattice-run", help="output folder")


def _running(p: argparse.ArgumentParser) -> None:
    """Options of the subcommands that run LAMMPS."""
    p.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    p.add_argument("--quiet", action="store_true", help="no progress output")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bonded-lattice",
                                     description="Bonded close-packed lattice DEM for LAMMPS.")
    parser.add_argument("--version", action="version", version=f"bonded-lattice {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("convert", help="rock properties <-> bond parameters")
    _common(p, test=False)
    p.add_argument("--bond", type=float, nargs=5, metavar=("Kn", "Ks", "Xb", "Fs0", "mu_p"),
                   help="convert these bond parameters to rock properties")
    p.set_defaults(func=cmd_convert)

    p = sub.add_parser("generate", help="write a lattice data file and a test deck")
    _common(p)
    _heterogeneity(p)
    p.set_defaults(func=cmd_generate)

    p = sub.add_parser("run", help="generate, run, measure and plot one test")
    _common(p)
    _running(p)
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("envelope", help="confined tests at several pressures: Cu and mu_i")
    _common(p)
    p.add_argument("--pressures", type=float, nargs="+", default=[0.0, 10e6, 20e6],
                   help="confining stresses in Pa (default 0 10e6 20e6)")
    _running(p)
    p.set_defaults(func=cmd_envelope)

    p = sub.add_parser("calibrate", help="adjust the bond parameters until this lattice's "
                       "E, nu, Tu and Cu match the rock")
    _common(p, choose_test=False)
    _running(p)
    p.add_argument("--tol", type=float, default=0.01,
                   help="relative tolerance per property (default 0.01)")
    p.add_argument("--max-runs", type=int, default=5, help="test runs per stage at most")
    p.set_defaults(func=cmd_calibrate)

    p = sub.add_parser("validate", help="reproduce the papers' tests and write "
                       "docs/validation.md")
    p.add_argument("--out", default="validation-runs", help="folder for the runs")
    p.add_argument("--doc", default="docs/validation.md", help="the document to write")
    _running(p)
    p.add_argument("--slow", action="store_true",
                   help="also the largest sizes and the papers' schedule (about an hour)")
    p.add_argument("--reuse", action="store_true",
                   help="keep runs whose summary.json exists (rewrite the doc only)")
    p.set_defaults(func=cmd_validate)

    p = sub.add_parser("scene", help="a Mike/Elle scene: competent layer, polycrystal or "
                       "expanding grains in a box of frictionless walls")
    p.add_argument("kind", choices=["layer-extension", "layer-compression", "polycrystal",
                                    "expanding"])
    p.add_argument("--mode", choices=["quasistatic", "dynamic"], default="quasistatic")
    p.add_argument("--n", type=int, default=40, help="particles per row (default 40)")
    p.add_argument("--ny", type=int, default=0, help="rows (default: a square box)")
    p.add_argument("--d", type=float, default=1e-3, help="particle diameter, m")
    p.add_argument("--rock", default="quartz", help="rock whose E and Tu give Kn and Xb")
    p.add_argument("--bond", type=float, nargs=2, metavar=("Kn", "Xb"),
                   help="central-spring parameters directly (Ks = mu_p = 0)")
    p.add_argument("--steps", type=int, default=30, help="strain steps (default 30)")
    p.add_argument("--strain-step", type=float, default=2e-5,
                   help="strain (or grain growth) per step (default 2e-5)")
    p.add_argument("--ftol", type=float, default=1e-3,
                   help="relaxation tolerance, fraction of Kn Xb (default 1e-3)")
    p.add_argument("--crossings", type=float, default=50.0,
                   help="dynamic: P-wave crossings of the box over the whole loading")
    p.add_argument("--deformation", choices=("pure-shear", "uniaxial"), default="pure-shear",
                   help="pure shear (default: the other axis keeps the area) or uniaxial (the "
                   "walls across the other axis held)")
    p.add_argument("--dt-fraction", type=float, default=0.19,
                   help="dynamic: time step as a fraction of the critical one (default 0.19, "
                   "at most 0.5)")
    p.add_argument("--damping", type=float, default=1.0,
                   help="dynamic: factor on the papers' damping sqrt(8 m Kn)/N")
    p.add_argument("--layer-thickness", type=float, default=0.2,
                   help="layer thickness, fraction of the box height (default 0.2)")
    p.add_argument("--contrast", type=float, default=3.0,
                   help="layer stiffness / matrix stiffness (default 3)")
    p.add_argument("--grains", type=int, default=12, help="Voronoi grains (default 12)")
    p.add_argument("--stiffness-sd", type=float, default=0.15,
                   help="sd of the grains' stiffness factors, mean 1 (default 0.15)")
    p.add_argument("--strength", type=float, nargs=2, default=[0.8, 1.2],
                   metavar=("MIN", "MAX"), help="bond strength factors, uniform (0.8 1.2)")
    p.add_argument("--boundary-strength", type=float, default=None,
                   help="strength factor across grain boundaries (default 0.5; 1 for the "
                   "layer's interfaces)")
    p.add_argument("--grain-seed", type=int, default=1, help="seed of grains and strengths")
    p.add_argument("--expanding", type=int, default=2, help="growing grains (default 2)")
    p.add_argument("--output-every", type=int, default=1,
                   help="strain steps between lines of scene.dat (dynamic; default 1)")
    p.add_argument("--bond-dumps", type=int, default=0,
                   help="dump the bond records every this many strain steps (0: only at the end)")
    p.add_argument("--atom-style", choices=("atomic", "sphere"), default=None,
                   help="atomic (equal particles, per-type mass; default) or sphere (default "
                   "and required for expanding, whose grains change their diameters)")
    p.add_argument("--run", action="store_true", help="run it, measure and plot")
    p.add_argument("--out", default="scene", help="output folder")
    _running(p)
    p.set_defaults(func=cmd_scene)

    p = sub.add_parser("info", help="package version and plugin location")
    p.set_defaults(func=cmd_info)

    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, KeyError, RuntimeError, FileNotFoundError) as exc:
        print(f"bonded-lattice {args.command}: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
