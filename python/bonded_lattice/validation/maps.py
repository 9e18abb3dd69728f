"""Where the largest 2D block breaks in compression: its broken-bond map and stress-strain
curve (Liu 2013 Fig. 7b)."""

from __future__ import annotations

from ..plotting import damage_map_png, damaged_particles, stress_strain_png
from .doc import DocContext
from .runner import Validation, curve, rock_for
from .section import Section

__all__ = ["FAILURE_MAP"]


def run_failure_map(v: Validation) -> dict:
    n = v.sizes(2)[-1]
    name = f"2d/n{n}_compression"
    run = v.run(name, rock_for(2), 2, "compression", n)
    folder = v.folder(name)
    return {"n": n, "run": run,
            "damage": damaged_particles(folder / "dump.initial", folder / "dump.final", 2),
            "curve": curve(folder)}


def doc_failure_map(data: dict, ctx: DocContext) -> list[str]:
    run, rock = data["run"], rock_for(2)
    title = f"2D quartz, {run['particles']} particles, after failure in compression"
    broken = damage_map_png(ctx.img / "compression_broken_bonds_2d.png", data["damage"], title)
    stress_strain_png(ctx.img / "compression_stress_strain_2d.png", data["curve"]["v_strain"],
                      data["curve"]["v_stress"], "compression", rock.E, rock.Cu, title)
    return ["## Where the largest 2D block breaks (Liu 2013 Fig. 7b)", "",
            f"N = {data['n']}, {run['particles']} particles, {broken} bonds broken "
            f"({run['broken_bonds']['tension']} in tension, {run['broken_bonds']['shear']} in "
            "shear).  The broken-bond map shows the conjugate shear zones (the \"X\" of Liu "
            "2013 Fig. 7b) along the lattice's 60-degree planes.", "",
            "![broken bonds after compression failure, 2D](img/compression_broken_bonds_2d.png)"
            " ![stress-strain curve](img/compression_stress_strain_2d.png)"]


FAILURE_MAP = Section("failure_map", run_failure_map, doc_failure_map)
