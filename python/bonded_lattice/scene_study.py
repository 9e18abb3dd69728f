"""Run, measure and plot a Mike/Elle scene (:mod:`bonded_lattice.scenes`): the scene's
:class:`bonded_lattice.study.Study`.

:class:`SceneStudy` (what ``bonded-lattice scene --run`` does): plan: the scene's particles,
grains and stiffness factors (:func:`bonded_lattice.scenes.build_model`); write: the data
file and the deck (:func:`bonded_lattice.scenes.write_scene`); execute: ``lmp`` on ``np_``
ranks; measure: :func:`summarize` (``scene.dat`` and ``bonds.final.txt``); plot:
:func:`picture_scene`; summary: ``summary.json``.  :func:`run_scene` is the one-call form.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .fractures import intergranular_fraction, layer_fractures, radial_fractures
from .runner import RunResult
from .scene_analysis import relaxation_costs
from .scenes import (Scene, SceneModel, bond_angles, box_lattice, box_period, break_steps,
                     broken_bonds, build_model, crack_normal_stats, first_breaks_near_edges,
                     lattice_bond_ids, read_bond_dump, read_scene_dat, resume_deck,
                     scene_title, write_scene)
from .study import Study

__all__ = ["SceneStudy", "first_breaks_at_edges", "fracture_summary", "fractures_along",
           "picture_scene", "run_scene", "summarize"]


def fracture_summary(scene: Scene, model: SceneModel, pairs: np.ndarray) -> dict:
    """The geology a scene exists to show, from its broken bonds (id1, id2)
    (:mod:`bonded_lattice.fractures`, docs/scenes.md): layer scenes
    ``fractures_in_layer``, ``fraction_in_layer``, ``spacing_to_thickness`` (and the
    ``layer_thickness`` and ``layer_fracture_x`` they come from; in a periodic box across
    its seam, the spacing the box length over the count); polycrystals and
    expanding grains ``intergranular_fraction``; expanding grains ``radial_fractures``."""
    positions = model.lattice.positions
    period = box_period(model.lattice) if scene.boundary == "periodic" else None
    if scene.kind.startswith("layer"):
        return layer_fractures(pairs, positions, model.grain == 1, scene.d, period)
    out = {"intergranular_fraction": intergranular_fraction(pairs, model.grain)}
    if scene.kind == "expanding":
        out["radial_fractures"] = radial_fractures(pairs, positions,
                                                   np.isin(model.grain, model.expanding),
                                                   scene.d, period=period)
    return out


def fractures_along(scene: Scene, run_dir: str | Path,
                    model: SceneModel | None = None) -> list[dict]:
    """The fracture measures (:func:`fracture_summary`) along the loading of a finished
    quasi-static run with bond dumps (``--bond-dumps K``): one dict per ``bonds.<k>.txt``,
    in the order of k, with ``step`` k, ``strain`` (e_xx, or the growth of expanding grains,
    after strain step k: the k-th line of ``scene.dat``), ``broken`` (broken bonds) and the
    measures of that dump's broken bonds."""
    if scene.mode != "quasistatic":
        raise ValueError(f"mode = {scene.mode!r}: need 'quasistatic' (the dumps of a dynamic "
                         "run are numbered by time step, not strain step)")
    run_dir = Path(run_dir)
    model = model or build_model(scene)
    dat = read_scene_dat(run_dir / "scene.dat")
    load = dat["growth"] if scene.kind == "expanding" else dat["exx"]
    at_step = {int(k): float(e) for k, e in zip(dat["k"], load)}
    steps = sorted(int(f.name.split(".")[1]) for f in run_dir.glob("bonds.*.txt")
                   if f.name.split(".")[1].isdigit())
    if not steps:
        raise ValueError(f"{run_dir}: no bonds.<k>.txt dumps (run the scene with --bond-dumps)")
    out = []
    for k in steps:
        if k not in at_step:
            raise ValueError(f"{run_dir}: bonds.{k}.txt has no line of step {k} in scene.dat")
        pairs = broken_bonds(run_dir / f"bonds.{k}.txt")[:, :2]
        row = {"step": k, "strain": at_step[k], "broken": int(len(pairs))}
        row.update(fracture_summary(scene, model, pairs))
        out.append(row)
    return out


def summarize(scene: Scene, run_dir: str | Path, positions: np.ndarray,
              model: SceneModel | None = None) -> dict:
    """Measured results of a finished scene run (scene.dat and bonds.final.txt); the
    fracture measures (:func:`fracture_summary`) need the scene's ``model``
    (:func:`bonded_lattice.scenes.build_model`, built here if not given)."""
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
    summary = {
        "kind": scene.kind, "mode": scene.mode, "boundary": scene.boundary,
        "particles": scene.n,
        "strain": float(dat["exx"][-1]) if scene.kind != "expanding" else float(dat["growth"][-1]),
        "broken": int(len(final)), "broken_tension": int((final[:, 2] == 1).sum()),
        "broken_shear": int((final[:, 2] == 2).sum()),
        "peak_stress": float(load[k_peak]),
        "peak_at_strain": float(dat["growth" if scene.kind == "expanding" else "exx"][k_peak]),
        "steps": int(dat["step"][-1]),
        "orientation": crack_normal_stats(angles),
    }
    if scene.mode == "quasistatic":
        summary["relaxation"] = {"method": scene.relax,
                                 **relaxation_costs(run_dir / "log.lammps", scene.n)}
    if scene.bond_dumps or scene.break_order:
        summary["first_breaks"] = first_breaks_at_edges(scene, run_dir, positions)
    summary.update(fracture_summary(scene, model or build_model(scene), final[:, :2]))
    return summary


def first_breaks_at_edges(scene: Scene, run_dir: str | Path, positions: np.ndarray,
                          count: int = 100, strip: float = 3.0) -> dict:
    """:func:`bonded_lattice.scenes.first_breaks_near_edges` of a finished run with bond
    dumps: the share of the first ``count`` breaks within ``strip`` d of the walls (or of
    where they would be: the periodic box's seam) against the strip's share of all bonds."""
    periodic = scene.boundary == "periodic"
    lattice = box_lattice(scene.n_x, scene.rows, scene.d, periodic)
    period = box_period(lattice) if periodic else None
    return first_breaks_near_edges(run_dir, positions, lattice_bond_ids(lattice, periodic),
                                   scene.d, count=count, strip=strip, period=period)


class SceneStudy(Study):
    """One scene, written, run on ``np_`` ranks, measured and (with ``pictures``) drawn.

    Writes ``summary.json``, ``broken_bonds.png`` (by mode), ``broken_steps.png`` (by the
    strain step of the break, if the deck wrote bond dumps) and ``stress_strain.png``.
    """

    json_end = "\n"

    def __init__(self, scene: Scene, out: str | Path, np_: int = 1, pictures: bool = True,
                 progress: bool = False, resume: bool = False) -> None:
        super().__init__(out, np_=np_, progress=progress, pictures=pictures)
        self.scene = scene
        self.resume = resume
        self.resumed_from: int | None = None

    def _plan(self) -> None:
        self.model = build_model(self.scene)

    def _write(self) -> Path:
        if self.resume:
            info = resume_deck(self.scene, self.out, self.model)
            self.resumed_from = info["from_step"]
            return Path(info["deck"])
        return Path(write_scene(self.scene, self.out)["deck"])

    def _failure(self, result: RunResult) -> str:
        return f"the scene run failed in {self.out}: {result.error}"

    def _measure(self, result: RunResult) -> None:
        self.measured = summarize(self.scene, self.out, self.model.lattice.positions,
                                  self.model)

    def _plot(self) -> None:
        picture_scene(self.scene, self.out, self.model)

    def _summary(self) -> dict:
        assert self.result is not None
        summary = dict(self.measured)
        summary["wall_time_s"] = round(self.result.wall_time, 2)
        summary["ranks"] = self.np_
        summary["expanding"] = self.model.expanding
        if self.resumed_from is not None:
            # the wall time and the relaxation counts are the resumed part's
            summary["resumed_from_step"] = self.resumed_from
        return summary


def run_scene(scene: Scene, out: str | Path, np_: int = 1, pictures: bool = True,
              progress: bool = False, resume: bool = False) -> dict:
    """Write, run (``lmp`` on np_ ranks), measure and plot a scene (:class:`SceneStudy`);
    returns the summary, also written to ``out/summary.json``.  ``resume``: go on with the
    cut-off run in ``out`` from its last restart file instead (:func:`resume_deck`)."""
    return SceneStudy(scene, out, np_=np_, pictures=pictures, progress=progress,
                      resume=resume).run()


def picture_scene(scene: Scene, out: str | Path, model: SceneModel | None = None,
                  prefix: str = "") -> None:
    """broken_bonds.png, broken_steps.png and stress_strain.png of a finished run."""
    from .plotting import scene_bonds_png, scene_stress_png

    out = Path(out)
    model = model or build_model(scene)
    records = read_bond_dump(out / "bonds.final.txt")
    highlight = np.isin(model.grain, model.expanding) if model.expanding else None
    title = f"{scene_title(scene)}\n{scene.n} particles, {scene.mode}"
    period = box_period(model.lattice) if scene.boundary == "periodic" else None
    scene_bonds_png(out / f"{prefix}broken_bonds.png", model.lattice.positions, model.grain,
                    records, scene.d, title=title + ": broken bonds by mode",
                    highlight=highlight, period=period)
    dated = break_steps(out)
    if dated:
        per = 1 if scene.mode == "quasistatic" else scene.steps_per_strain_step()
        dated = {key: (k // per if k >= 0 else scene.n_steps) for key, k in dated.items()}
        scene_bonds_png(out / f"{prefix}broken_steps.png", model.lattice.positions,
                        model.grain, records, scene.d, broken_at=dated,
                        step_label="strain step", title=title + ": broken bonds by step",
                        highlight=highlight, period=period)
    dat = read_scene_dat(out / "scene.dat")
    x = dat["growth"] if scene.kind == "expanding" else dat["exx"]
    label = "grain growth (1e-3)" if scene.kind == "expanding" else "strain e_xx (1e-3)"
    scene_stress_png(out / f"{prefix}stress_strain.png",
                     [{"label": scene.mode, "strain": x, "sxx": dat["sxx"], "syy": dat["syy"],
                       "broken": dat["tension"] + dat["shear"]}], xlabel=label, title=title)
