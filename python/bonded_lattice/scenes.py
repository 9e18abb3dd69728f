"""The Mike/Elle scenes: a 2D central-spring lattice in a deformation box.

The seed's model (issue 7): a triangular lattice of particles joined by
central springs (``Ks = 0``, ``mu_p = 0``) that break in tension and then
only repel, inside a "deformation box": a row of wall particles on each of
the four sides, held perpendicular to its wall and free to slide along it
(frictionless walls).  Scenes (:data:`KINDS`):

- ``layer-extension``, ``layer-compression``: a competent (stiffer) layer in
  a weak matrix (:func:`bonded_lattice.grains.competent_layer`), layer
  parallel to x, pure shear along the layer: x scaled by (1 + e), y by
  1/(1 + e) (extension) or the reverse (compression);
- ``polycrystal``: Voronoi grains with Gaussian stiffness factors and
  uniform bond strengths, weak grain boundaries, pure shear (x extended);
- ``expanding``: Voronoi grains of which a few near the centre grow (their
  particles' diameters, hence the rest lengths r_i + r_j of their bonds,
  increase step by step), the walls held.

Two loadings (:data:`MODES`):

- ``quasistatic``: the seed's loop in LAMMPS: a strain step by ``change_box
  ... remap`` (the affine pre-displacement) or a diameter step, then
  ``lattice/quasistatic ftol F break one`` (FIRE), repeated;
- ``dynamic``: the walls move at a constant strain rate (their normal
  velocity held: ``fix setforce`` zeroes the normal force), the lattice
  integrated by ``fix lattice/nve`` and damped by ``fix lattice/viscous``;
  the pair style breaks bonds as it goes.  The expanding grains grow at a
  constant rate (``fix adapt``).

The wall reaction is the force ``fix setforce`` removes (its global vector),
so the wall stress is the same quantity in both modes.  Every deck writes
``scene.dat``: one line per strain step (quasi-static) or per output interval
(dynamic) with the cumulative step count (time steps, or minimiser
iterations), the wall strains, the wall stresses and the bond counts; and
``bonds.final.txt``, a ``dump local`` of ``compute lattice/bond/local id1
id2 state x y z``.  With ``bond_dumps`` > 0 it also writes that dump every
few strain steps (``bonds.<step>.txt``), from which :func:`break_steps`
dates each broken bond.

The scenes are made in layers, one module each: the definition
(:mod:`bonded_lattice.scene_definition`: :class:`Scene`, :func:`central_spring_bond`), the
particles and grains (:mod:`bonded_lattice.scene_model`: :func:`build_model`), the deck and
data file (:mod:`bonded_lattice.scene_deck`: :func:`write_scene`, from the sections of
:mod:`bonded_lattice.deck`) and what a finished run shows
(:mod:`bonded_lattice.scene_analysis`); this module runs, measures and plots a scene and
keeps every name importable from here.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .io.dump import read_bond_dump
from .scene_analysis import bond_angles, break_steps, broken_bonds, crack_normal_stats
from .scene_deck import (ATOMIC_SAVING_PER_PARTICLE, BYTES_PER_PARTICLE, BYTES_PER_RANK,
                         DATA_FILE, SCENE_COLUMNS, TITLES, deck_text, expected_memory,
                         read_scene_dat, scene_title, write_scene)
from .scene_definition import (DEFORMATIONS, KINDS, MODES, ROW, SQRT3, Scene,
                               central_spring_bond, plane_moduli)
from .scene_model import (SceneModel, box_lattice, build_model, expanding_grains, grain_model,
                          wall_masks)

__all__ = ["ATOMIC_SAVING_PER_PARTICLE", "BYTES_PER_PARTICLE", "BYTES_PER_RANK", "DATA_FILE",
           "DEFORMATIONS", "KINDS", "MODES", "ROW", "SCENE_COLUMNS", "SQRT3", "TITLES",
           "Scene", "SceneModel", "bond_angles", "box_lattice", "break_steps", "broken_bonds",
           "build_model", "central_spring_bond", "crack_normal_stats", "deck_text",
           "expanding_grains", "expected_memory", "grain_model", "picture_scene",
           "plane_moduli", "read_bond_dump", "read_scene_dat", "run_scene", "scene_title",
           "summarize", "wall_masks", "write_scene"]


# ---------------------------------------------------------------- run, measure, plot

def summarize(scene: Scene, run_dir: str | Path, positions: np.ndarray) -> dict:
    """Measured results of a finished scene run (scene.dat and bonds.final.txt)."""
    run_dir = Path(run_dir)
    dat = read_scene_dat(run_dir / "scene.dat")
    final = broken_bonds(run_dir / "bonds.final.txt")
    angles = bond_angles(final[:, :2], positions)
    # the peak of the stress along the loading: sigma_xx in tension (extension), in
    # compression (layer compression), the mean wall stress for growing grains
    if scene.kind == "expanding":
        load = -0.5 * (dat["sxx"] + dat["syy"])
    elif scene.kind == "layer-compression":
        load = -dat["sxx"]
    else:
        load = dat["sxx"]
    k_peak = int(np.argmax(load))
    return {
        "kind": scene.kind, "mode": scene.mode, "particles": scene.n,
        "strain": float(dat["exx"][-1]) if scene.kind != "expanding" else float(dat["growth"][-1]),
        "broken": int(len(final)), "broken_tension": int((final[:, 2] == 1).sum()),
        "broken_shear": int((final[:, 2] == 2).sum()),
        "peak_stress": float(load[k_peak]),
        "peak_at_strain": float(dat["growth" if scene.kind == "expanding" else "exx"][k_peak]),
        "steps": int(dat["step"][-1]),
        "orientation": crack_normal_stats(angles),
    }


def run_scene(scene: Scene, out: str | Path, np_: int = 1, pictures: bool = True,
              progress: bool = False) -> dict:
    """Write, run (``lmp`` on np_ ranks), measure and plot a scene; returns the summary.

    Writes ``summary.json``, ``broken_bonds.png`` (by mode), ``broken_steps.png``
    (by the strain step of the break, if the deck wrote bond dumps) and
    ``stress_strain.png`` into ``out``.
    """
    import json

    from .runner import run_deck

    info = write_scene(scene, out)
    result = run_deck(info["deck"], out, np_=np_, progress=progress)
    if result.returncode != 0:
        raise RuntimeError(f"the scene run failed in {out}: {result.error}")
    model = build_model(scene)
    summary = summarize(scene, out, model.lattice.positions)
    summary["wall_time_s"] = round(result.wall_time, 2)
    summary["ranks"] = np_
    summary["expanding"] = model.expanding
    if pictures:
        picture_scene(scene, out, model)
    Path(out, "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return summary


def picture_scene(scene: Scene, out: str | Path, model: SceneModel | None = None,
                  prefix: str = "") -> None:
    """broken_bonds.png, broken_steps.png and stress_strain.png of a finished run."""
    from .plotting import scene_bonds_png, scene_stress_png

    out = Path(out)
    model = model or build_model(scene)
    records = read_bond_dump(out / "bonds.final.txt")
    highlight = np.isin(model.grain, model.expanding) if model.expanding else None
    title = f"{scene_title(scene)}\n{scene.n} particles, {scene.mode}"
    scene_bonds_png(out / f"{prefix}broken_bonds.png", model.lattice.positions, model.grain,
                    records, scene.d, title=title + ": broken bonds by mode",
                    highlight=highlight)
    dated = break_steps(out)
    if dated:
        per = 1 if scene.mode == "quasistatic" else scene.steps_per_strain_step()
        dated = {key: (k // per if k >= 0 else scene.n_steps) for key, k in dated.items()}
        scene_bonds_png(out / f"{prefix}broken_steps.png", model.lattice.positions,
                        model.grain, records, scene.d, broken_at=dated,
                        step_label="strain step", title=title + ": broken bonds by step",
                        highlight=highlight)
    dat = read_scene_dat(out / "scene.dat")
    x = dat["growth"] if scene.kind == "expanding" else dat["exx"]
    label = "grain growth (1e-3)" if scene.kind == "expanding" else "strain e_xx (1e-3)"
    scene_stress_png(out / f"{prefix}stress_strain.png",
                     [{"label": scene.mode, "strain": x, "sxx": dat["sxx"], "syy": dat["syy"],
                       "broken": dat["tension"] + dat["shear"]}], xlabel=label, title=title)
