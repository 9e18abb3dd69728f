"""The LAMMPS deck and data file of a Mike/Elle scene (:func:`write_scene`).

The deck is made of the shared sections of :mod:`bonded_lattice.deck` (opening with the
grains' pair style, the wall rows of the deformation box, integrator, bond counts and
records, thermo) around the scene's own measurements (the walls' reactions, or the virial
pressure tensor of a periodic box) and loading: the quasi-static loop
(a strain or diameter step, then ``lattice/quasistatic``) or the dynamic run (affine
velocities, ``fix adapt`` for growing grains).  Every deck writes ``scene.dat``
(:data:`SCENE_COLUMNS`, read by :func:`read_scene_dat`) and the bond dumps
``bonds.final.txt`` and ``bonds.<step>.txt`` (:func:`bonded_lattice.io.read_bond_dump`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .deck import (BOND_COUNTS, BOND_RECORDS, PROPERTY_FIX, PairStyle, bond_counts,
                   bond_records, integrator, neighbours, opening, thermo, wall_rows)
from .io.table import read_table
from .lattice import write_data
from .scene_definition import Scene
from .scene_model import SceneModel, build_model

DATA_FILE = "data.scene"
SCENE_COLUMNS = ("k", "step", "exx", "eyy", "sxx", "syy", "intact", "tension", "shear",
                 "contacts", "growth")
# the thermo columns, before the energy (pe while minimising, ke while running)
THERMO_COLUMNS = f"step v_exx v_eyy v_sxx v_syy {BOND_COUNTS}"
# memory of a scene run: bytes per particle (atoms, 3 bond records, neighbour lists, the
# final bond dump's buffers) and per rank, fitted to the peak resident size of 10-step runs
# on 1 rank of 184,800 and 737,600 particles (213 and 775 MB; docs/scenes.md)
BYTES_PER_PARTICLE = 1020.0
BYTES_PER_RANK = 30.0e6
# atom_style atomic carries no diameter, mass, angular velocity or torque: the benchmark's
# peak memory per particle falls by this much (docs/performance.md, 2D and 3D alike)
ATOMIC_SAVING_PER_PARTICLE = 81.0


def _strain_scales(scene: Scene) -> tuple[str, str]:
    """change_box scale factors of one quasi-static strain step (x, y)."""
    a = 1.0 + scene.strain_step
    # pure shear: the other axis by the inverse (area kept); uniaxial: held
    other = (lambda f: repr(1.0)) if scene.deformation == "uniaxial" else (lambda f: repr(1.0 / f))
    if scene.kind == "layer-compression":
        return repr(1.0 / a), other(1.0 / a)
    return repr(a), other(a)


def _rates(scene: Scene, duration: float) -> tuple[float, float]:
    """Engineering strain rates (x, y) of the dynamic loading."""
    if scene.kind == "expanding":
        return 0.0, 0.0
    rate = scene.total_strain() / duration
    other = 0.0 if scene.deformation == "uniaxial" else 1.0
    return (-rate, other * rate) if scene.kind == "layer-compression" else (rate, -other * rate)


TITLES = {
    "layer-extension": "competent layer in a weak matrix, layer-parallel extension (pure shear)",
    "layer-compression": "competent layer in a weak matrix, layer-parallel compression "
                         "(pure shear)",
    "polycrystal": "polycrystal under pure shear, x extended",
    "expanding": "expanding grains in a polycrystal, walls held",
}


def scene_title(scene: Scene) -> str:
    """The scene's title, with its deformation."""
    title = TITLES[scene.kind]
    if scene.deformation == "uniaxial":
        title = title.replace("pure shear", "uniaxial strain")
    if scene.boundary == "periodic":
        title = title.replace("walls held", "box held") + ", periodic box"
    return title


RESTART_FILE = "restart.scene"
# what a resumed deck needs besides the restart file: the box's initial lengths (the strains'
# reference) and the last strain step the restart file holds
RESTART_VARS = "restart.vars"
RESTART_STEP = "restart.step"


def deck_text(scene: Scene, model: SceneModel | None = None,
              data_file: str = DATA_FILE, resume: bool = False) -> str:
    """The LAMMPS deck of a scene (reads ``data_file``, written by :func:`write_scene`);
    ``resume``: the deck that goes on from the last restart file of a quasi-static run with
    ``restart_every`` (:func:`resume_deck`)."""
    if resume and not (scene.mode == "quasistatic" and scene.restart_every):
        raise ValueError("resume: only a quasi-static scene with restart_every > 0 writes the "
                         "restart files a run can go on from")
    if model is None and scene.kind == "expanding":
        model = build_model(scene)
    b, d = scene.bond, scene.d
    fb = b.Kn * b.Xb
    qs = scene.mode == "quasistatic"
    # fix adapt changes radii during a run: only with a dynamic radius (sphere 1)
    style = "sphere 1" if scene.kind == "expanding" and not qs else scene.atom_style
    pair = PairStyle(b, d, scene.atom_style, scene.pair_options())
    boundary = "p p p" if scene.boundary == "periodic" else "f f p"
    head = f"""# Mike/Elle scene: {scene_title(scene)}
# {scene.n} particles ({scene.n_x} per row, {scene.rows} rows), {scene.mode} loading.
# Written by bonded_lattice.scenes; run: lmp -in <this file> (or mpirun -np 2 lmp -in ...)
# Central springs (the seed's): Kn {b.Kn:.6g} N/m, Ks 0, Xb {b.Xb:.6g} m, mu_p 0;
# a broken spring only repels.  Breaking force Kn Xb = {fb:.6g} N.

{_resumed_opening(pair) if resume else opening(2, boundary, style, data_file, pair)}\
variable        d equal {d!r}

{_box_measures(scene, resume)}{bond_counts()}{bond_records()}"""
    grow = ""
    if scene.kind == "expanding":
        ids = " ".join(str(g) for g in model.expanding)
        cond = "||".join(f"(i_grain=={g})" for g in model.expanding)
        grow = f"""
# ---- expanding grains {ids}: their particles' diameters grow; the rest length of a
# bond is r_i + r_j, so the grains' own bonds and their boundary bonds lengthen ----
variable        isgrow atom {cond}
group           grow variable isgrow
variable        d0 equal {d!r}
"""
    head += grow
    if qs:
        return head + _quasistatic(scene, fb, resume)
    return head + _dynamic(scene)


def _resumed_opening(pair: PairStyle) -> str:
    """The opening of a resumed deck: the restart file (box, atoms, groups, pair style and
    coefficients, bond records), the grain data's fix declared again (its per-atom values
    come back from the restart file at the first run) and the neighbour settings."""
    fix = ""
    if pair.grains is not None:
        fix = (f"fix             {PROPERTY_FIX} all property/atom {pair.grains.properties()} "
               "ghost yes\n")
    return (f"# the state after the last strain step the restart file holds\n"
            f"read_restart    {RESTART_FILE}\n{fix}{neighbours(pair.d)}")


WALL_MEASURES = """# strains: the walls' distance against the initial one; stresses (tension
# positive): the wall reactions over the length they hold.  sigma_yy: the top
# row's 2 n_x - 1 bonds to the row below carry (n_x - 1/2) d of the lattice;
# sigma_xx: n_y rows of sqrt3/2 d (the 2 n_y - 1 bonds across a column make
# an edge error of order 1/(3 n_y), docs/scenes.md)
{lengths}variable        exx equal (xcm(right,x)-xcm(left,x))/v_Lx0-1
variable        eyy equal (xcm(top,y)-xcm(bottom,y))/v_Ly0-1
variable        sxx equal 0.5*(f_wleft[1]-f_wright[1])/(xcm(top,y)-xcm(bottom,y)+sqrt(3)/2*v_d)
variable        syy equal 0.5*(f_wbottom[2]-f_wtop[2])/(xcm(right,x)-xcm(left,x)+0.5*v_d)
"""

PERIODIC_MEASURES = """# ---- a box periodic in x and y: no walls; the lattice fills the periodic cell ----
# strains: the box lengths against the initial ones; stresses (tension positive):
# minus the virial pressure tensor, sum of r f over the bonds over the box's area
# lx ly (LAMMPS' 2D volume): the 2D stress per unit thickness, in the wall
# reactions' units (N/m per m of thickness)
compute         press all pressure NULL virial
{lengths}variable        exx equal lx/v_Lx0-1
variable        eyy equal ly/v_Ly0-1
variable        sxx equal -c_press[1]
variable        syy equal -c_press[2]
"""


def _box_measures(scene: Scene, resume: bool = False) -> str:
    """The boundary's groups and fixes and the strain and stress variables exx, eyy, sxx,
    syy: the wall rows and their reactions, or the periodic box and its pressure tensor.
    ``resume``: the groups are the restart file's, the initial lengths its run's."""
    if resume:
        lengths = f"include         {RESTART_VARS}\n"
    else:
        measure = (("lx", "ly") if scene.boundary == "periodic"
                   else ("xcm(right,x)-xcm(left,x)", "xcm(top,y)-xcm(bottom,y)"))
        if scene.restart_every:
            # the number's text is kept for a resumed run (restart.vars): LAMMPS' parser
            # of a formula is not exact to the last bit, so the same text, not the value
            # printed again, gives the same double
            lengths = "".join(f"variable        {v}text string $({m})\n"
                              f"variable        {v} equal ${{{v}text}}\n"
                              for v, m in zip(("Lx0", "Ly0"), measure))
        else:
            lengths = "".join(f"variable        {v} equal $({m})\n"
                              for v, m in zip(("Lx0", "Ly0"), measure))
    if scene.boundary == "periodic":
        return PERIODIC_MEASURES.format(lengths=lengths)
    walls = wall_rows()
    if resume:
        walls = "".join(line + "\n" for line in walls.splitlines()
                        if line.startswith("fix "))
    return f"{walls}\n{WALL_MEASURES.format(lengths=lengths)}"


def _line_vars() -> str:
    """The values of one scene.dat line (:data:`SCENE_COLUMNS`), for ``print``."""
    counts = " ".join(f"$({c})" for c in BOND_COUNTS.split())
    return f"${{k}} $(step) ${{exx}} ${{eyy}} ${{sxx}} ${{syy}} {counts} ${{growth}}"


def _quasistatic(scene: Scene, fb: float, resume: bool = False) -> str:
    if scene.kind == "expanding":
        step = ("variable        growth equal (1+{e})^v_k-1\n"
                "set             group grow diameter $(v_d0*(1+v_growth))").format(
                    e=repr(scene.strain_step))
        what = f"diameters of the growing grains x (1 + {scene.strain_step:g}) per step"
    else:
        sx, sy = _strain_scales(scene)
        step = ("variable        growth equal 0\n"
                f"change_box      all x scale {sx} y scale {sy} remap")
        what = f"box x scaled by {sx}, y by {sy} per step (affine pre-displacement)"
    dumps = ""
    if scene.bond_dumps:
        # the bond records every few strain steps, to date the breaks (break_steps)
        dumps = (f"if \"$(v_k%{scene.bond_dumps}) == 0\" then "
                 f"\"write_dump all local bonds.${{k}}.txt {BOND_RECORDS}\"\n")
    if scene.relax == "local":
        how = "over-relaxation where the forces exceed the tolerance, relax local"
        minimizer = ""
    elif scene.relax == "direct":
        how = "Newton steps with a sparse Cholesky factor, relax direct"
        minimizer = ""
    else:
        how, minimizer = "FIRE", "min_style       fire\n"
    saves, start = "", f"""variable        growth equal 0
variable        k equal 0
print           "# {' '.join(SCENE_COLUMNS)}" file scene.dat screen no
print           "{_line_vars()}" append scene.dat screen no
variable        k delete
"""
    first = "1"
    if scene.restart_every:
        # the restart file is replaced only once the new one is complete, and the step it
        # holds is written after it
        n = scene.restart_every
        saves = (f"if \"$(v_k%{n}) == 0\" then \"write_restart {RESTART_FILE}.new\" "
                 f"\"shell mv {RESTART_FILE}.new {RESTART_FILE}\" "
                 f"\"print 'variable kdone equal ${{k}}' file {RESTART_STEP} screen no\"\n")
        lengths = (f"print           \"variable Lx0 equal ${{Lx0text}}\" file {RESTART_VARS} "
                   "screen no\n"
                   f"print           \"variable Ly0 equal ${{Ly0text}}\" append {RESTART_VARS} "
                   "screen no\n")
        start = lengths + start
    if resume:
        start = f"include         {RESTART_STEP}\n"
        first = "$(v_kdone+1)"
    return f"""
# ---- quasi-static loading (the seed's loop): {scene.n_steps} steps ----
# {what};
# then relax ({how}) until no force component exceeds {scene.relax_tolerance:g} x Kn Xb,
# break the most over-stressed bond, relax again, ... until no bond exceeds its threshold;
# breaks.txt: every break in order (time step, IDs, mode, ratio to the threshold)
{minimizer}{thermo(THERMO_COLUMNS + " pe", 1000000)}run             0 post no
{start}# the number of strain steps; shorten a trial with -var nsteps 2
variable        nsteps index {scene.n_steps}
variable        k loop {first} ${{nsteps}}
label           strain
{step}
{_relax(scene, fb)}run             0 post no
print           "{_line_vars()}" append scene.dat screen no
{dumps}{saves}next            k
jump            SELF strain

write_dump      all local bonds.final.txt {BOND_RECORDS}
"""


def _relax(scene: Scene, fb: float) -> str:
    """The relaxation and breaking of one quasi-static step (``lattice/quasistatic ... break
    one``); with ``break_order``, first a loop of ``maxbreak 1`` calls (the same sequence:
    relax, break the worst bond, relax, ...) that writes the bond records after each of the
    first ``break_order`` breaks (``break.<n>.txt``).  No run between the calls: outside the
    command the pair style would break every bond past its threshold at once."""
    how = f"relax {scene.relax} quiet yes " if scene.relax in ("local", "direct") else ""
    if scene.threads > 1:
        how += f"threads {scene.threads} "
    relax = (f"lattice/quasistatic ftol {scene.relax_tolerance * fb:.6g} {how}break one "
             f"maxsteps {scene.maxsteps} breaks breaks.txt")
    if not scene.break_order:
        return relax + "\n"
    n = scene.break_order
    return f"""# the first {n} breaks one call each, the bond records after each (break.<n>.txt)
label           brk
variable        nb0 equal $(c_bonds[2]+c_bonds[3])
{relax} maxbreak 1
variable        nb1 equal $(c_bonds[2]+c_bonds[3])
if "${{nb1}} > ${{nb0}} && ${{nb1}} <= {n}" then "write_dump all local break.${{nb1}}.txt {BOND_RECORDS}"
if "${{nb1}} > ${{nb0}} && ${{nb1}} < {n}" then "jump SELF brk"
{relax}
"""


DAMPING_NOTE = ("# damping of the interior only: the walls keep their speed, and their reaction\n"
                "# is the bonds' force alone\n")


def _dynamic(scene: Scene) -> str:
    steps = scene.dynamic_steps()
    dt = scene.dt()
    per_step = scene.steps_per_strain_step()
    # the rates that reach the total strain at the last step exactly
    rx, ry = _rates(scene, steps * dt)
    out_every = per_step * scene.output_every
    dumps = ""
    if scene.bond_dumps:
        dumps = (f"dump            bdump all local {per_step * scene.bond_dumps} "
                 f"bonds.*.txt {BOND_RECORDS}\n")
    if scene.kind == "expanding":
        rate = scene.total_strain() / (steps * dt)
        growth = (f"variable        growth equal {rate!r}*time\n"
                  f"variable        dgrow equal v_d0*(1+v_growth)\n"
                  "# mass no: only the size grows (the quasi-static loop changes no mass either)\n"
                  "fix             expand grow adapt 1 atom diameter v_dgrow mass no\n")
        what = f"growing grains: diameters + {rate:.6g} /s relative"
    else:
        growth = "variable        growth equal 0\n"
        what = f"walls at engineering strain rates {rx:.6g} /s (x), {ry:.6g} /s (y)"
    return f"""
# ---- dynamic loading: {what} ----
# total strain {scene.total_strain():g} over {scene.crossings:g} P-wave crossings of the box,
# {steps} time steps of {dt:.6g} s ({scene.dt_fraction:g} of the critical time step)
variable        xc equal $(0.5*(xcm(left,x)+xcm(right,x)))
variable        yc equal $(0.5*(xcm(bottom,y)+xcm(top,y)))
# start from the affine velocity field, so no wave runs in from the walls; the
# walls' normal velocity then stays as set (their normal force is zeroed)
variable        vx atom {rx!r}*(x-v_xc)
variable        vy atom {ry!r}*(y-v_yc)
velocity        all set v_vx v_vy NULL units box
velocity        left set $({rx!r}*(xcm(left,x)-v_xc)) NULL NULL units box
velocity        right set $({rx!r}*(xcm(right,x)-v_xc)) NULL NULL units box
velocity        bottom set NULL $({ry!r}*(xcm(bottom,y)-v_yc)) NULL units box
velocity        top set NULL $({ry!r}*(xcm(top,y)-v_yc)) NULL units box
{growth}{integrator("all", scene.eta(), "inner", DAMPING_NOTE)}timestep        {dt!r}
variable        k equal floor(step/{per_step})
{thermo(THERMO_COLUMNS + " ke", out_every)}print           "# {' '.join(SCENE_COLUMNS)}" file scene.dat screen no
fix             out all print {out_every} "{_line_vars()}" append scene.dat screen no
{dumps}# the number of time steps; shorten a trial with -var nsteps 10
variable        nsteps index {steps}
run             ${{nsteps}}
write_dump      all local bonds.final.txt {BOND_RECORDS}
"""


def write_scene(scene: Scene, out: str | Path, deck_name: str | None = None) -> dict:
    """Write the data file and the deck of a scene into ``out``; return a summary dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    model = build_model(scene)
    write_data(model.lattice, out / DATA_FILE, scene.mass, grain=model.grain,
               stiffness=model.stiffness, atom_style=scene.atom_style, strength=model.strength)
    name = deck_name or f"in.{scene.kind}.{scene.mode}"
    (out / name).write_text(deck_text(scene, model))
    return {"deck": str(out / name), "data": str(out / DATA_FILE), "particles": scene.n,
            "data_bytes": (out / DATA_FILE).stat().st_size, "expanding": model.expanding,
            "memory_bytes": expected_memory(scene.n, atom_style=scene.atom_style)}


def resume_deck(scene: Scene, out: str | Path, model: SceneModel | None = None) -> dict:
    """Prepare ``out``, the folder of a quasi-static run with ``restart_every`` that was cut
    off, to go on from its last restart file: ``scene.dat`` and ``breaks.txt`` lose what the
    run wrote after the strain step the restart file holds (``break.<n>.txt`` of later breaks
    go), and the resumed deck ``in.<kind>.quasistatic.resume`` is written.  ``scene`` must be
    the first run's.  Returns the deck's path and that strain step ("from_step").  Raises
    ValueError if a file is missing, the files disagree, or the run had finished."""
    out = Path(out)
    deck = deck_text(scene, model, resume=True)    # checks the scene
    missing = [name for name in (RESTART_FILE, RESTART_STEP, RESTART_VARS, "scene.dat")
               if not (out / name).exists()]
    if missing:
        raise ValueError(f"{out}: {', '.join(missing)} missing; a run goes on only from the "
                         "restart files it wrote (--restart N, Scene.restart_every)")
    words = (out / RESTART_STEP).read_text().split()
    if len(words) != 4 or words[:3] != ["variable", "kdone", "equal"] or not words[3].isdigit():
        raise ValueError(f"{out / RESTART_STEP}: {' '.join(words)!r} is not 'variable kdone "
                         "equal <step>'")
    done = int(words[3])
    if done >= scene.n_steps:
        raise ValueError(f"{out}: the restart file holds strain step {done} of "
                         f"{scene.n_steps}: the run had finished, nothing to go on with")
    dat = read_scene_dat(out / "scene.dat")
    at = np.flatnonzero(dat["k"] == done)
    if len(at) == 0:
        raise ValueError(f"{out / 'scene.dat'}: no line of strain step {done}, which "
                         f"{RESTART_STEP} says the restart file holds")
    last = int(at[-1])
    broken = int(dat["tension"][last] + dat["shear"][last])
    # the text up to that line (the header and its data lines, in the reader's order)
    lines = (out / "scene.dat").read_text().splitlines()
    data = [i for i, line in enumerate(lines) if line.strip() and not line.startswith("#")]
    (out / "scene.dat").write_text("\n".join(lines[:data[last] + 1]) + "\n")
    log = out / "breaks.txt"
    if log.exists():
        breaks = [line for line in log.read_text().splitlines() if line.strip()]
        if len(breaks) < broken:
            raise ValueError(f"{log}: {len(breaks)} breaks, fewer than the {broken} broken "
                             f"bonds of strain step {done} in scene.dat")
        log.write_text("".join(line + "\n" for line in breaks[:broken]))
    for dump in out.glob("break.*.txt"):
        tag = dump.name.split(".")[1]
        if tag.isdigit() and int(tag) > broken:
            dump.unlink()
    path = out / f"in.{scene.kind}.{scene.mode}.resume"
    path.write_text(deck)
    return {"deck": str(path), "from_step": done}


def expected_memory(n: int, ranks: int = 1, atom_style: str = "sphere") -> float:
    """Expected resident memory (bytes) of a scene run with n particles, all ranks."""
    per_particle = BYTES_PER_PARTICLE - (ATOMIC_SAVING_PER_PARTICLE if atom_style == "atomic"
                                         else 0.0)
    return per_particle * n + ranks * BYTES_PER_RANK


def read_scene_dat(path: str | Path) -> dict[str, np.ndarray]:
    """The columns of a scene deck's ``scene.dat`` (:data:`SCENE_COLUMNS`), by name."""
    return read_table(path, SCENE_COLUMNS)
