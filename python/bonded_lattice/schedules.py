"""The loading schedules: one vocabulary for the library, the decks and the command line.

Two schedules load a test (docs/python.md, "Loading options"):

- ``constant`` (ours, the default): the platens or end layers move at a constant speed,
  slow enough that loading to failure takes many elastic-wave crossings of the block
  (:func:`default_loading`: :data:`DEFAULT_LOADING`, per test kind
  :data:`DEFAULT_CROSSINGS_BY_TEST`), at the time step :data:`DEFAULT_DT_FRACTION` sqrt(m/Kn);
- ``stepwise`` (the papers'): the platens or end layers jump by a step size, then the block
  relaxes for a number of time steps (:data:`PAPER_SCHEDULES`).

``paper`` is an accepted alias of ``stepwise`` (the command line's name before issue 18:
``--schedule paper``); :func:`schedule_name` turns either into the one name, which is what
the plans (``RunPlan.schedule``), the decks (``DeckSpec.schedule``) and ``summary.json``
carry.
"""

from __future__ import annotations

__all__ = ["DEFAULT_CROSSINGS_BY_TEST", "DEFAULT_DT_FRACTION", "DEFAULT_LOADING",
           "PAPER_SCHEDULES", "SCHEDULES", "SCHEDULE_ALIASES", "default_loading",
           "schedule_name"]

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
# the papers' eta), chosen by the rule of docs/speed_error.md: the cheapest setting of its
# grid whose E, nu, Tu and Cu stay within 0.1% / 0.1% / 0.5% / 0.5% of the papers' stepwise
# schedule at that setting and every slower one, checked on a block of another size.
# - 2D (N = 30 / 15 quartz): 50 crossings with a quarter of the papers' damping (76x (E, nu)
#   to 690x (Tu) fewer time steps than the papers' schedule).
# - 3D (n_y = 10 / 6 quartzite, checked on n_y = 10): the papers' damping, because in 3D the
#   damping takes part in how the block fails (at 3000 crossings a quarter of it reads Cu 4.1%
#   low; half of it matches on n_y = 6 but reads 4.0% low on n_y = 10); compression needs 1000
#   crossings (Cu +0.49% against the papers' schedule, +0.48% on n_y = 10; at 100, the former
#   3D default, +5.6%; at 3000, +0.04%): the 3D value here, for every test without its own
#   below.  That is 8.8x the former default's time steps, still 12x fewer than the papers'.
DEFAULT_LOADING = {2: {"crossings": 50.0, "damping": 0.25},
                   3: {"crossings": 1000.0, "damping": 1.0}}

# crossings per test kind where the same rule, on that test's quantities alone and at the
# dimension's default damping, accepts faster loading (docs/speed_error.md, part 4): the 3D
# elastic test's E and nu move by less than 0.01% over the whole grid, 30 to 3000 crossings
# (30 is its fastest setting), and the 3D tension test holds Tu within 0.25% from 100
# crossings on (+0.22% on n_y = 10): 33x and 10x fewer time steps than 1000 crossings
DEFAULT_CROSSINGS_BY_TEST = {2: {}, 3: {"elastic": 30.0, "tension": 100.0}}


def default_loading(dim: int, test: str) -> dict[str, float]:
    """The constant schedule's default ``crossings`` and ``damping`` of ``test`` in ``dim`` D:
    :data:`DEFAULT_LOADING` with the crossings of :data:`DEFAULT_CROSSINGS_BY_TEST`; a
    ValueError for another dimension."""
    if dim not in DEFAULT_LOADING:
        raise ValueError(f"dim = {dim} is out of range: need 2 or 3")
    base = DEFAULT_LOADING[dim]
    return {"crossings": DEFAULT_CROSSINGS_BY_TEST[dim].get(test, base["crossings"]),
            "damping": base["damping"]}


def schedule_name(name: str) -> str:
    """The schedule's one name (:data:`SCHEDULES`), also for an alias (``paper``:
    ``stepwise``); a ValueError naming the unknown name and the known ones."""
    name = SCHEDULE_ALIASES.get(name, name)
    if name not in SCHEDULES:
        aliases = ", ".join(f"{a} (= {n})" for a, n in SCHEDULE_ALIASES.items())
        raise ValueError(f"schedule = {name!r} is not known: use one of "
                         f"{', '.join(SCHEDULES)} (alias: {aliases})")
    return name
