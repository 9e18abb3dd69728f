"""Command-line tool ``bonded-lattice``: convert, generate, run, envelope, calibrate, rocks.

    bonded-lattice convert --rock quartz --dim 2
    bonded-lattice convert --rock-file my-rocks.toml --rock my-granite --dim 2
    bonded-lattice rocks [--rock-file my-rocks.toml]
    bonded-lattice convert --dim 3 --bond 4.6794e7 8.0679e6 1.7037e-7 18.452 0.39645
    bonded-lattice generate --rock quartz --dim 2 --test tension --n 30 --out tension2d
    bonded-lattice generate --dim 2 --n 60 --grains 40 --stiffness-sd 0.2 --strength 0.5 1.5
    bonded-lattice run --rock quartz --dim 2 --test compression --n 30 --np 2 --out run2d
    bonded-lattice calibrate --rock quartz --dim 2 --n 15 --out cal2d
    bonded-lattice validate [--slow]      # docs/validation.json and .md
    bonded-lattice scene polycrystal --n 40 --steps 20 --run --np 1 --out poly
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from . import __version__
from .cli_options import (add, heterogeneity_options, plan_options, running_options,
                          scene_options, test_options)


def _rock(args: argparse.Namespace):
    """The rock of ``--rock`` and ``--rock-file`` (:func:`bonded_lattice.rock_file.choose_rock`)."""
    from .cli_options import TEST_DEFAULTS
    from .rock_file import choose_rock

    return choose_rock(getattr(args, "rock", None), getattr(args, "rock_file", None),
                       default=TEST_DEFAULTS["rock"])


def cmd_rocks(args: argparse.Namespace) -> int:
    from .rock_file import read_rock_file, rock_summary
    from .rocks import ROCKS

    file_rocks = read_rock_file(args.rock_file) if args.rock_file else {}
    print("# values in GPa, MPa and kg/m^3 (rock files give them in SI: Pa, kg/m^3); "
          "lattice: the dimensions that reproduce all five properties")
    groups = [("library", sorted(ROCKS.values(), key=lambda r: r.name))]
    if args.rock_file:
        groups.append((str(args.rock_file), list(file_rocks.values())))
    for where, rocks in groups:
        for rock in rocks:
            print(f"{rock.name} ({where})")
            print("\n".join(rock_summary(rock)))
    return 0


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
    from .experiment import (check_platen_stiffness, choose_ends, deck_spec, has_mid_height,
                             plan_test, test_lattice)
    from .lattice import write_data

    rock = _rock(args)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, args.d, args.dim)
    lattice = test_lattice(args.dim, args.n, args.d, args.test, args.orientation)
    plan = plan_test(rock, bond, lattice, args.test, **plan_options(args))
    model, pair = _grain_model(args)
    grain = stiffness = None
    if model is not None:
        from .grains import grain_arrays

        grain, stiffness = grain_arrays(lattice.positions, lattice.d, model)
    write_data(lattice, out / "data.lattice", plan.mass, grain=grain, stiffness=stiffness,
               atom_style=args.atom_style)
    write_deck(deck_spec(plan, args.test, args.dim, bond, args.confining, args.dump_every,
                         has_mid_height(lattice), args.energy, args.shear_frame, pair,
                         atom_style=args.atom_style,
                         ends=choose_ends(lattice, args.test, args.ends),
                         wall_kn=check_platen_stiffness(args.platen_stiffness) * bond.Kn,
                         grips=args.grips),
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
                       ends=args.ends, platen_stiffness=args.platen_stiffness,
                       grips=args.grips, **plan_options(args))
    print(summary_table(summary))
    if summary["energy"]:
        e = summary["energy"]
        print(f"energy: external work {e['external_work']:.4g} J, balance error "
              f"{e['balance_error']:.3g} J (at most {e['max_balance_ratio']:.2g} of the work), "
              f"peak kinetic energy {100 * e['peak_kinetic_fraction']:.1f}% of the work "
              "(thermo rows)" + ("" if e["peak_kinetic_fraction_every_step"] is None else
                                 f", {100 * e['peak_kinetic_fraction_every_step']:.1f}% (every "
                                 "step)"))
        duration = e["breaking_duration_s"]
        if duration:
            speed = summary["lateral_width_m"] / duration
            print(f"bonds broke within {1e6 * duration:.3g} us (2% to 98% of the breaking heat, "
                  f"every step; {1e6 * e['breaking_duration_full_s']:.3g} us from its start to "
                  f"its end); block width / duration = {speed:.3g} m/s")
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
        options = {**plan_options(args), "confining": p}
        summary = run_test(rock, args.dim, "confined", args.n, Path(args.out) / f"confined_{p:g}",
                           np_=args.np, d=args.d, progress=not args.quiet,
                           orientation=args.orientation, atom_style=args.atom_style,
                           ends=args.ends, platen_stiffness=args.platen_stiffness, **options)
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
                       **{k: v for k, v in plan_options(args).items() if k != "confining"})
    print(calibration_table(result))
    print(f"details in {Path(args.out) / 'calibration.json'}")
    return 0 if result.converged else 1


def cmd_validate(args: argparse.Namespace) -> int:
    from .validation import validate

    sections = args.sections.split(",") if args.sections else None
    doc = validate(args.out, args.doc, np_=args.np, slow=args.slow, reuse=args.reuse,
                   progress=not args.quiet, sections=sections, results=args.results,
                   doc_only=args.doc_only)
    print(f"wrote {doc}")
    return 0


def scene_from_args(args: argparse.Namespace):
    """The :class:`bonded_lattice.scenes.Scene` of parsed ``scene`` options (the command line's
    meaning of them, also for scripts that print the commands they run)."""
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
                 matrix_strength=args.matrix_strength, n_grains=args.grains, stiffness_sd=args.stiffness_sd,
                 strength_min=args.strength[0], strength_max=args.strength[1],
                 boundary_strength=args.boundary_strength, seed=args.grain_seed,
                 n_expanding=args.expanding, mode=args.mode, strain_step=args.strain_step,
                 n_steps=args.steps, ftol=args.ftol, relax=args.relax, threads=args.threads,
                 crossings=args.crossings,
                 damping=args.damping, output_every=args.output_every,
                 bond_dumps=args.bond_dumps, break_order=args.break_order,
                 restart_every=args.restart,
                 dt_fraction=args.dt_fraction,
                 deformation=args.deformation, boundary=args.boundary,
                 atom_style=args.atom_style or ("sphere" if args.kind == "expanding" else "atomic"))


def _cost(summary: dict) -> str:
    """The work of a scene run: its relaxations' (quasi-static) or its time steps."""
    relax = summary.get("relaxation")
    if not relax:
        return f"{summary['steps']} time steps"
    what = {"local": "sweeps", "direct": "solves"}.get(relax["method"], "minimiser iterations")
    extra = (f", {relax.get('factorisations', 0)} factorisations"
             if relax["method"] == "direct" else "")
    return (f"{relax['relaxations']} relaxations, {relax['iterations']} {what}{extra}, "
            f"{relax['updates']:.3g} particle updates")


def _fracture_line(summary: dict) -> str:
    """The fracture measures of a scene's summary (those of its kind), one line."""
    def num(value: float | None) -> str:
        return "undefined" if value is None else f"{value:.3g}"

    if "fractures_in_layer" in summary:
        return (f"fractures crossing the layer {summary['fractures_in_layer']}; broken bonds "
                f"in the layer {num(summary['fraction_in_layer'])}; spacing / thickness "
                f"{num(summary['spacing_to_thickness'])}; scanline along the layer's middle "
                f"row {summary.get('scanline_fractures', 'undefined')} fractures, spacing / "
                f"thickness {num(summary.get('scanline_spacing_to_thickness'))}")
    line = f"intergranular broken bonds {num(summary['intergranular_fraction'])}"
    if "radial_fractures" in summary:
        line += f"; radial fractures {summary['radial_fractures']}"
    return line


def cmd_scene(args: argparse.Namespace) -> int:
    from .scene_study import run_scene
    from .scenes import expected_memory, write_scene

    scene = scene_from_args(args)
    out = Path(args.out)
    if args.resume and not args.run:
        raise SystemExit("bonded-lattice scene: --resume goes on with a run; add --run")
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
    summary = run_scene(scene, out, np_=args.np, progress=not args.quiet, resume=args.resume)
    o = summary["orientation"]
    orientation = (f"mean broken-bond orientation {o['mean']:.3g} deg from x"
                   if summary["broken"] else "no broken bond to orient")
    print(f"{summary['kind']} ({summary['mode']}, {summary['particles']} particles): "
          f"{summary['broken']} broken bonds ({summary['broken_tension']} tension, "
          f"{summary['broken_shear']} shear) at strain {summary['strain']:.4g}; peak "
          f"stress {summary['peak_stress'] / 1e6:.4g} MPa; {orientation}; "
          f"{_cost(summary)}; {summary['wall_time_s']} s")
    print(_fracture_line(summary))
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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bonded-lattice",
                                     description="Bonded close-packed lattice DEM for LAMMPS.")
    parser.add_argument("--version", action="version", version=f"bonded-lattice {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("convert", help="rock properties <-> bond parameters")
    test_options(p, test=False)
    p.add_argument("--bond", type=float, nargs=5, metavar=("Kn", "Ks", "Xb", "Fs0", "mu_p"),
                   help="convert these bond parameters to rock properties")
    p.set_defaults(func=cmd_convert)

    p = sub.add_parser("generate", help="write a lattice data file and a test deck")
    test_options(p)
    heterogeneity_options(p)
    p.set_defaults(func=cmd_generate)

    p = sub.add_parser("run", help="generate, run, measure and plot one test")
    test_options(p)
    running_options(p)
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("envelope", help="confined tests at several pressures: Cu and mu_i")
    test_options(p)
    p.add_argument("--pressures", type=float, nargs="+", default=[0.0, 10e6, 20e6],
                   help="confining stresses in Pa (default 0 10e6 20e6)")
    running_options(p)
    p.set_defaults(func=cmd_envelope)

    p = sub.add_parser("calibrate", help="adjust the bond parameters until this lattice's "
                       "E, nu, Tu and Cu match the rock")
    test_options(p, choose_test=False)
    running_options(p)
    p.add_argument("--tol", type=float, default=0.01,
                   help="relative tolerance per property (default 0.01)")
    p.add_argument("--max-runs", type=int, default=5, help="test runs per stage at most")
    p.set_defaults(func=cmd_calibrate)

    p = sub.add_parser("validate", help="reproduce the papers' tests and write "
                       "docs/validation.md")
    p.add_argument("--out", default="validation-runs", help="folder for the runs")
    p.add_argument("--doc", default="docs/validation.md", help="the document to write")
    running_options(p)
    p.add_argument("--slow", action="store_true",
                   help="also the largest sizes and the papers' schedule (about an hour)")
    p.add_argument("--reuse", action="store_true",
                   help="keep runs whose summary.json exists")
    p.add_argument("--sections", default="",
                   help="comma-separated sections to run (default: all); the others keep "
                   "their data in the results file")
    p.add_argument("--results", default=None,
                   help="the results file (default: the doc's name with .json)")
    p.add_argument("--doc-only", action="store_true",
                   help="run nothing: rewrite the doc from the results file")
    p.set_defaults(func=cmd_validate)

    p = sub.add_parser("scene", help="a Mike/Elle scene: competent layer, polycrystal or "
                       "expanding grains in a box of frictionless walls")
    scene_options(p)
    running_options(p)
    p.set_defaults(func=cmd_scene)

    p = sub.add_parser("rocks", help="list the rocks (the library's and, with --rock-file, "
                       "the file's) with their values, units and sources")
    add(p, "rock_file", None)
    p.set_defaults(func=cmd_rocks)

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
