"""The energy budget of the 2017 paper's example (section 5.3, Fig. 6): the 2166-element
quartzite block in tension and compression, with compute lattice/energy."""

from __future__ import annotations


from .doc import DocContext
from .papers import PAPER
from .runner import Validation, rock_for
from .section import Section

__all__ = ["ENERGY", "ENERGY_SIZE"]

ENERGY_SIZE = 12            # the 2017 paper's energy example: 2166 elements, 12 along y
HEATS = ("viscous_heat", "breaking_heat_normal", "breaking_heat_shear", "frictional_heat")


def run_energy(v: Validation) -> dict:
    runs = {}
    for test in ("tension", "compression"):
        runs[test] = v.run(f"3d/energy_n{ENERGY_SIZE}_{test}", rock_for(3), 3, test,
                           ENERGY_SIZE, energy=True)
    if v.slow:
        runs["tension, papers' schedule"] = v.run(
            f"3d/energy_paper_n{ENERGY_SIZE}_tension", rock_for(3), 3, "tension",
            ENERGY_SIZE, energy=True, schedule="stepwise")
    return {"runs": runs}


def doc_energy(data: dict, ctx: DocContext) -> list[str]:
    runs = data["runs"]
    L = ["## Energy budget (Liu 2017, section 5.3 and Fig. 6)", "",
         f"3D quartzite, {runs['tension']['particles']} elements ({ENERGY_SIZE} along y), "
         "with `compute lattice/energy` (`bonded-lattice run --energy`): elastic + kinetic "
         "energy + heat against the work of the platens.", "",
         "| test | external work (J) | max abs(balance error) / work | peak kinetic energy / "
         "work (thermo rows) | (every step) | bonds break within, 2-98% (us) | start to end "
         "(us) | width / that time (m/s) | viscous / breaking (n, s) / frictional heat (% of "
         "work) |", "|---|---|---|---|---|---|---|---|---|"]
    for test, r in runs.items():
        e = r["energy"]
        w = e["external_work"]
        heats = ", ".join(f"{100 * e[k] / w:.1f}" for k in HEATS)
        dur, full = e["breaking_duration_s"], e.get("breaking_duration_full_s")
        every = e.get("peak_kinetic_fraction_every_step")
        speed = f"{r['lateral_width_m'] / dur:.0f}" if dur and "tension" in test else ""
        L.append(f"| {test} | {w:.4g} | {e['max_balance_ratio']:.1e} | "
                 f"{100 * e['peak_kinetic_fraction']:.1f}% | "
                 f"{'' if every is None else f'{100 * every:.1f}%'} | "
                 f"{'' if dur is None else f'{1e6 * dur:.2f}'} | "
                 f"{'' if full is None else f'{1e6 * full:.2f}'} | {speed} | {heats} |")
    p = PAPER
    L += ["", f"The paper: peak kinetic energy {100 * p['3d.energy.tension.peak_kinetic'].value:.1f}%"
          f" of the total in tension; the bonds break within "
          f"{1e6 * p['3d.energy.tension.duration_s'].value:.2f} us, from the start to the end of "
          f"the breaking heat, a crack crossing the "
          f"{100 * p['3d.energy.tension.width_m'].value:.1f} cm block at about "
          f"{p['3d.energy.tension.crack_speed'].value:.0f} m/s.  Our width is the centres' "
          "span."]
    return L


ENERGY = Section("energy", run_energy, doc_energy)
