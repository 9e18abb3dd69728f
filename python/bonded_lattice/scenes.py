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
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .conversion import BondParameters, lattice_mass, rock_to_bond
from .grains import (GrainPairOptions, competent_layer, particle_stiffness,
                     voronoi_grains, voronoi_seeds)
from .io.dump import read_local_dump
from .lattice import Lattice, check_atom_style, write_data

KINDS = ("layer-extension", "layer-compression", "polycrystal", "expanding")
# how the box deforms: pure shear (the other axis shortens or lengthens to keep the area),
# or uniaxial (the other axis' walls stay where they are)
DEFORMATIONS = ("pure-shear", "uniaxial")
MODES = ("quasistatic", "dynamic")
SQRT3 = math.sqrt(3.0)
ROW = 0.5 * SQRT3            # row spacing of the hexagonal lattice, in units of d
DATA_FILE = "data.scene"
SCENE_COLUMNS = ("k", "step", "exx", "eyy", "sxx", "syy", "intact", "tension", "shear",
                 "contacts", "growth")
# memory of a scene run: bytes per particle (atoms, 3 bond records, neighbour lists, the
# final bond dump's buffers) and per rank, fitted to the peak resident size of 10-step runs
# on 1 rank of 184,800 and 737,600 particles (213 and 775 MB; docs/scenes.md)
BYTES_PER_PARTICLE = 1020.0
BYTES_PER_RANK = 30.0e6
# atom_style atomic carries no diameter, mass, angular velocity or torque: the benchmark's
# peak memory per particle falls by this much (docs/performance.md, 2D and 3D alike)
ATOMIC_SAVING_PER_PARTICLE = 81.0


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

    Heterogeneity: layer_thickness (fraction of the box height) and
    layer_contrast (layer stiffness / matrix); n_grains Voronoi grains with
    stiffness factors from a Gaussian (mean 1, stiffness_sd); every bond's
    strength factor uniform in [strength_min, strength_max], times
    boundary_strength across grain (and layer) boundaries (default 0.5 for
    grains, 1 for the layer: :attr:`boundary_factor`); n_expanding grains
    (those nearest the centre, preferably touching no wall) grow.

    Loading: deformation "pure-shear" (y scaled by the inverse of x) or
    "uniaxial" (y walls held; not for expanding grains, whose walls are held
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
    ftol: float = 1.0e-3
    crossings: float = 50.0
    dt_fraction: float = 0.19
    damping: float = 1.0
    output_every: int = 1          # strain steps between scene.dat lines (dynamic: the equivalent)
    bond_dumps: int = 0            # >0: bonds.<step>.txt every this many strain steps
    maxsteps: int = 100000         # per relaxation (lattice/quasistatic maxsteps)
    # "atomic": per-type mass and pair_style lattice/bond diameter d (less memory); not
    # for expanding grains, whose particles need their own diameters
    atom_style: str = "sphere"

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
        check_atom_style(self.atom_style)
        if self.kind == "expanding" and self.atom_style != "sphere":
            raise ValueError(f"atom_style = {self.atom_style!r}: growing grains change their "
                             "particles' diameters, which needs atom_style sphere")
        if self.n_x < 4:
            raise ValueError(f"n_x = {self.n_x} is out of range: need n_x >= 4")
        if self.n_y != 0 and self.n_y < 4:
            raise ValueError(f"n_y = {self.n_y} is out of range: need 0 (square) or n_y >= 4")
        if self.bond.Ks != 0.0 or self.bond.mu_p != 0.0:
            raise ValueError(f"Ks = {self.bond.Ks}, mu_p = {self.bond.mu_p}: the scenes are the "
                             "seed's central springs, need Ks = 0 and mu_p = 0")
        for name in ("d", "rho", "layer_thickness", "layer_contrast", "strain_step", "ftol",
                     "crossings", "dt_fraction"):
            value = getattr(self, name)
            if not (value > 0 and math.isfinite(value)):
                raise ValueError(f"{name} = {value} is out of range: need 0 < {name} < inf")
        if not self.layer_thickness < 1:
            raise ValueError(f"layer_thickness = {self.layer_thickness} is out of range: need "
                             "0 < layer_thickness < 1 (a fraction of the box height)")
        if not self.dt_fraction <= 0.5:
            raise ValueError(f"dt_fraction = {self.dt_fraction} is out of range: need <= 0.5")
        if not (self.damping >= 0 and math.isfinite(self.damping)):
            raise ValueError(f"damping = {self.damping} is out of range: need 0 <= damping < inf")
        for name in ("n_steps", "output_every", "maxsteps", "n_grains"):
            if getattr(self, name) < 1:
                raise ValueError(f"{name} = {getattr(self, name)} is out of range: need >= 1")
        if self.bond_dumps < 0:
            raise ValueError(f"bond_dumps = {self.bond_dumps} is out of range: need >= 0")
        if self.kind == "expanding" and not 1 <= self.n_expanding < self.n_grains:
            raise ValueError(f"n_expanding = {self.n_expanding} is out of range: need "
                             f"1 <= n_expanding < n_grains = {self.n_grains}")
        if self.kind in ("polycrystal", "expanding") and self.n_grains < 2:
            raise ValueError(f"n_grains = {self.n_grains}: a polycrystal needs >= 2 grains")
        # checks the strength and seed ranges
        self.pair_options()

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
        """Effective width n_x d: the wall rows' centre distance + d (carries sigma_yy)."""
        return self.n_x * self.d

    @property
    def height(self) -> float:
        """Effective height rows x sqrt3/2 d (carries sigma_xx)."""
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
                                self.boundary_factor)

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


# ---------------------------------------------------------------- geometry and grains

def box_lattice(n_x: int, n_y: int, d: float) -> Lattice:
    """n_x x n_y particles: rows along x at y = (j + 1/2) sqrt3/2 d... from d/2, odd rows
    shifted by d/2, so every row holds n_x particles; numbered row by row."""
    j, i = np.meshgrid(np.arange(n_y), np.arange(n_x), indexing="ij")
    pos = np.zeros((n_x * n_y, 3))
    pos[:, 0] = ((i + 0.5 * (j % 2)) * d + 0.5 * d).reshape(-1)
    pos[:, 1] = (j * ROW * d + 0.5 * d).reshape(-1)
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    # margin 2 d: the walls move out by strain x half the box, a fraction of d
    box = np.array([[lo[0] - 2 * d, hi[0] + 2 * d], [lo[1] - 2 * d, hi[1] + 2 * d],
                    [-0.5 * d, 0.5 * d]])
    return Lattice(pos, d, 2, box)


def wall_masks(positions: np.ndarray, d: float) -> dict[str, np.ndarray]:
    """The four wall rows (the deck selects the same particles with regions)."""
    x, y = positions[:, 0], positions[:, 1]
    return {"left": x < x.min() + 0.6 * d, "right": x > x.max() - 0.6 * d,
            "bottom": y < y.min() + 0.1 * d, "top": y > y.max() - 0.1 * d}


def expanding_grains(grain: np.ndarray, positions: np.ndarray, d: float, n_grains: int,
                     seed: int, count: int) -> list[int]:
    """The ``count`` grains whose Voronoi seed points lie nearest the box centre, those
    that touch no wall row first (with few grains every grain may touch a wall: then the
    nearest ones that do)."""
    p = positions[:, :2]
    lo, hi = p.min(axis=0) - 0.5 * d, p.max(axis=0) + 0.5 * d
    seeds = voronoi_seeds(lo, hi, n_grains, seed)
    walls = np.zeros(len(p), dtype=bool)
    for mask in wall_masks(positions, d).values():
        walls |= mask
    touching = set(np.unique(grain[walls]).tolist())
    present = set(np.unique(grain).tolist())
    order = np.argsort(np.linalg.norm(seeds - 0.5 * (lo + hi), axis=1))
    inner = [int(g) for g in order if g in present and g not in touching]
    outer = [int(g) for g in order if g in present and g in touching]
    chosen = (inner + outer)[:count]
    if len(chosen) < count:
        raise ValueError(f"only {len(chosen)} grains have particles: need {count} growing "
                         "ones and one more (use more grains or fewer expanding ones)")
    return sorted(chosen)


@dataclass
class SceneModel:
    """The particles of a scene with their grain ids and stiffness factors."""

    lattice: Lattice
    grain: np.ndarray
    stiffness: np.ndarray
    expanding: list[int]


def build_model(scene: Scene) -> SceneModel:
    """Lattice, grain ids and stiffness factors of a scene."""
    lat = box_lattice(scene.n_x, scene.rows, scene.d)
    p = lat.positions
    expanding: list[int] = []
    if scene.kind.startswith("layer"):
        y = p[:, 1]
        thickness = scene.layer_thickness * scene.height
        grain, stiffness = competent_layer(p, "y", 0.5 * (y.min() + y.max()), thickness,
                                           scene.layer_contrast)
    else:
        lo, hi = p[:, :2].min(axis=0) - 0.5 * scene.d, p[:, :2].max(axis=0) + 0.5 * scene.d
        grain = voronoi_grains(p, lo, hi, scene.n_grains, scene.seed)
        stiffness = particle_stiffness(grain, 1.0, scene.stiffness_sd, scene.seed)
        if scene.kind == "expanding":
            expanding = expanding_grains(grain, p, scene.d, scene.n_grains, scene.seed,
                                         scene.n_expanding)
    return SceneModel(lat, grain, stiffness, expanding)


# ---------------------------------------------------------------- the deck

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
    return title.replace("pure shear", "uniaxial strain") if scene.deformation == "uniaxial" else title


def deck_text(scene: Scene, model: SceneModel | None = None,
              data_file: str = DATA_FILE) -> str:
    """The LAMMPS deck of a scene (reads ``data_file``, written by :func:`write_scene`)."""
    if model is None and scene.kind == "expanding":
        model = build_model(scene)
    b, d = scene.bond, scene.d
    fb = b.Kn * b.Xb
    qs = scene.mode == "quasistatic"
    # fix adapt changes radii during a run: only with a dynamic radius (sphere 1)
    style = "sphere 1" if scene.kind == "expanding" and not qs else scene.atom_style
    # atom_style atomic: one diameter for every particle, given to the pair style
    diameter = f"diameter {d!r} " if scene.atom_style == "atomic" else ""
    head = f"""# Mike/Elle scene: {scene_title(scene)}
# {scene.n} particles ({scene.n_x} per row, {scene.rows} rows), {scene.mode} loading.
# Written by bonded_lattice.scenes; run: lmp -in <this file> (or mpirun -np 2 lmp -in ...)
# Central springs (the seed's): Kn {b.Kn:.6g} N/m, Ks 0, Xb {b.Xb:.6g} m, mu_p 0;
# a broken spring only repels.  Breaking force Kn Xb = {fb:.6g} N.

units           si
dimension       2
boundary        f f p
atom_style      {style}
newton          on
# grain id and stiffness factor per particle (the data file's Grains section)
fix             grains all property/atom i_grain d_stiffness ghost yes
read_data       {data_file} fix grains NULL Grains

# bond stiffness: mean of the two particles' factors; strength uniform in
# [{scene.strength_min:g}, {scene.strength_max:g}),
# x {scene.boundary_factor:g} across grain boundaries
pair_style      lattice/bond {diameter}{scene.pair_options().pair_style_args()}
{b.pair_coeff()}
neighbor        {0.1 * d:.6g} bin
# neighbour and atom-sorting bins of one cutoff (LAMMPS' default of half a
# cutoff takes 8x the bins in 3D, about 20 bytes per particle each)
neigh_modify    every 1 delay 0 check yes binsize {1.1 * d:.6g}
atom_modify     sort 1000 {1.1 * d:.6g}
variable        d equal {d!r}

# ---- the deformation box: one row of wall particles per side ----
# held perpendicular to its wall (fix setforce zeroes that force component:
# the force it removes, its global vector, is the wall's reaction), free to
# slide along it: frictionless walls.  Corner particles belong to two walls.
region          rleft block INF $(bound(all,xmin)+0.6*v_d) INF INF INF INF units box
region          rright block $(bound(all,xmax)-0.6*v_d) INF INF INF INF INF units box
region          rbottom block INF INF INF $(bound(all,ymin)+0.1*v_d) INF INF units box
region          rtop block INF INF $(bound(all,ymax)-0.1*v_d) INF INF INF units box
group           left region rleft
group           right region rright
group           bottom region rbottom
group           top region rtop
group           walls union left right bottom top
group           inner subtract all walls
fix             wleft left setforce 0.0 NULL NULL
fix             wright right setforce 0.0 NULL NULL
fix             wbottom bottom setforce NULL 0.0 NULL
fix             wtop top setforce NULL 0.0 NULL

# strains: the walls' distance against the initial one; stresses (tension
# positive): the wall reactions over the length they hold.  sigma_yy: the top
# row's 2 n_x - 1 bonds to the row below carry (n_x - 1/2) d of the lattice;
# sigma_xx: n_y rows of sqrt3/2 d (the 2 n_y - 1 bonds across a column make
# an edge error of order 1/(3 n_y), docs/scenes.md)
variable        Lx0 equal $(xcm(right,x)-xcm(left,x))
variable        Ly0 equal $(xcm(top,y)-xcm(bottom,y))
variable        exx equal (xcm(right,x)-xcm(left,x))/v_Lx0-1
variable        eyy equal (xcm(top,y)-xcm(bottom,y))/v_Ly0-1
variable        sxx equal 0.5*(f_wleft[1]-f_wright[1])/(xcm(top,y)-xcm(bottom,y)+sqrt(3)/2*v_d)
variable        syy equal 0.5*(f_wbottom[2]-f_wtop[2])/(xcm(right,x)-xcm(left,x)+0.5*v_d)
compute         bonds all lattice/bonds
compute         bl all lattice/bond/local id1 id2 state x y z
"""
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
        return head + _quasistatic(scene, fb)
    return head + _dynamic(scene)


def _line_vars() -> str:
    return "${k} $(step) ${exx} ${eyy} ${sxx} ${syy} $(c_bonds[1]) $(c_bonds[2]) " \
           "$(c_bonds[3]) $(c_bonds[4]) ${growth}"


def _quasistatic(scene: Scene, fb: float) -> str:
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
                 "\"write_dump all local bonds.${k}.txt c_bl[*]\"\n")
    return f"""
# ---- quasi-static loading (the seed's loop): {scene.n_steps} steps ----
# {what};
# then relax (FIRE) until no force component exceeds {scene.ftol:g} x Kn Xb, break the
# most over-stressed bond, relax again, ... until no bond exceeds its threshold
min_style       fire
thermo_style    custom step v_exx v_eyy v_sxx v_syy c_bonds[1] c_bonds[2] c_bonds[3] c_bonds[4] pe
thermo_modify   norm no
thermo          1000000
run             0 post no
variable        growth equal 0
variable        k equal 0
print           "# {' '.join(SCENE_COLUMNS)}" file scene.dat screen no
print           "{_line_vars()}" append scene.dat screen no
variable        k delete
# the number of strain steps; shorten a trial with -var nsteps 2
variable        nsteps index {scene.n_steps}
variable        k loop ${{nsteps}}
label           strain
{step}
lattice/quasistatic ftol {scene.ftol * fb:.6g} break one maxsteps {scene.maxsteps}
run             0 post no
print           "{_line_vars()}" append scene.dat screen no
{dumps}next            k
jump            SELF strain

write_dump      all local bonds.final.txt c_bl[*]
"""


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
                 "bonds.*.txt c_bl[*]\n")
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
{growth}fix             integrate all lattice/nve
# damping of the interior only: the walls keep their speed, and their reaction
# is the bonds' force alone
fix             damp inner lattice/viscous {scene.eta():.6g}
timestep        {dt!r}
variable        k equal floor(step/{per_step})
thermo_style    custom step v_exx v_eyy v_sxx v_syy c_bonds[1] c_bonds[2] c_bonds[3] c_bonds[4] ke
thermo_modify   norm no
thermo          {out_every}
print           "# {' '.join(SCENE_COLUMNS)}" file scene.dat screen no
fix             out all print {out_every} "{_line_vars()}" append scene.dat screen no
{dumps}# the number of time steps; shorten a trial with -var nsteps 10
variable        nsteps index {steps}
run             ${{nsteps}}
write_dump      all local bonds.final.txt c_bl[*]
"""


def write_scene(scene: Scene, out: str | Path, deck_name: str | None = None) -> dict:
    """Write the data file and the deck of a scene into ``out``; return a summary dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    model = build_model(scene)
    write_data(model.lattice, out / DATA_FILE, scene.mass, grain=model.grain,
               stiffness=model.stiffness, atom_style=scene.atom_style)
    name = deck_name or f"in.{scene.kind}.{scene.mode}"
    (out / name).write_text(deck_text(scene, model))
    return {"deck": str(out / name), "data": str(out / DATA_FILE), "particles": scene.n,
            "data_bytes": (out / DATA_FILE).stat().st_size, "expanding": model.expanding,
            "memory_bytes": expected_memory(scene.n, atom_style=scene.atom_style)}


def expected_memory(n: int, ranks: int = 1, atom_style: str = "sphere") -> float:
    """Expected resident memory (bytes) of a scene run with n particles, all ranks."""
    per_particle = BYTES_PER_PARTICLE - (ATOMIC_SAVING_PER_PARTICLE if atom_style == "atomic"
                                         else 0.0)
    return per_particle * n + ranks * BYTES_PER_RANK


# ---------------------------------------------------------------- reading results

def read_scene_dat(path: str | Path) -> dict[str, np.ndarray]:
    """The columns of ``scene.dat`` (:data:`SCENE_COLUMNS`)."""
    rows = np.atleast_2d(np.loadtxt(path, comments="#"))
    return {name: rows[:, k] for k, name in enumerate(SCENE_COLUMNS)}


def read_bond_dump(path: str | Path) -> np.ndarray:
    """Rows (id1, id2, state, x, y, z) of a ``dump local`` of the scene's bond compute
    (:func:`bonded_lattice.io.read_local_dump`; no rows: an empty (0, 6) array)."""
    rows = read_local_dump(path)[1]
    return rows if len(rows) else np.zeros((0, 6))


def broken_bonds(path: str | Path) -> np.ndarray:
    """(id1, id2, state, x, y) of the broken bonds (state 1 tension, 2 shear) in a dump."""
    rows = read_bond_dump(path)
    rows = rows[(rows[:, 2] == 1) | (rows[:, 2] == 2)]
    return rows[:, :5]


def break_steps(run_dir: str | Path) -> dict[tuple[int, int], int]:
    """Strain step (k of the dump's name) at which each bond was first seen broken,
    from the ``bonds.<k>.txt`` dumps (quasi-static: k is the strain step; dynamic:
    the time step)."""
    found: dict[tuple[int, int], int] = {}
    files = sorted(Path(run_dir).glob("bonds.*.txt"),
                   key=lambda p: int(p.name.split(".")[1]) if p.name.split(".")[1].isdigit()
                   else 1 << 62)
    for f in files:
        tag = f.name.split(".")[1]
        k = int(tag) if tag.isdigit() else -1
        for i, j, *_ in broken_bonds(f).tolist():
            found.setdefault((int(i), int(j)), k)
    return found


def bond_angles(pairs: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Orientation (degrees, 0-180 from the x axis) of bonds (id1, id2) in the initial lattice."""
    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    v = positions[pairs[:, 1] - 1, :2] - positions[pairs[:, 0] - 1, :2]
    return np.degrees(np.arctan2(v[:, 1], v[:, 0])) % 180.0


def crack_normal_stats(angles: np.ndarray) -> dict[str, float]:
    """Statistics of broken-bond orientations (degrees from x, i.e. from the extension axis).

    A tensile break of a central spring opens a crack normal to the bond.
    mean: the axial (mod 180) mean bond orientation, from the doubled-angle
    resultant; fraction_0: share of bonds at 0 degrees (parallel to x, the
    extension of the pure-shear scenes), fraction_60: at 60 or 120.
    """
    a = np.asarray(angles, dtype=float)
    if len(a) == 0:
        return {"n": 0, "mean": float("nan"), "resultant": 0.0, "fraction_0": float("nan"),
                "fraction_60": float("nan")}
    z = np.exp(2j * np.radians(a)).mean()
    mean = (np.degrees(np.angle(z)) / 2.0) % 180.0
    if mean > 90:
        mean -= 180.0
    horizontal = np.minimum(a, 180.0 - a) < 15.0
    return {"n": int(len(a)), "mean": float(mean), "resultant": float(abs(z)),
            "fraction_0": float(horizontal.mean()), "fraction_60": float((~horizontal).mean())}
