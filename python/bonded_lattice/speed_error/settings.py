"""What the speed-against-error study runs: its tolerances, its two modes (full and quick)
and its lattice runs (:class:`Case`, :func:`lattice_cases`)."""

from __future__ import annotations

from dataclasses import dataclass

from ..schedules import DEFAULT_LOADING, PAPER_SCHEDULES, default_loading

# accuracy that counts as "the papers' accuracy": a setting reaches it for quantity q when
# |error_q - error_q of the papers' schedule| <= TOLERANCE[q], i.e. it measures what the
# papers' schedule measures to within the tolerance (errors of E, nu against the formulas, of
# Tu, Cu against the strength the papers' schedule measures, which is error 0 there); the size
# effect of the block is in both, so a fast run whose loading error happens to cancel part of
# it does not count as more accurate
TOLERANCE = {"E": 0.001, "nu": 0.001, "Tu": 0.005, "Cu": 0.005}
# error levels of the "cheapest setting within" table
LEVELS = [0.001, 0.002, 0.005, 0.01, 0.02]
QUANTITIES = ("E", "nu", "Tu", "Cu")
TEST_OF = {"E": "elastic", "nu": "elastic", "Tu": "tension", "Cu": "compression"}
PAPER_KEY = {"relax_steps": 400, "step_factor": 1.0}   # the papers' 2D schedule (docs/theory.md)
DEFAULT = DEFAULT_LOADING[2]        # the deck generators' 2D defaults (schedules.py)
# the constant setting of the time-step variants (family dt) and of the stability scan: the
# 2D defaults when this study was first made
DT_BASE = {"crossings": 100.0, "damping": 1.0}
# the rock of each dimension: the papers' quartz (2013, 2D) and quartzite (2017, 3D), the
# same values (rocks.py)
ROCK_OF = {2: "quartz", 3: "quartzite"}


def paper_relax(dim: int) -> int:
    """Relaxation steps of the papers' stepwise schedule in ``dim`` D (PAPER_SCHEDULES)."""
    if dim not in PAPER_SCHEDULES:
        raise ValueError(f"dim = {dim} is out of range: need 2 or 3")
    return int(PAPER_SCHEDULES[dim]["relax_steps"])


@dataclass(frozen=True)
class Settings:
    """What one mode of the study runs."""

    n_elastic: int                 # 2D block (particles across) of the elastic tests
    n_strength: int                # ... of the strength tests
    n_check: int                   # strength block of the transfer check
    crossings: tuple[float, ...]   # constant schedule: elastic-wave crossings to failure
    dampings: tuple[float, ...]    # multiples of the papers' eta
    slow_crossings: tuple[float, ...]
    dt_fractions: tuple[float, ...]   # time step / sqrt(m/Kn), at the default crossings/damping
    relax: tuple[int, ...]         # stepwise schedule: relaxation steps per loading step
    step_factors: tuple[float, ...]   # ... and the step size, a multiple of the papers'
    n_stability: int               # block of the lattice's time-step scan
    stability_fractions: tuple[float, ...]
    stability_bisections: int
    contact_dts: tuple[float, ...]
    contact_tests: tuple[str, ...]
    contact_bisect_rel: float
    # the reference of the transfer check: a slow constant run at these crossings (damping 1),
    # or None: the papers' stepwise schedule at the check's size
    check_reference_crossings: float | None
    dim: int = 2                   # 2D quartz or 3D quartzite (block sizes: n_y in 3D)
    stability: bool = True         # also the lattice's time-step scan

    def __post_init__(self) -> None:
        paper_relax(self.dim)      # (validates dim)

    @property
    def size_name(self) -> str:
        """The block size's name: N (particles across, 2D) or n_y (elements along y, 3D)."""
        return "N" if self.dim == 2 else "n_y"

    @property
    def default(self) -> dict[str, float]:
        """The package's constant-schedule defaults in this dimension (DEFAULT_LOADING)."""
        return DEFAULT_LOADING[self.dim]

    def default_for(self, test: str) -> dict[str, float]:
        """The package's default of ``test`` in this dimension (schedules.default_loading:
        DEFAULT_LOADING with the per-test crossings)."""
        return default_loading(self.dim, test)


FULL = Settings(
    n_elastic=30, n_strength=15, n_check=30,
    crossings=(3, 6, 12, 25, 50, 100, 200), dampings=(0.0, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0),
    slow_crossings=(400, 800), dt_fractions=(0.05, 0.2, 0.4),
    relax=(400, 100, 25), step_factors=(1, 4, 16, 64),
    n_stability=15, stability_fractions=(0.2, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0),
    stability_bisections=4,
    contact_dts=tuple(1.0e-3 * 2.0**k for k in range(-3, 5)),
    contact_tests=("T1", "T2", "T3", "T4"), contact_bisect_rel=1e-4,
    check_reference_crossings=800)

QUICK = Settings(
    n_elastic=8, n_strength=8, n_check=15,
    crossings=(6, 25, 100), dampings=(0.5, 1.0, 4.0),
    slow_crossings=(400,), dt_fractions=(0.2,),
    relax=(400, 25), step_factors=(1, 16),
    n_stability=8, stability_fractions=(0.4, 0.7, 1.0), stability_bisections=2,
    contact_dts=tuple(1.0e-3 * 2.0**k for k in range(-1, 3)),
    contact_tests=("T1", "T3"), contact_bisect_rel=1e-3,
    check_reference_crossings=400)



@dataclass(frozen=True)
class Case:
    """One lattice run."""

    # constant, slow, dt, paper (the papers' stepwise setting), stepwise (its variants),
    # check, stability
    family: str
    test: str              # elastic, tension, compression
    n: int
    schedule: str = "constant"   # constant or stepwise (bonded_lattice.schedules)
    crossings: float = 100.0
    damping: float = 1.0
    dt_fraction: float | None = None   # None: the schedule's own (0.1 / 0.107 sqrt(m/Kn))
    relax_steps: int = 400
    step_factor: float = 1.0
    dim: int = 2           # 2: 2D quartz, n particles across; 3: 3D quartzite, n = n_y

    @property
    def name(self) -> str:
        """The run's folder name (unique within a family and a dimension)."""
        base = f"{self.test}_n{self.n}" if self.dim == 2 else f"{self.test}_ny{self.n}"
        if self.schedule == "stepwise":
            base += f"_stepwise_r{self.relax_steps}_s{self.step_factor:g}"
        else:
            base += f"_c{self.crossings:g}_f{self.damping:g}"
        if self.dt_fraction is not None:
            base += f"_dt{self.dt_fraction:g}"
        return base

    def label(self) -> str:
        """The setting in words, for the report."""
        if self.schedule == "stepwise":
            return f"stepwise, {self.relax_steps} relax, step x{self.step_factor:g}"
        text = f"constant, {self.crossings:g} crossings, damping {self.damping:g}"
        if self.dt_fraction is not None:
            text += f", dt {self.dt_fraction:g} sqrt(m/Kn)"
        return text



def lattice_cases(s: Settings) -> list[Case]:
    """The main sweep: constant grid, slow and dt variants, the stepwise grid."""
    cases: list[Case] = []
    dim = s.dim
    paper = (paper_relax(dim), PAPER_KEY["step_factor"])
    for test in ("elastic", "tension", "compression"):
        n = s.n_elastic if test == "elastic" else s.n_strength
        for c in s.crossings:
            for f in s.dampings:
                cases.append(Case("constant", test, n, crossings=c, damping=f, dim=dim))
        for c in s.slow_crossings:
            cases.append(Case("slow", test, n, crossings=c, damping=1.0, dim=dim))
        for fr in s.dt_fractions:
            cases.append(Case("dt", test, n, dt_fraction=fr, dim=dim))
        for r in s.relax:
            for sf in s.step_factors:
                fam = "paper" if (r, sf) == paper else "stepwise"
                cases.append(Case(fam, test, n, schedule="stepwise", relax_steps=r,
                                  step_factor=sf, dim=dim))
    # cheap first: the stepwise runs with many relaxation steps come last
    return sorted(cases, key=lambda c: (c.schedule == "stepwise",
                                        c.relax_steps / c.step_factor if c.schedule == "stepwise"
                                        else c.crossings))


def test_n(s: Settings, test: str) -> int:
    """The block size of ``test`` in the main sweep of ``s``."""
    return s.n_elastic if test == "elastic" else s.n_strength


def grid_case(s: Settings, test: str, crossings: float, damping: float) -> Case:
    """The main sweep's constant-schedule run of ``test`` at (crossings, damping): family
    ``constant`` for the grid's crossings, ``slow`` for the slow ones."""
    family = "constant" if crossings in set(s.crossings) else "slow"
    return Case(family, test, test_n(s, test), crossings=crossings, damping=damping, dim=s.dim)
