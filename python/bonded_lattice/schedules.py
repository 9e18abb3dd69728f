"""The loading schedules: one vocabulary for the library, the decks and the command line.

Two schedules load a test (docs/python.md, "Loading options"):

- ``constant`` (ours, the default): the platens or end layers move at a constant speed,
  slow enough that loading to failure takes many elastic-wave crossings of the block
  (:data:`DEFAULT_LOADING`), at the time step :data:`DEFAULT_DT_FRACTION` sqrt(m/Kn);
- ``stepwise`` (the papers'): the platens or end layers jump by a step size, then the block
  relaxes for a number of time steps (:data:`PAPER_SCHEDULES`).

``paper`` is an accepted alias of ``stepwise`` (the command line's name before issue 18:
``--schedule paper``); :func:`schedule_name` turns either into the one name, which is what
the plans (``RunPlan.schedule``), the decks (``DeckSpec.schedule``) and ``summary.json``
carry.
"""

from __future__ import annotations

__all__ = ["DEFAULT_DT_FRACTION", "DEFAULT_LOADING", "PAPER_SCHEDULES", "SCHEDULES",
           "SCHEDULE_ALIASES", "schedule_name"]

SCHEDULES = ("constant", "stepwise")
SCHEDULE_ALIASES = {"paper": "stepwise"}

# The papers' stepwise schedules for 1 mm particles (Liu 2013 sections 5.2-5.3, Liu 2017
# section 5.1; docs/theory.md, "The papers' loading schedules"): displacement of
# each platen per loading step (m) and time steps of relaxation after each; time
# step as a fraction of sqrt(m/Kn) (2e-8 s in 2D and 1e-8 s in 3D for quartz).
PAPER_SCHEDULES = {
    2: {"relax_steps": 400, "dt_fraction": 0.10715,
        "step_size": {"elastic": 6.0e-10, "tension": 1.9e-10, "compression": 1.9e-9,
                      "confined": 1.9e-9}},
    3: {"relax_steps": 100, "dt_fraction": 0.04997,
        "step_size": {"elastic": 1.7e-10, "tension": 1.7e-10, "compression": 1.7e-9,
                      "confined": 1.7e-9}},
}

DEFAULT_DT_FRACTION = 0.1      # of sqrt(m/Kn), the constant schedule's time step

# the constant schedule's defaults (wave crossings during loading, damping as a multiple of
# the papers' eta), chosen from the speed-versus-error front of docs/speed_error.md: in 2D
# 50 crossings with a quarter of the papers' damping is the cheapest setting whose E, nu,
# Tu and Cu stay within 0.1% / 0.5% of the papers' schedule for every slower loading (it
# takes 76x (E, nu) to 690x (Tu) fewer time steps); 3D was not studied and keeps 100 and 1
DEFAULT_LOADING = {2: {"crossings": 50.0, "damping": 0.25},
                   3: {"crossings": 100.0, "damping": 1.0}}


def schedule_name(name: str) -> str:
    """The schedule's one name (:data:`SCHEDULES`), also for an alias (``paper``:
    ``stepwise``); a ValueError naming the unknown name and the known ones."""
    name = SCHEDULE_ALIASES.get(name, name)
    if name not in SCHEDULES:
        aliases = ", ".join(f"{a} (= {n})" for a, n in SCHEDULE_ALIASES.items())
        raise ValueError(f"schedule = {name!r} is not known: use one of "
                         f"{', '.join(SCHEDULES)} (alias: {aliases})")
    return name
