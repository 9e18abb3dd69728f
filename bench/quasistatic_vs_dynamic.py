"""Quasi-static against dynamic loading of one Mike/Elle scene: speed against error.

Runs the same scene (default: the polycrystal under pure shear, 50 particles
per row, 2900 particles) once with the seed's quasi-static loop and with
dynamic loading at several rates (the whole loading over C P-wave crossings
of the box, with the papers' damping or F times it), and prints a table: wall time, time steps or minimiser
iterations, broken bonds, peak sigma_xx and the orientation of the broken
bonds, each dynamic result with its difference from the quasi-static one.

    python bench/quasistatic_vs_dynamic.py                 # ~3 minutes on 1 core
    python bench/quasistatic_vs_dynamic.py --img docs/img  # also the figures

The runs go into --out (default bench-qs-dynamic/); --reuse keeps finished
runs (their summary.json) and only rewrites the table and figures.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from bonded_lattice.cli_options import relax_option
from bonded_lattice.plotting import angle_histogram_png, scene_stress_png
from bonded_lattice.scene_study import SceneStudy
from bonded_lattice.scenes import Scene, bond_angles, broken_bonds, build_model, read_scene_dat


def run(scene: Scene, out: Path, reuse: bool, np_: int) -> dict:
    """The scene's summary: its stored summary.json with ``reuse``, else a new run."""
    return SceneStudy(scene, out, np_=np_).run(reuse=reuse)


def curve_error(qs: dict, dyn: dict) -> float:
    """Mean |N_dyn(e) - N_qs(e)| over the quasi-static strain steps, over N_qs at the end."""
    e = np.interp(qs["exx"], dyn["exx"], dyn["tension"] + dyn["shear"])
    n_qs = qs["tension"] + qs["shear"]
    return float(np.mean(np.abs(e - n_qs)) / max(1.0, n_qs[-1]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kind", default="polycrystal")
    relax_option(ap, "fire", "the relaxation of the numbers in docs/scenes.md")
    ap.add_argument("--n", type=int, default=50, help="particles per row (default 50)")
    ap.add_argument("--steps", type=int, default=40, help="strain steps (default 40)")
    ap.add_argument("--strain-step", type=float, default=5e-6)
    ap.add_argument("--dynamic", nargs="+", default=["5", "20", "80", "320", "80x4", "320x4"],
                    help="dynamic runs: C (loading over C P-wave crossings of the box) or CxF "
                    "(and F times the papers' damping)")
    ap.add_argument("--out", default="bench-qs-dynamic")
    ap.add_argument("--img", default="", help="folder for the figures (e.g. docs/img)")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()

    out = Path(args.out)
    base = Scene(args.kind, n_x=args.n, n_steps=args.steps, strain_step=args.strain_step,
                 bond_dumps=0, relax=args.relax)
    positions = build_model(base).lattice.positions
    runs = [("quasi-static", Scene(**{**base.__dict__, "mode": "quasistatic"}),
             out / "quasistatic")]
    for text in args.dynamic:
        c, _, f = text.partition("x")
        c, f = float(c), float(f or 1.0)
        label = f"dynamic, {c:g} crossings" + (f", damping x{f:g}" if f != 1.0 else "")
        runs.append((label, Scene(**{**base.__dict__, "mode": "dynamic", "crossings": c,
                                     "damping": f}), out / f"dynamic-{text}"))
    results = []
    for label, scene, folder in runs:
        summary = run(scene, folder, args.reuse, args.np)
        dat = read_scene_dat(folder / "scene.dat")
        final = broken_bonds(folder / "bonds.final.txt")
        results.append((label, scene, summary, dat, bond_angles(final[:, :2], positions)))

    _, qs_scene, qs, qs_dat, _ = results[0]
    print(f"{qs_scene.kind}, {qs_scene.n} particles, total strain "
          f"{qs_scene.total_strain():g} in {qs_scene.n_steps} steps, 1 rank\n")
    print("| loading | wall time (s) | time steps or minimiser iterations | broken bonds "
          "(error) | broken-count curve error | peak sigma_xx, MPa (error) | strain at peak "
          "| mean orientation, deg (error) | share at 0 deg (error) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, scene, s, dat, _ in results:
        o, oq = s["orientation"], qs["orientation"]
        if s is qs:
            errs = ("", "", "", "", "")
        else:
            errs = (f" ({(s['broken'] - qs['broken']) / qs['broken']:+.1%})",
                    f"{curve_error(qs_dat, dat):.1%}",
                    f" ({(s['peak_stress'] - qs['peak_stress']) / qs['peak_stress']:+.1%})",
                    f" ({o['mean'] - oq['mean']:+.2f})",
                    f" ({o['fraction_0'] - oq['fraction_0']:+.3f})")
        print(f"| {label} | {s['wall_time_s']:.1f} | {s['steps']} | {s['broken']}{errs[0]} | "
              f"{errs[1] or '-'} | {s['peak_stress'] / 1e6:.3f}{errs[2]} | "
              f"{s['peak_at_strain']:.3g} | {o['mean']:.2f}{errs[3]} | "
              f"{o['fraction_0']:.3f}{errs[4]} |")

    if args.img:
        img = Path(args.img)
        img.mkdir(parents=True, exist_ok=True)
        curves = [{"label": label, "strain": dat["exx"], "sxx": dat["sxx"], "syy": dat["syy"],
                   "broken": dat["tension"] + dat["shear"]}
                  for label, _, _, dat, _ in results]
        scene_stress_png(img / "scenes_qs_vs_dynamic_stress.png", curves,
                         title=f"{qs_scene.kind}, {qs_scene.n} particles: quasi-static "
                         "and dynamic loading")
        angle_histogram_png(img / "scenes_qs_vs_dynamic_angles.png",
                            [(label, a) for label, _, _, _, a in results],
                            title="orientation of the broken bonds")
        print(f"\nwrote {img}/scenes_qs_vs_dynamic_stress.png and "
              "scenes_qs_vs_dynamic_angles.png")


if __name__ == "__main__":
    main()
