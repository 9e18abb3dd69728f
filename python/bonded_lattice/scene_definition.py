"""A Mike/Elle scene's definition: geometry, heterogeneity and loading (:class:`Scene`).

The seed's model (issue 7) is a 2D triangular lattice of central springs (``Ks = 0``,
``mu_p = 0``: :func:`central_spring_bond`) in a deformation box; :mod:`bonded_lattice.scenes`
describes the scenes and the two loadings.  A :class:`Scene` checks its parameters and
derives what the deck needs from them: the particle count, mass and box size, the time
step, the wave speed, the dynamic loading's duration and the damping coefficient.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace

from .conversion import BondParameters, lattice_mass, rock_to_bond
from .grains import GrainPairOptions
from .lattice import check_atom_style

KINDS = ("layer-extension", "layer-compression", "polycrystal", "expanding")
# how the box deforms: pure shear (the other axis shortens or lengthens to keep the area),
# or uniaxial (the other axis' walls stay where they are)
DEFORMATIONS = ("pure-shear", "uniaxial")
MODES = ("quasistatic", "dynamic")
# how a quasi-static step relaxes: lattice/quasistatic relax direct (Newton steps with a
# sparse Cholesky factor updated per break; the default), relax local (over-relaxation where
# the forces exceed the tolerance), or LAMMPS' FIRE minimiser over the whole box
RELAXATIONS = ("local", "direct", "fire")
# the default tolerance of each, a fraction of Kn Xb.  relax local at 1e-4 breaks the bonds
# of an exact linear solve in its order at 4200, 11,600 and 16,560 particles; FIRE at 1e-3
# only at 4200 (at 11,600 it departs after 10 breaks), at 1e-5 also in the periodic box
# measured (docs/lattice_quasistatic.rst, "Accuracy")
# relax direct solves each linear equilibrium exactly; its tolerance only ends the Newton
# passes that remove what the linear model leaves (second order in the displacements)
DEFAULT_FTOL = {"local": 1.0e-4, "direct": 1.0e-4, "fire": 1.0e-3}
# what bounds the lattice: a row of wall particles on each side held by fix setforce
# (the deformation box), or a box periodic in x and y (no walls, no edges)
BOUNDARIES = ("walls", "periodic")
SQRT3 = math.sqrt(3.0)
ROW = 0.5 * SQRT3            # row spacing of the hexagonal lattice, in units of d


# ---------------------------------------------------------------- bond parameters

def central_spring_bond(E: float, Tu: float, d: float) -> BondParameters:
    """Bond parameters of the seed's central springs for a rock of modulus E and strength Tu.

    The package's 2D conversion (Liu et al. 2013, eqs. B1-B5) gives Ks = 0 for
    nu = 1/4 (plane strain; the lattice's plane Poisson's ratio is then 1/3),
    and then Kn = E / (sqrt3 (1 - 2 nu)(1 + nu)) and Xb = Tu d / (sqrt3 Kn).
    Shear is off: Ks = 0 and mu_p = 0 (a broken spring only repels); Fs0 is
    kept positive (= Cu d / 4 with Cu = 10 Tu) but never used, since the
    shear ratio (Fs + mu_p Fn) / Fs0 of a bond without shear spring is 0.
    """
    with warnings.catch_warnings():   # the Cu caveat of Ks = 0: no shear failure, as wanted
        warnings.simplefilter("ignore", UserWarning)
        b = rock_to_bond(E, 0.25, Tu, 10.0 * Tu, 1.0 / SQRT3, d, 2)
    return replace(b, Ks=0.0, mu_p=0.0)


def plane_moduli(Kn: float) -> tuple[float, float]:
    """(lambda, mu) of the central-spring triangular lattice, 2D (per unit thickness).

    lambda = mu = sqrt3/4 Kn (Liu et al. 2013 eqs. 15-16 with Ks = 0): plane
    Young's modulus 8 mu / 3 = 2 Kn / sqrt3, plane Poisson's ratio 1/3.
    """
    return SQRT3 / 4.0 * Kn, SQRT3 / 4.0 * Kn


# ---------------------------------------------------------------- the scene

@dataclass(frozen=True)
class Scene:
    """One scene: geometry, heterogeneity and loading.

    Geometry: n_x particles in every row, n_y rows (0: the square box,
    round(n_x 2/sqrt3) rows, rounded to even), rows alternately shifted by
    d/2.  The seed's medium and high resolutions are 400 x 462 = 184,800 and
    800 x 922 = 737,600 particles.

    Heterogeneity: layer_thickness (fraction of the box height),
    layer_contrast (layer stiffness / matrix) and matrix_strength (the
    matrix particles' strength factor, the layer's 1: a bond's breaking force
    takes the mean of its particles' factors); n_grains Voronoi grains with
    stiffness factors from a Gaussian (mean 1, stiffness_sd); every bond's
    strength factor uniform in [strength_min, strength_max], times
    boundary_strength across grain (and layer) boundaries (default 0.5 for
    grains, 1 for the layer: :attr:`boundary_factor`); n_expanding grains
    (those nearest the centre, preferably touching no wall) grow.

    Boundary: "walls" (the deformation box: a row of wall particles on each
    side, held perpendicular to it, stresses from the walls' reactions) or
    "periodic" (a box periodic in x and y that the lattice fills exactly,
    width n_x d and height n_y sqrt3/2 d, n_y even; no walls; stresses from
    LAMMPS' virial pressure tensor; quasi-static only).

    Loading: deformation "pure-shear" (y scaled by the inverse of x) or
    "uniaxial" (y walls held, or the periodic box's height kept; not for expanding grains, whose walls are held
    anyway); quasistatic: n_steps steps of strain_step (engineering strain of
    the box along x; for expanding grains the relative diameter increase of
    the growing grains per step), each relaxed to ftol x Kn Xb (the force
    of a bond at its breaking point) with break one; dynamic: the same total
    strain (n_steps x strain_step) applied at a constant rate over
    ``crossings`` P-wave crossings of the box, time step dt_fraction x the
    critical one, viscous damping ``damping`` x the critical damping of one
    particle on its bonds divided by the number of particles across (the
    papers' sqrt(8 m Kn) / N, eq. 34 of Liu et al. 2013).
    """

    kind: str
    n_x: int = 40
    n_y: int = 0
    d: float = 1.0e-3
    bond: BondParameters = field(default_factory=lambda: central_spring_bond(90e9, 25e6, 1e-3))
    rho: float = 2650.0
    layer_thickness: float = 0.2
    layer_contrast: float = 3.0
    matrix_strength: float = 1.0   # layer scenes: the matrix's breaking-force factor
    n_grains: int = 12
    stiffness_sd: float = 0.15
    strength_min: float = 0.8
    strength_max: float = 1.2
    boundary_strength: float | None = None   # None: 0.5 (the seed's) for grains, 1 for a layer
    seed: int = 1
    n_expanding: int = 2
    mode: str = "quasistatic"
    deformation: str = "pure-shear"
    strain_step: float = 2.0e-5
    n_steps: int = 30
    ftol: float | None = None      # None: DEFAULT_FTOL of the relaxation
    crossings: float = 50.0
    dt_fraction: float = 0.19
    damping: float = 1.0
    output_every: int = 1          # strain steps between scene.dat lines (dynamic: the equivalent)
    bond_dumps: int = 0            # >0: bonds.<step>.txt every this many strain steps
    # >0 (quasi-static): break.<n>.txt after each of the first break_order breaks, n = 1, 2,
    # ...: the exact order of the first breaks (within a strain step too)
    break_order: int = 0
    # >0 (quasi-static): restart.scene every this many strain steps, for a run cut off to
    # go on from (scene_deck.resume_deck)
    restart_every: int = 0
    maxsteps: int = 100000         # per relaxation (lattice/quasistatic maxsteps)
    relax: str = "direct"          # quasistatic: RELAXATIONS
    threads: int = 1               # relax direct: threads of its factor, solves and loops (rank 0)
    # "atomic": per-type mass and pair_style lattice/bond diameter d (less memory); not
    # for expanding grains, whose particles need their own diameters
    atom_style: str = "sphere"
    boundary: str = "walls"        # BOUNDARIES: wall rows or a periodic box

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"kind = {self.kind!r} is not known: use one of {', '.join(KINDS)}")
        if self.mode not in MODES:
            raise ValueError(f"mode = {self.mode!r} is not known: use one of {', '.join(MODES)}")
        if self.deformation not in DEFORMATIONS:
            raise ValueError(f"deformation = {self.deformation!r} is not known: use one of "
                             f"{', '.join(DEFORMATIONS)}")
        if self.kind == "expanding" and self.deformation != "pure-shear":
            raise ValueError(f"deformation = {self.deformation!r}: growing grains load a box "
                             "whose walls are held; the deformation does not apply")
        if self.boundary not in BOUNDARIES:
            raise ValueError(f"boundary = {self.boundary!r} is not known: use one of "
                             f"{', '.join(BOUNDARIES)}")
        if self.boundary == "periodic" and self.mode != "quasistatic":
            raise ValueError(f"boundary = 'periodic' with mode = {self.mode!r}: the periodic "
                             "box is deformed by the quasi-static steps only; use mode "
                             "quasistatic (or boundary walls)")
        check_atom_style(self.atom_style)
        if self.kind == "expanding" and self.atom_style != "sphere":
            raise ValueError(f"atom_style = {self.atom_style!r}: growing grains change their "
                             "particles' diameters, which needs atom_style sphere")
        if self.n_x < 4:
            raise ValueError(f"n_x = {self.n_x} is out of range: need n_x >= 4")
        if self.n_y != 0 and self.n_y < 4:
            raise ValueError(f"n_y = {self.n_y} is out of range: need 0 (square) or n_y >= 4")
        if self.boundary == "periodic" and self.n_y % 2:
            raise ValueError(f"n_y = {self.n_y} is out of range for boundary = 'periodic': need "
                             "an even number of rows (the rows alternate their d/2 shift, so "
                             "only an even count repeats across the periodic seam)")
        if self.bond.Ks != 0.0 or self.bond.mu_p != 0.0:
            raise ValueError(f"Ks = {self.bond.Ks}, mu_p = {self.bond.mu_p}: the scenes are the "
                             "seed's central springs, need Ks = 0 and mu_p = 0")
        if self.relax not in RELAXATIONS:
            raise ValueError(f"relax = {self.relax!r} is not known: use one of "
                             f"{', '.join(RELAXATIONS)}")
        if self.threads != 1 and self.relax != "direct":
            raise ValueError(f"threads = {self.threads} with relax = {self.relax!r}: the threads "
                             "are relax direct's (its factor and solves); use relax direct or "
                             "threads 1")
        for name in ("d", "rho", "layer_thickness", "layer_contrast", "matrix_strength",
                     "strain_step",
                     "relax_tolerance", "crossings", "dt_fraction"):
            value = getattr(self, name)
            if not (value > 0 and math.isfinite(value)):
                raise ValueError(f"{name} = {value} is out of range: need 0 < {name} < inf")
        if self.matrix_strength != 1.0 and not self.kind.startswith("layer"):
            raise ValueError(f"matrix_strength = {self.matrix_strength} with kind = "
                             f"{self.kind!r}: the matrix is the layer scenes' (use "
                             "layer-extension or layer-compression, or matrix_strength 1)")
        if not self.layer_thickness < 1:
            raise ValueError(f"layer_thickness = {self.layer_thickness} is out of range: need "
                             "0 < layer_thickness < 1 (a fraction of the box height)")
        if not self.dt_fraction <= 0.5:
            raise ValueError(f"dt_fraction = {self.dt_fraction} is out of range: need <= 0.5")
        if not (self.damping >= 0 and math.isfinite(self.damping)):
            raise ValueError(f"damping = {self.damping} is out of range: need 0 <= damping < inf")
        for name in ("n_steps", "output_every", "maxsteps", "n_grains", "threads"):
            if getattr(self, name) < 1:
                raise ValueError(f"{name} = {getattr(self, name)} is out of range: need >= 1")
        if self.bond_dumps < 0:
            raise ValueError(f"bond_dumps = {self.bond_dumps} is out of range: need >= 0")
        if self.break_order < 0:
            raise ValueError(f"break_order = {self.break_order} is out of range: need >= 0")
        if self.restart_every < 0:
            raise ValueError(f"restart_every = {self.restart_every} is out of range: need >= 0")
        if self.restart_every and self.mode != "quasistatic":
            raise ValueError(f"restart_every = {self.restart_every} with mode = {self.mode!r}: "
                             "the restart files are written between the quasi-static steps; "
                             "use mode quasistatic or restart_every 0")
        if self.break_order and self.mode != "quasistatic":
            raise ValueError(f"break_order = {self.break_order} with mode = {self.mode!r}: "
                             "the breaks are ordered by the quasi-static loop only")
        if self.kind == "expanding" and not 1 <= self.n_expanding < self.n_grains:
            raise ValueError(f"n_expanding = {self.n_expanding} is out of range: need "
                             f"1 <= n_expanding < n_grains = {self.n_grains}")
        if self.kind in ("polycrystal", "expanding") and self.n_grains < 2:
            raise ValueError(f"n_grains = {self.n_grains}: a polycrystal needs >= 2 grains")
        # checks the strength and seed ranges
        self.pair_options()

    @property
    def relax_tolerance(self) -> float:
        """The relaxation tolerance, a fraction of Kn Xb: ftol, or the relaxation's default."""
        return DEFAULT_FTOL[self.relax] if self.ftol is None else self.ftol

    @property
    def rows(self) -> int:
        """Number of rows (n_y, or the square box's even count)."""
        if self.n_y:
            return self.n_y
        return max(4, 2 * round(self.n_x / SQRT3))

    @property
    def n(self) -> int:
        """Number of particles."""
        return self.n_x * self.rows

    @property
    def mass(self) -> float:
        """Particle mass per unit thickness, rho sqrt3 d^2 / 2."""
        return lattice_mass(self.rho, self.d, 2)

    @property
    def width(self) -> float:
        """Width n_x d: walls: the wall rows' centre distance + d (carries sigma_yy);
        periodic: the box's period along x."""
        return self.n_x * self.d

    @property
    def height(self) -> float:
        """Height rows x sqrt3/2 d: walls: the effective height (carries sigma_xx);
        periodic: the box's period along y."""
        return self.rows * ROW * self.d

    @property
    def boundary_factor(self) -> float:
        """Strength factor across grain boundaries: as given, or 0.5 (the seed's grain
        boundaries) for the polycrystals and 1 for the layer's interfaces (the seed
        weakens only grain boundaries; a weak interface would delaminate first)."""
        if self.boundary_strength is not None:
            return self.boundary_strength
        return 1.0 if self.kind.startswith("layer") else 0.5

    def pair_options(self) -> GrainPairOptions:
        return GrainPairOptions(self.strength_min, self.strength_max, self.seed,
                                self.boundary_factor,
                                particle_strength=self.matrix_strength != 1.0)

    def dt(self) -> float:
        """Time step: dt_fraction x sqrt(2 m / (6 Kn k_max)), the stiffest grain's bonds."""
        k_max = self.bond.Kn * self.max_stiffness()
        return self.dt_fraction * math.sqrt(2.0 * self.mass / (6.0 * k_max))

    def max_stiffness(self) -> float:
        if self.kind.startswith("layer"):
            return max(1.0, self.layer_contrast)
        return 1.0 + 5.0 * self.stiffness_sd

    def wave_speed(self) -> float:
        """P-wave speed sqrt((lambda + 2 mu) / rho) of the matrix (stiffness factor 1)."""
        lam, mu = plane_moduli(self.bond.Kn)
        return math.sqrt((lam + 2.0 * mu) / self.rho)

    def total_strain(self) -> float:
        return self.strain_step * self.n_steps

    def duration(self) -> float:
        """Dynamic loading time: crossings x width / wave speed."""
        return self.crossings * self.width / self.wave_speed()

    def steps_per_strain_step(self) -> int:
        """Dynamic: time steps per quasi-static strain step (the output interval unit)."""
        return max(1, math.ceil(self.duration() / self.dt() / self.n_steps))

    def dynamic_steps(self) -> int:
        """Dynamic: time steps of the whole loading, a whole number of output intervals."""
        return self.steps_per_strain_step() * self.n_steps

    def eta(self) -> float:
        """Viscous damping coefficient (N s/m per unit thickness)."""
        return self.damping * math.sqrt(8.0 * self.mass * self.bond.Kn) / self.n_x
