"""The geology the scenes exist to show (issue 20, point 4), measured at small sizes.

Runs (or, with --reuse, reads) quasi-static scenes of 4200 particles (60 per row, 70 rows)
on one rank and prints the tables of docs/scenes.md, "The geology, measured":

1. competent layer, layer-parallel extension, periodic box: three layer thicknesses at two
   stiffness contrasts; the layer-crossing fractures and their spacing over the layer
   thickness along the loading (from the bond dumps, ``scene_study.fractures_along``);
2. competent layer, layer-parallel compression, periodic box: what breaks and where;
3. polycrystal in pure shear, periodic box: the intergranular share of the breaks against the
   grain-boundary strength factor (same seed);
4. expanding grains (walls held): the radial fractures against the growth;
5. the extension runs of table 1 with one set-up choice changed, a matrix three times as
   strong as the layer (``--matrix-strength 3``), loaded twice as far (100 steps), relaxed by
   relax direct: whether the fractures stay in the layer and their spacing saturates;
6. table 5's runs of contrast 10, seed 1, at 46,000 particles (200 per row, 230 rows): the
   same box in mm, particles a third as wide, so a layer is 23 to 46 rows thick; whether the
   spacing then follows the thickness;
7. the polycrystal of table 3 (boundary strength 0.5) with the set-up choices of the
   184,800-particle run of docs/scenes.md changed one at a time (12 grains, walls, 30 steps of
   2e-5), then all three: the intergranular share at e_xx = 2e-4 and at the end.

    python bench/scene_geology.py --out scene-geology --img docs/img/scenes_layer_spacing.png
    python bench/scene_geology.py --out scene-geology --parts 5 \
        --img-strong docs/img/scenes_layer_spacing_strong_matrix.png
    python bench/scene_geology.py --out scene-geology --parts 6 \
        --img-fine docs/img/scenes_layer_spacing_fine.png
    python bench/scene_geology.py --out scene-geology --parts 7

Each run is the ``bonded-lattice scene`` command printed beside it (``--out`` its folder).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from bonded_lattice.cli import scene_from_args
from bonded_lattice.cli_options import running_options, scene_options
from bonded_lattice.fractures import intergranular_fraction
from bonded_lattice.scene_study import SceneStudy, fractures_along
from bonded_lattice.scene_analysis import break_sequence
from bonded_lattice.scenes import (Scene, bond_angles, broken_bonds, build_model, lattice_bond_ids,
                                   read_scene_dat)

BASE = "--n 60 --np 1 --relax local --boundary periodic"
THICKNESSES = (0.1, 0.15, 0.2)
#: (contrast, grain seed) of the extension runs: three draws of the disorder at contrast 10,
#: one at the scenes' default contrast 3
EXTENSION_RUNS = ((10.0, 1), (10.0, 2), (10.0, 3), (3.0, 1))
EXTENSION = "layer-extension {base} --steps 50 --strain-step 2e-6 --bond-dumps 1 " \
            "--layer-thickness {t} --contrast {c:g}{seed}"
COMPRESSION = "layer-compression {base} --steps 40 --strain-step 1e-5 --bond-dumps 2 " \
              "--contrast 10"
POLYCRYSTAL = "polycrystal {base} --grains 30 --steps 40 --strain-step 5e-6 " \
              "--boundary-strength {g:g}"
BOUNDARY_STRENGTHS = (0.3, 0.5, 0.7, 1.0)
#: table 5: the extension runs' command with a strong matrix, loaded to 2e-4
STRONG_MATRIX = 3.0
STRONG_STEPS = 100
#: table 6: table 5's contrast-10 seed-1 runs with particles a third as wide (--n 200 --d
#: 0.3e-3 keeps the box's 60 mm), bond dumps every 5 strain steps
FINE = "--n 200 --d 0.0003 --np 1 --relax direct --boundary periodic"
FINE_RUNS = ((10.0, 1),)
FINE_DUMPS = 5
#: table 7: table 3's polycrystal at boundary strength 0.5 (relax direct, which breaks the
#: same bonds as relax local there), and each set-up choice of the medium run on its own
SETUP_BASE = "polycrystal --n 60 --np 1 --relax direct --boundary-strength 0.5"
SETUP_CHOICES = (
    ("table 3 (30 grains, periodic box, 40 steps of 5e-6)",
     "--boundary periodic --grains 30 --steps 40 --strain-step 5e-6"),
    ("12 grains", "--boundary periodic --grains 12 --steps 40 --strain-step 5e-6"),
    ("walls", "--boundary walls --grains 30 --steps 40 --strain-step 5e-6"),
    ("30 steps of 2e-5 (to 6e-4)", "--boundary periodic --grains 30 --steps 30 --strain-step 2e-5"),
    ("all three (the medium run's choices)", "--boundary walls --grains 12 --steps 30 "
     "--strain-step 2e-5"))
SETUP_STRAIN = 2.0e-4
EXPANDING = "expanding --n 60 --np 1 --relax local --grains 20 --expanding 3 --steps 30 " \
            "--strain-step 5e-5 --bond-dumps 1"


def scene_of(command: str) -> Scene:
    """The Scene of a ``bonded-lattice scene`` command line (without ``--out``)."""
    p = argparse.ArgumentParser()
    scene_options(p)
    running_options(p)
    return scene_from_args(p.parse_args(command.split()))


def run(command: str, name: str, out: Path, reuse: bool) -> tuple[Scene, dict]:
    """Run (or with ``reuse`` read) one scene into out/name; its summary and folder."""
    scene = scene_of(command)
    folder = out / name
    print(f"bonded-lattice scene {command} --run --out {name}", flush=True)
    summary = SceneStudy(scene, folder, np_=1).run(reuse=reuse)
    return scene, summary | {"folder": str(folder)}


def fmt(value: float | None, digits: int = 3) -> str:
    return "-" if value is None else f"{value:.{digits}g}"


def extension(out: Path, reuse: bool) -> dict:
    """Table 1: the layer-crossing fractures along the loading."""
    series = {}
    print("\n| contrast | seed | layer thickness (mm, rows) | first crossing at e | crossings "
          "(e at which reached) | spacing / thickness at the end | in the layer: at the "
          "first crossing, at the end | broken at the end | matrix breaks reach 30 at e | crossings "
          "and spacing / thickness just before | wall time (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for c, seed in EXTENSION_RUNS:
        for t in THICKNESSES:
            tag = f" --grain-seed {seed}" if seed != 1 else ""
            scene, summary = run(EXTENSION.format(base=BASE, t=t, c=c, seed=tag),
                                 f"extension-c{c:g}-t{t:g}" + (f"-s{seed}" if seed != 1 else ""),
                                 out, reuse)
            along = fractures_along(scene, summary["folder"])
            series[(c, seed, t)] = along
            thick = along[0]["layer_thickness"]
            rows = round(thick / (np.sqrt(3) / 2 * scene.d))
            reached, last = [], 0
            for r in along:
                if r["fractures_in_layer"] > last:
                    reached.append(f"{r['fractures_in_layer']} ({r['strain']:.3g})")
                    last = r["fractures_in_layer"]
            first = next((r for r in along if r["fractures_in_layer"]), None)
            # broken bonds outside the layer: 30 of them are half a crack across the box
            cracked = [bool(r["broken"]) and r["broken"] * (1 - r["fraction_in_layer"]) >= 30
                       for r in along]
            matrix = along[cracked.index(True)]["strain"] if any(cracked) else None
            before = ([r for r, m in zip(along, cracked) if not m] or along[:1])[-1]
            end = along[-1]
            print(f"| {c:g} | {seed} | {thick * 1e3:.2f} ({rows}) | "
                  f"{fmt(first['strain'] if first else None)} | {', '.join(reached) or '0'} | "
                  f"{fmt(end['spacing_to_thickness'])} | "
                  f"{fmt(first['fraction_in_layer'] if first else None)}, "
                  f"{fmt(end['fraction_in_layer'])} | {end['broken']} | {fmt(matrix)} | "
                  f"{before['fractures_in_layer']}, {fmt(before['spacing_to_thickness'])} | "
                  f"{summary['wall_time_s']} |")
    return series


def strong_matrix(out: Path, reuse: bool, base: str = BASE.replace("local", "direct"),
                  runs: tuple = EXTENSION_RUNS, dumps: int = 1, prefix: str = "strong") -> dict:
    """Table 5: table 1's runs with ``--matrix-strength 3``, loaded to 2e-4: the crossings and
    S/T at table 1's end (e = 1e-4) and at 2e-4, their most and the strain at which the count
    last rose, and the layer's share of the breaks. Table 6: the same at another resolution
    (``base``, ``runs``, bond dumps every ``dumps`` strain steps, folders ``prefix``-...)."""
    series = {}
    print(f"\n| contrast | seed | layer thickness (mm, rows) | first crossing at e | crossings, "
          f"S/T at e = 1e-4 | crossings, S/T at e = 2e-4 | most crossings (S/T) | count last "
          f"rose at e | scanline: count, S/T at e = 1e-4 | scanline at e = 2e-4 | "
          f"in the layer at the end | broken at the end | wall time (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for c, seed in runs:
        for t in THICKNESSES:
            tag = f" --grain-seed {seed}" if seed != 1 else ""
            # relax direct: the same breaks as table 1's relax local (checked: 204 of 204 in
            # order for contrast 10, T 0.1), 30-90x faster
            command = (EXTENSION.format(base=base, t=t, c=c, seed=tag)
                       .replace("--steps 50", f"--steps {STRONG_STEPS}")
                       .replace("--bond-dumps 1", f"--bond-dumps {dumps}")
                       + f" --matrix-strength {STRONG_MATRIX:g}")
            scene, summary = run(command, f"{prefix}-c{c:g}-t{t:g}" + (f"-s{seed}" if seed != 1
                                                                     else ""), out, reuse)
            along = fractures_along(scene, summary["folder"])
            series[(c, seed, t)] = along
            thick = along[0]["layer_thickness"]
            rows = round(thick / (np.sqrt(3) / 2 * scene.d))
            first = next((r for r in along if r["fractures_in_layer"]), None)
            half = min(along, key=lambda r: abs(r["strain"] - 1e-4))
            end = along[-1]
            most = max(along, key=lambda r: r["fractures_in_layer"])
            rose = max((r for r, p in zip(along[1:], along) if r["fractures_in_layer"] >
                        p["fractures_in_layer"]), key=lambda r: r["strain"], default=None)
            print(f"| {c:g} | {seed} | {thick * 1e3:.2f} ({rows}) | "
                  f"{fmt(first['strain'] if first else None)} | {half['fractures_in_layer']}, "
                  f"{fmt(half['spacing_to_thickness'])} | {end['fractures_in_layer']}, "
                  f"{fmt(end['spacing_to_thickness'])} | {most['fractures_in_layer']} "
                  f"({fmt(most['spacing_to_thickness'])}) | "
                  f"{fmt(rose['strain'] if rose else None)} | {half['scanline_fractures']}, "
                  f"{fmt(half['scanline_spacing_to_thickness'])} | {end['scanline_fractures']}, "
                  f"{fmt(end['scanline_spacing_to_thickness'])} | {fmt(end['fraction_in_layer'])} | "
                  f"{end['broken']} | {summary['wall_time_s']} |")
    return series


def compression(out: Path, reuse: bool) -> None:
    """Table 2: what breaks and where under layer-parallel compression."""
    scene, summary = run(COMPRESSION.format(base=BASE), "compression", out, reuse)
    model = build_model(scene)
    pairs = broken_bonds(Path(summary["folder"]) / "bonds.final.txt")[:, :2].astype(np.int64)
    layer = model.grain == 1
    a, b = layer[pairs[:, 0] - 1], layer[pairs[:, 1] - 1]
    angles = bond_angles(pairs, model.lattice.positions)
    horizontal = np.minimum(angles, 180 - angles) < 15
    print("\n| broken | peak -sigma_xx (MPa) at e | in the layer | across an interface | "
          "in the matrix | x-parallel bonds (cracks normal to x) | diagonal bonds | "
          "crossings of the layer | wall time (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    n = max(len(pairs), 1)
    print(f"| {len(pairs)} | {summary['peak_stress'] / 1e6:.3g} at {summary['peak_at_strain']:.3g} | "
          f"{(a & b).sum() / n:.3f} | {(a ^ b).sum() / n:.3f} | {(~a & ~b).sum() / n:.3f} | "
          f"{horizontal.mean() if len(pairs) else 0:.3f} | "
          f"{(~horizontal).mean() if len(pairs) else 0:.3f} | "
          f"{summary['fractures_in_layer']} | {summary['wall_time_s']} |")


def polycrystal(out: Path, reuse: bool) -> None:
    """Table 3: intergranular share against the grain-boundary strength factor."""
    print("\n| boundary strength | broken | intergranular share of the breaks | share of "
          "all bonds on grain boundaries | peak sigma_xx (MPa) at e | wall time (s) |")
    print("|---|---|---|---|---|---|")
    for g in BOUNDARY_STRENGTHS:
        scene, summary = run(POLYCRYSTAL.format(base=BASE, g=g), f"polycrystal-g{g:g}", out, reuse)
        model = build_model(scene)
        every = intergranular_fraction(lattice_bond_ids(model.lattice, True), model.grain)
        print(f"| {g:g} | {summary['broken']} | {fmt(summary['intergranular_fraction'])} | "
              f"{every:.3f} | {summary['peak_stress'] / 1e6:.3g} at "
              f"{summary['peak_at_strain']:.3g} | {summary['wall_time_s']} |")


def share_at(run_dir: str | Path, grain: np.ndarray, strain: float) -> tuple[int, float | None]:
    """Broken bonds and their intergranular share at the strain step closest to ``strain``
    (e_xx): the first breaks of breaks.txt, as many as scene.dat counts broken there."""
    dat = read_scene_dat(Path(run_dir) / "scene.dat")
    k = int(np.argmin(np.abs(dat["exx"] - strain)))
    n = int(dat["tension"][k] + dat["shear"][k])
    return n, intergranular_fraction(break_sequence(run_dir, "log")[:n], grain)


def setup_choices(out: Path, reuse: bool) -> None:
    """Table 7: the polycrystal's intergranular share with one set-up choice changed at a
    time."""
    print(f"\n| set-up | broken at e_xx = {SETUP_STRAIN:g} | intergranular share there | "
          "broken at the end | intergranular share at the end | share of all bonds on grain "
          "boundaries | wall time (s) |")
    print("|---|---|---|---|---|---|---|")
    for k, (label, choice) in enumerate(SETUP_CHOICES):
        scene, summary = run(f"{SETUP_BASE} {choice}", f"setup-{k}", out, reuse)
        model = build_model(scene)
        every = intergranular_fraction(lattice_bond_ids(model.lattice, True), model.grain)
        n, share = share_at(summary["folder"], model.grain, SETUP_STRAIN)
        print(f"| {label} | {n} | {fmt(share)} | {summary['broken']} | "
              f"{fmt(summary['intergranular_fraction'])} | {every:.3f} | "
              f"{summary['wall_time_s']} |")


def expanding(out: Path, reuse: bool) -> None:
    """Table 4: radial fractures against the growth."""
    scene, summary = run(EXPANDING, "expanding", out, reuse)
    along = fractures_along(scene, summary["folder"])
    print("\n| growth | " + " | ".join(f"{r['strain']:.2g}" for r in along[1::2]) + " |")
    print("|---|" + "---|" * len(along[1::2]))
    print("| broken | " + " | ".join(str(r["broken"]) for r in along[1::2]) + " |")
    print("| radial fractures | " + " | ".join(str(r["radial_fractures"])
                                              for r in along[1::2]) + " |")
    print("| intergranular | " + " | ".join(fmt(r["intergranular_fraction"], 2)
                                           for r in along[1::2]) + " |")
    print(f"(wall time {summary['wall_time_s']} s)")


def spacing_png(path: Path, series: dict, title: str = "",
                particles: str = "4200 particles") -> None:
    """Spacing over thickness against strain, one panel per contrast, one colour per
    thickness, one line style per seed, with the band 0.8-1.2 of Bai & Pollard (2000) at
    saturation."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    contrasts = sorted({c for c, _, _ in series}, reverse=True)
    fig, axes = plt.subplots(1, len(contrasts), figsize=(5.2 * len(contrasts), 5.0), dpi=130,
                             sharex=True, sharey=True, squeeze=False)
    colours = dict(zip(THICKNESSES, ("tab:blue", "tab:orange", "tab:green")))
    styles = {1: "-", 2: "--", 3: ":"}
    for ax, c in zip(axes[0], contrasts):
        ax.axhspan(0.8, 1.2, color="0.88", label="S/T 0.8-1.2 at saturation (Bai & Pollard 2000)")
        for (cc, seed, t), along in sorted(series.items()):
            if cc != c:
                continue
            e = [r["strain"] * 1e3 for r in along if r["spacing_to_thickness"] is not None]
            s = [r["spacing_to_thickness"] for r in along if r["spacing_to_thickness"] is not None]
            if e:
                e.append(along[-1]["strain"] * 1e3)
                s.append(s[-1])
                ax.step(e, s, where="post", color=colours[t], ls=styles.get(seed, "-."),
                        label=f"T = {along[0]['layer_thickness'] * 1e3:.1f} mm ({t:g} of the "
                              f"box), seed {seed}")
        ax.set_xlabel("strain e_xx (1e-3)")
        ax.set_xlim(0.0, None)
        ax.set_yscale("log")
        ax.set_title(f"stiffness contrast {c:g}", fontsize=9)
    axes[0][0].set_ylabel("mean fracture spacing / layer thickness, L_x / n / T")
    fig.suptitle(f"competent layer, layer-parallel extension, periodic box, {particles}, "
                 f"quasi-static{title}", fontsize=9)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0.0, 0.17, 1.0, 1.0))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="scene-geology", help="folder of the runs")
    ap.add_argument("--img", default="", help="the spacing figure (default OUT/layer_spacing.png)")
    ap.add_argument("--reuse", action="store_true", help="keep finished runs")
    ap.add_argument("--img-strong", default="", help="the spacing figure of table 5 (default "
                    "OUT/layer_spacing_strong_matrix.png)")
    ap.add_argument("--img-fine", default="", help="the spacing figure of table 6 (default "
                    "OUT/layer_spacing_fine.png)")
    ap.add_argument("--parts", default="12345", help="which tables (default 12345; 6, the "
                    "finer lattice, and 7, the polycrystal's set-up choices, only when asked "
                    "for)")
    args = ap.parse_args()
    out = Path(args.out)
    if "1" in args.parts:
        series = extension(out, args.reuse)
        spacing_png(Path(args.img) if args.img else out / "layer_spacing.png", series)
        (out / "extension_along.json").write_text(json.dumps(
            {f"contrast {c:g} seed {seed} thickness {t:g}": v
             for (c, seed, t), v in series.items()}, indent=1))
    if "2" in args.parts:
        compression(out, args.reuse)
    if "3" in args.parts:
        polycrystal(out, args.reuse)
    if "4" in args.parts:
        expanding(out, args.reuse)
    if "5" in args.parts:
        series = strong_matrix(out, args.reuse)
        spacing_png(Path(args.img_strong) if args.img_strong
                    else out / "layer_spacing_strong_matrix.png", series,
                    f", matrix {STRONG_MATRIX:g} x as strong as the layer")
        (out / "strong_matrix_along.json").write_text(json.dumps(
            {f"contrast {c:g} seed {seed} thickness {t:g}": v
             for (c, seed, t), v in series.items()}, indent=1))
    if "7" in args.parts:
        setup_choices(out, args.reuse)
    if "6" in args.parts:
        series = strong_matrix(out, args.reuse, base=FINE, runs=FINE_RUNS, dumps=FINE_DUMPS,
                               prefix="fine")
        spacing_png(Path(args.img_fine) if args.img_fine else out / "layer_spacing_fine.png",
                    series, f", matrix {STRONG_MATRIX:g} x as strong as the layer",
                    "46,000 particles")
        (out / "fine_along.json").write_text(json.dumps(
            {f"contrast {c:g} seed {seed} thickness {t:g}": v
             for (c, seed, t), v in series.items()}, indent=1))


if __name__ == "__main__":
    main()
