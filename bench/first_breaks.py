"""Where the first breaks of quasi-static scenes occur: side by side, and their share at the walls.

Runs (or, with --reuse, reads) quasi-static scenes that differ in one setting, with a bond
dump every strain step, and prints for each the first K breaks (completed to the end of
their strain step: the order within a step is not recorded), their share within BAND
diameters of the box outline, and the uniform expectations: the share of all bonds and of
the area in that band.  Draws them side by side (first_breaks.first_breaks_png).

    python bench/first_breaks.py --out first-breaks --img first_breaks.png   # ~15 s, 1 rank

Default: the polycrystal, 40 particles per row (1840), 40 steps of 5e-6, under pure shear
(all four walls move) and uniaxial extension (the walls across y held).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from bonded_lattice.cli_options import relax_option
from bonded_lattice.first_breaks import break_sites, first_breaks_png
from bonded_lattice.scene_study import SceneStudy
from bonded_lattice.scenes import Scene, build_model


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kind", default="polycrystal")
    relax_option(ap, "fire", "the relaxation of the numbers in docs/scenes.md")
    ap.add_argument("--n", type=int, default=40, help="particles per row (default 40)")
    ap.add_argument("--steps", type=int, default=40)
    ap.add_argument("--strain-step", type=float, default=5e-6)
    ap.add_argument("--deformations", nargs="+", default=["pure-shear", "uniaxial"])
    ap.add_argument("--k", type=int, default=100, help="first breaks (default 100)")
    ap.add_argument("--band", type=float, default=3.0, help="diameters from the walls (default 3)")
    ap.add_argument("--out", default="first-breaks")
    ap.add_argument("--img", default="", help="the figure's file (default: OUT/first_breaks.png)")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--reuse", action="store_true", help="keep finished runs")
    args = ap.parse_args()

    out = Path(args.out)
    sites = []
    for deformation in args.deformations:
        scene = Scene(args.kind, n_x=args.n, n_steps=args.steps, strain_step=args.strain_step,
                      bond_dumps=1, deformation=deformation, relax=args.relax)
        folder = out / f"{args.kind}-{deformation}"
        SceneStudy(scene, folder, np_=args.np).run(reuse=args.reuse)
        sites.append(break_sites(folder, build_model(scene).lattice.positions, scene.d,
                                 k=args.k, band=args.band, label=deformation))
    print("| run | first breaks | steps | within band | all bonds within band | area within "
          "band | ratio to the bonds' share |")
    print("|---|---|---|---|---|---|---|")
    for s in sites:
        print(f"| {s.label} | {len(s.points)} | {int(s.steps.min())}-{int(s.steps.max())} | "
              f"{100 * s.share:.1f} % | {100 * s.bond_share:.1f} % | {100 * s.area_share:.1f} % "
              f"| {s.enrichment:.2f} |")
    (out / "first_breaks.json").write_text(json.dumps([s.as_dict() for s in sites], indent=1))
    first_breaks_png(args.img or out / "first_breaks.png", sites,
                     title=f"{args.kind}, {args.n} particles per row, quasi-static: the first "
                     f"{args.k} breaks")


if __name__ == "__main__":
    main()
