"""Close-packed blocks of equal spheres and LAMMPS data files for them.

All particles have the same diameter ``d`` and every neighbour pair touches, so
``pair_style lattice/bond`` bonds each particle to 6 neighbours (2D hexagonal
lattice) or 12 (3D close packing) at the first run.

Geometry of the papers' models
------------------------------
2D (Liu, Pollard & Shi 2013): close-packed rows along x, stacked along y (the
loading axis), rows alternating ``N`` and ``N - 1`` particles, the first row
full.  :func:`hex_block_2d` reproduces the LAMMPS recipe::

    lattice  hex d
    region   box block -0.25 N-0.75 -0.25 N/sqrt(3)-0.2 -0.5 0.5   # lattice units

i.e. rows at ``y = j sqrt(3)/2 d`` while ``y <= (N - 0.2 sqrt(3)) d``.  This gives
the paper's 3, 18, 68, 247, 1033, 4106, 16611 particles for N = 2, 4, 8, 15, 30,
60, 120 (2, 5, 9, 17, 35, 69, 139 rows).

3D (Liu et al. 2017): hexagonal close packing (ABAB...), close-packed layers
horizontal (xy) and stacked along z (the loading axis), so that the elementary
tetrahedron has three elements on its base and one on top.  In each layer the
close-packed rows run along y and hold ``n_y`` and ``n_y - 1`` elements.  The
block is bounded by complete A planes: an odd number of rows (along x) and an
odd number of layers (along z), the largest whose centre extent does not exceed
``(n_y - 0.2 sqrt(3)) d`` (the same allowance as the 2D recipe).  This gives
exactly 82, 255, 580, 1105, 2166, 5461, 10985, 18079, 37681 elements for
n_y = 4, 6, 8, 10, 12, 16, 20, 24, 30 (any allowance between 0.21 d and
0.40 d does); n_y = 2 is the paper's single tetrahedral unit (4 elements).
With face-centred (ABC) stacking no number of rows and layers of this kind
gives these counts (n_y = 4 already fails); with hcp every value is matched.

Particle ids
------------
Positions are sorted layer by layer along the loading axis, then row by row, so
neighbours have nearby ids; :func:`write_data` numbers them in that order.
Bonds are owned by the lower id, so this keeps bond ownership balanced.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .io.data import GRAINS_SECTION, read_grain_strengths, read_grains  # noqa: F401  (the readers)

SQRT3 = math.sqrt(3.0)
LAYER_SPACING = math.sqrt(2.0 / 3.0)  # between close-packed layers, in units of d
ALLOWANCE = 0.2 * SQRT3               # the 2D recipe's "-0.2 lattice units" along y, in units of d
_TOL = 1e-9                           # relative tolerance (units of d) when cutting a block
MAX_PARTICLES = 10**8                 # generators refuse larger blocks (memory: ~10 GB of sites)

# in-plane shift of the B and C layers (x, y in units of d), rows along y
_LAYER_SHIFT = {"A": (0.0, 0.0), "B": (SQRT3 / 6.0, 0.5), "C": (SQRT3 / 3.0, 0.0)}
_STACKING = {"hcp": "AB", "fcc": "ABC"}


@dataclass
class Lattice:
    """Particles of one diameter on a close-packed lattice.

    positions: (n, 3) centres, sorted so that neighbours have nearby ids
        (z = 0 in 2D).
    d: particle diameter.
    dim: 2 or 3.  The loading axis is y in 2D and z in 3D.
    box: (3, 2) lower/upper simulation box bounds for the data file: the
        particles plus a margin on each side so that walls and fixes fit
        (2D: z from -d/2 to d/2, meant to be periodic).
    types: (n,) atom types, 1 by default.
    tilt: the tilt factors (xy, xz, yz) of a triclinic box, or None for an
        orthogonal one (:mod:`bonded_lattice.periodic` makes periodic cells
        whose edges are lattice vectors).
    """

    positions: np.ndarray
    d: float
    dim: int
    box: np.ndarray
    types: np.ndarray = field(default=None)  # type: ignore[assignment]
    tilt: tuple[float, float, float] | None = None

    def __post_init__(self) -> None:
        self.d = float(self.d)
        self.positions = np.asarray(self.positions, dtype=float).reshape(-1, 3)
        self.box = np.asarray(self.box, dtype=float).reshape(3, 2)
        if self.types is None:
            self.types = np.ones(len(self.positions), dtype=int)
        self.types = np.asarray(self.types, dtype=int).reshape(-1)
        if self.dim not in (2, 3):
            raise ValueError(f"dim = {self.dim} is out of range: use 2 or 3")
        if not self.d > 0:
            raise ValueError(f"d = {self.d} is out of range: need d > 0")
        if len(self.types) != len(self.positions):
            raise ValueError(f"{len(self.types)} types for {len(self.positions)} particles")

    @property
    def n(self) -> int:
        """Number of particles."""
        return len(self.positions)

    @property
    def axis(self) -> int:
        """Index of the loading axis: 1 (y) in 2D, 2 (z) in 3D."""
        return 1 if self.dim == 2 else 2

    @property
    def bounds(self) -> np.ndarray:
        """(3, 2) minimum and maximum of the particle centres."""
        return np.stack([self.positions.min(axis=0), self.positions.max(axis=0)], axis=1)

    @property
    def width(self) -> float:
        """Extent of the centres along x (add d for the block's outer width)."""
        b = self.bounds[0]
        return float(b[1] - b[0])

    @property
    def height(self) -> float:
        """Extent of the centres along the loading axis (y in 2D, z in 3D)."""
        b = self.bounds[self.axis]
        return float(b[1] - b[0])

    def cross_section_area(self) -> float:
        """Outer area of the block across the loading axis (centre extents + d).

        2D: ``width + d`` per unit thickness; 3D: ``(x extent + d) (y extent + d)``.
        """
        ext = self.bounds[:, 1] - self.bounds[:, 0] + self.d
        return float(ext[0]) if self.dim == 2 else float(ext[0] * ext[1])

    def loaded_area(self) -> float:
        """Area between the centres of the outermost particles across the loading axis.

        The stress convention under which a block's measured E matches the
        lattice formulas to 0.8% (the outer half-particle of the free sides carries
        almost no load): with the outer area instead, E comes out low by about
        100/N % in 2D and 180/n_y % in 3D (measured with the elastic tests).
        2D: ``width`` per unit thickness; 3D: ``x extent * y extent``.
        """
        ext = self.bounds[:, 1] - self.bounds[:, 0]
        return float(ext[0]) if self.dim == 2 else float(ext[0] * ext[1])


def _box(positions: np.ndarray, d: float, dim: int) -> np.ndarray:
    """Box around the particles: half a diameter plus d + 25 % of the extent per side."""
    lo, hi = positions.min(axis=0), positions.max(axis=0)
    margin = 0.5 * d + d + 0.25 * (hi - lo)
    box = np.stack([lo - margin, hi + margin], axis=1)
    if dim == 2:
        box[2] = (-0.5 * d, 0.5 * d)
    return box


def _sorted(positions: np.ndarray, d: float, dim: int) -> np.ndarray:
    """Order: loading axis (layers/rows) first, then across, then along the rows."""
    if dim == 2:
        row = np.floor(positions[:, 1] / (0.5 * SQRT3 * d) + 0.5)
        order = np.lexsort((positions[:, 0], row))
    else:
        layer = np.floor(positions[:, 2] / (LAYER_SPACING * d) + 0.5)
        row = np.floor(positions[:, 0] / (0.5 * SQRT3 * d) + 0.5)
        order = np.lexsort((positions[:, 1], row, layer))
    return positions[order]


def _check_size(d: float, **sizes: float) -> None:
    if not (d > 0 and math.isfinite(d)):
        raise ValueError(f"d = {d} is out of range: need 0 < d < inf")
    volume = 1.0
    for name, value in sizes.items():
        if not (value >= d and math.isfinite(value)):
            raise ValueError(f"{name} = {value} is out of range: need d = {d} <= {name} < inf")
        volume *= value / d
    # about one site per d^dim: refuse before allocating the sites
    if volume > MAX_PARTICLES:
        raise ValueError(f"{' x '.join(sizes)} = {' x '.join(f'{v:g}' for v in sizes.values())} "
                         f"holds about {volume:.3g} particles of d = {d}: more than the "
                         f"generators' limit of {MAX_PARTICLES:.0e}")


def block_2d(width: float, height: float, d: float, orientation: float = 0.0) -> Lattice:
    """Hexagonal lattice filling the rectangle [0, width] x [0, height].

    Keeps every site whose disc lies inside the rectangle.  The lattice has a
    site at (d/2, d/2), the centre of the lower-left particle.

    orientation: angle (degrees, counter-clockwise) from the x axis to the
        close-packed rows; the lattice is rotated about (d/2, d/2) and the
        rectangle stays put.  Bonds then point along orientation, +60 and +120
        degrees.  At 0 (the papers' set-up) the rows are horizontal and the
        loading axis y is perpendicular to them (90 degrees to the rows, as
        in the papers' triangular unit: two particles on the base, one on
        top); at 30 (equivalently 90) one bond family is parallel to the
        loading axis.  The lattice repeats every 60 degrees.  Its linear
        elastic response is isotropic, but strength and fracture pattern
        depend on the orientation (the lattice's anisotropy).
    """
    _check_size(d, width=width, height=height)
    if not math.isfinite(orientation):
        raise ValueError(f"orientation = {orientation} is out of range: need a finite angle "
                         f"in degrees")
    t = math.radians(orientation)
    c, s = math.cos(t), math.sin(t)
    a1 = d * np.array([c, s])                                     # along the rows
    a2 = d * np.array([0.5 * c - 0.5 * SQRT3 * s, 0.5 * s + 0.5 * SQRT3 * c])  # next row
    origin = np.array([0.5 * d, 0.5 * d])
    hi = np.array([width - 0.5 * d, height - 0.5 * d])
    # lattice coordinates of the corners of the region the centres may occupy
    corners = np.array([[0, 0], [hi[0] - origin[0], 0], [0, hi[1] - origin[1]], hi - origin])
    ij = np.linalg.solve(np.stack([a1, a2], axis=1), corners.T)
    lo_ij = np.floor(ij.min(axis=1)).astype(int) - 1
    hi_ij = np.ceil(ij.max(axis=1)).astype(int) + 1
    i, j = np.meshgrid(np.arange(lo_ij[0], hi_ij[0] + 1), np.arange(lo_ij[1], hi_ij[1] + 1),
                       indexing="ij")
    xy = origin + i.reshape(-1, 1) * a1 + j.reshape(-1, 1) * a2
    tol = _TOL * d
    keep = np.all((xy >= origin - tol) & (xy <= hi + tol), axis=1)
    pos = np.zeros((int(keep.sum()), 3))
    pos[:, :2] = xy[keep]
    pos = _sorted(pos, d, 2)
    return Lattice(pos, d, 2, _box(pos, d, 2))


def hex_block_2d(n_across: int, d: float, aspect: float = 1.0, orientation: float = 0.0) -> Lattice:
    """The 2013 paper's block: ``n_across`` particles along x, height about aspect x width.

    Rows along x alternate n_across and n_across - 1 particles (first row
    full); rows are added along y while the centres stay within
    ``(aspect n_across - 0.2 sqrt(3)) d`` of the first row, as the LAMMPS
    recipe ``lattice hex d`` + ``region block -0.25 N-0.75 -0.25 N/sqrt(3)-0.2``
    does.  For aspect 1 and n_across = 2, 4, 8, 15, 30, 60, 120 this gives the
    paper's 3, 18, 68, 247, 1033, 4106, 16611 particles (2 is the single
    triangular unit).

    orientation: see :func:`block_2d`; the rotated lattice fills a rectangle
        of the same size as the unrotated block.
    """
    if n_across < 2:
        raise ValueError(f"n_across = {n_across} is out of range: need n_across >= 2")
    if not (aspect > 0 and math.isfinite(aspect)):
        raise ValueError(f"aspect = {aspect} is out of range: need 0 < aspect < inf")
    if n_across * n_across * aspect > MAX_PARTICLES:
        raise ValueError(f"n_across = {n_across} with aspect = {aspect} holds about "
                         f"{n_across * n_across * aspect:.3g} particles: more than the "
                         f"generators' limit of {MAX_PARTICLES:.0e}")
    rows = math.floor((aspect * n_across - ALLOWANCE) / (0.5 * SQRT3) + _TOL) + 1
    if rows < 1:
        raise ValueError(f"aspect = {aspect} is too small: no complete row fits")
    height = ((rows - 1) * 0.5 * SQRT3 + 1.0) * d
    return block_2d(n_across * d, height, d, orientation)


def block_3d(size_x: float, size_y: float, size_z: float, d: float,
             stacking: str = "hcp") -> Lattice:
    """Close packing filling the box [0, size_x] x [0, size_y] x [0, size_z].

    Keeps every site whose sphere lies inside the box.  Close-packed layers
    are horizontal (stacked along z, the loading axis, spacing sqrt(2/3) d),
    close-packed rows run along y (stacked along x, spacing sqrt(3)/2 d), and
    the lattice has a site at (d/2, d/2, d/2).

    stacking: "hcp" (ABAB..., the 2017 paper's hexagonal close packing) or
        "fcc" (ABCABC...).
    """
    _check_size(d, size_x=size_x, size_y=size_y, size_z=size_z)
    if stacking not in _STACKING:
        raise ValueError(f"stacking = {stacking!r} is not known: use 'hcp' or 'fcc'")
    seq = _STACKING[stacking]
    shift = np.array([_LAYER_SHIFT[c] for c in seq])
    n_layers = math.floor((size_z / d - 1.0) / LAYER_SPACING + _TOL) + 1
    n_rows = math.floor((size_x / d - 1.0) / (0.5 * SQRT3) + _TOL) + 2  # B/C rows may reach further
    n_along = math.floor(size_y / d - 1.0 + _TOL) + 2
    i, j, k = np.meshgrid(np.arange(-1, n_along + 1), np.arange(-1, n_rows + 1),
                          np.arange(n_layers), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    s = shift[k % len(seq)]
    pos = np.empty((len(i), 3))
    pos[:, 0] = j * 0.5 * SQRT3 + s[:, 0]
    pos[:, 1] = i + 0.5 * (j % 2) + s[:, 1]
    pos[:, 2] = k * LAYER_SPACING
    pos = (pos + 0.5) * d
    hi = np.array([size_x, size_y, size_z]) - 0.5 * d
    tol = _TOL * d
    keep = np.all((pos >= 0.5 * d - tol) & (pos <= hi + tol), axis=1)
    pos = _sorted(pos[keep], d, 3)
    return Lattice(pos, d, 3, _box(pos, d, 3))


def close_packed_block_3d(n_y: int, d: float, aspect: float = 1.0,
                          stacking: str = "hcp") -> Lattice:
    """The 2017 paper's cubic block: ``n_y`` elements along y, loading axis z.

    Rows along y alternate n_y and n_y - 1 elements.  Along x (rows) and z
    (layers) the block takes the largest odd number of rows / layers whose
    centre extent stays within ``(n_y - 0.2 sqrt(3)) d`` (``aspect n_y`` along
    z), so it starts and ends on complete A rows and A layers.  With hcp
    stacking and aspect 1, n_y = 2, 4, 6, 8, 10, 12, 16, 20, 24, 30 give the
    paper's 4, 82, 255, 580, 1105, 2166, 5461, 10985, 18079, 37681 elements;
    n_y = 2 is the single tetrahedral unit (three elements on the base, one on
    top).
    """
    if n_y < 2:
        raise ValueError(f"n_y = {n_y} is out of range: need n_y >= 2")
    if not (aspect > 0 and math.isfinite(aspect)):
        raise ValueError(f"aspect = {aspect} is out of range: need 0 < aspect < inf")
    if float(n_y) ** 3 * aspect > MAX_PARTICLES:
        raise ValueError(f"n_y = {n_y} with aspect = {aspect} holds about "
                         f"{float(n_y) ** 3 * aspect:.3g} particles: more than the generators' "
                         f"limit of {MAX_PARTICLES:.0e}")
    if n_y == 2:  # the single unit: base rows of 2 and 1, one element on top
        return block_3d((0.5 * SQRT3 + 1.0) * d, 2 * d, (LAYER_SPACING + 1.0) * d, d, stacking)
    pairs_x = math.floor((n_y - ALLOWANCE) / SQRT3 + _TOL)
    pairs_z = math.floor((aspect * n_y - ALLOWANCE) / (2 * LAYER_SPACING) + _TOL)
    if pairs_z < 1:
        raise ValueError(f"aspect = {aspect} is too small: fewer than three layers fit")
    size_x = (pairs_x * SQRT3 + 1.0) * d
    size_z = (pairs_z * 2 * LAYER_SPACING + 1.0) * d
    return block_3d(size_x, n_y * d, size_z, d, stacking)


ORIENTATIONS_3D = (0.0, 90.0)   # of turned_block_3d: layers across the load, rows along it


def turned_block_3d(lattice: Lattice, orientation: float) -> Lattice:
    """A 3D block (loading axis z) turned about x by ``orientation`` degrees, 0 or 90.

    0: the block as it is (the 2017 paper's set-up: close-packed layers across the load).
    90: (x, y, z) -> (x, -z, y), moved back so its lower corner centre is again at
    (d/2, d/2, d/2): the close-packed rows, which ran along y, now run along the loading
    axis z (one bond family along the load), and the close-packed layers stand upright, in
    the xz plane.  The ends are then stepped: rows alternate n_y and n_y - 1 elements, so
    the end faces hold elements at 0 and d/2 from the end.  Other angles would cut the
    lattice obliquely, which the 3D generator does not do: a ValueError names the two.
    """
    if lattice.dim != 3:
        raise ValueError(f"lattice.dim = {lattice.dim}: turned_block_3d turns 3D blocks")
    if orientation not in ORIENTATIONS_3D:
        raise ValueError(f"orientation = {orientation} is out of range in 3D: use one of "
                         f"{', '.join(f'{o:g}' for o in ORIENTATIONS_3D)} (degrees about x: "
                         "layers across the load, or rows along it)")
    if orientation == 0.0:
        return lattice
    p = lattice.positions
    pos = np.stack([p[:, 0], -p[:, 2], p[:, 1]], axis=1)
    pos += 0.5 * lattice.d - pos.min(axis=0)
    pos = _sorted(pos, lattice.d, 3)
    return Lattice(pos, lattice.d, 3, _box(pos, lattice.d, 3))


def contact_pairs(lattice: Lattice, rtol: float = 1e-6) -> np.ndarray:
    """Index pairs (i < j) of touching particles: | |ri - rj| - d | <= rtol d.

    These are the pairs that ``pair_style lattice/bond`` bonds at the first run.
    """
    i, j, r = pairs_within(lattice.positions, (1.0 + rtol) * lattice.d)
    keep = np.abs(r - lattice.d) <= rtol * lattice.d
    return np.stack([i[keep], j[keep]], axis=1)


def pairs_within(positions: np.ndarray,
                 cutoff: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """All pairs (i < j) closer than ``cutoff``: index arrays i, j and distances r.

    Cell binning with cells of size ``cutoff``; memory and time grow linearly
    with the number of particles.
    """
    p = np.asarray(positions, dtype=float).reshape(-1, 3)
    if len(p) < 2:
        empty = np.zeros(0, dtype=int)
        return empty, empty, np.zeros(0)
    cell = np.floor((p - p.min(axis=0)) / cutoff).astype(np.int64) + 1  # padded by one cell
    nc = cell.max(axis=0) + 2
    key = cell[:, 0] + nc[0] * (cell[:, 1] + nc[1] * cell[:, 2])
    order = np.argsort(key, kind="stable")
    counts = np.bincount(key, minlength=int(nc.prod()))
    start = np.concatenate([[0], np.cumsum(counts)])
    ii, jj = [], []
    idx = np.arange(len(p))
    offsets = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)]
    for a, b, c in offsets:
        nkey = key + a + nc[0] * (b + nc[1] * c)
        first, last = start[nkey], start[nkey + 1]
        for t in range(int((last - first).max(initial=0))):
            has = first + t < last
            src = idx[has]
            dst = order[first[has] + t]
            mine = src < dst
            ii.append(src[mine])
            jj.append(dst[mine])
    i = np.concatenate(ii) if ii else np.zeros(0, dtype=int)
    j = np.concatenate(jj) if jj else np.zeros(0, dtype=int)
    r = np.linalg.norm(p[i] - p[j], axis=1)
    keep = r < cutoff
    return i[keep], j[keep], r[keep]


ATOM_STYLES = ("sphere", "atomic")    # of write_data; atomic: pair_style lattice/bond diameter D


def check_atom_style(atom_style: str) -> str:
    """The atom style, if one of :data:`ATOM_STYLES`; else a ValueError naming it."""
    if atom_style not in ATOM_STYLES:
        raise ValueError(f"atom_style = {atom_style!r} is not supported: use one of "
                         f"{', '.join(ATOM_STYLES)}")
    return atom_style


def write_data(lattice: Lattice, path: str | Path, mass: float,
               atom_types: int | None = None, grain: np.ndarray | None = None,
               stiffness: np.ndarray | None = None, atom_style: str = "sphere",
               strength: np.ndarray | None = None) -> None:
    """Write a LAMMPS data file for ``atom_style sphere`` (or ``atomic``).

    Atoms are numbered 1..n in the order of ``lattice.positions``; each line is
    ``id type diameter density x y z``.  LAMMPS (version 22 Jul 2025, checked
    by reading the file back) sets ``rmass = density * 4/3 pi (d/2)^3`` in 2D
    as well as in 3D, so density is written as ``mass / (4/3 pi (d/2)^3)`` and
    every particle gets exactly ``mass``, in either dimension (in 2D,
    ``mass`` is the mass per unit thickness, e.g. ``rho sqrt(3) d^2 / 2``).

    atom_style: ``"sphere"`` (the default, as above) or ``"atomic"``: a
        ``Masses`` section gives every atom type ``mass`` and each atom line is
        ``id type x y z``; the deck then gives the diameter to the pair style,
        ``pair_style lattice/bond diameter d`` (the same model in less memory).
    atom_types: number of atom types declared in the header (default: the
        largest type used).
    grain, stiffness: per-particle grain ids (integers >= 0) and stiffness
        factors (> 0) of a heterogeneous model (:mod:`bonded_lattice.grains`),
        both or neither.  They are written as a ``Grains`` section after the
        atoms, one line ``atom-ID grain stiffness`` per particle: the format of
        LAMMPS' ``fix property/atom``, read by ``fix grains all property/atom
        i_grain d_stiffness ghost yes`` defined before ``read_data FILE fix
        grains NULL Grains`` (:func:`read_grains` reads it back).
    strength: per-particle strength factors (> 0; needs grain and stiffness), a
        fourth column of the Grains section, for ``fix property/atom i_grain
        d_stiffness d_strength`` and the pair style's ``strength_factor
        d_strength`` (:func:`read_grain_strengths` reads it back).
    """
    mass = float(mass)
    if not mass > 0:
        raise ValueError(f"mass = {mass} is out of range: need mass > 0")
    check_atom_style(atom_style)
    if (grain is None) != (stiffness is None):
        raise ValueError("grain and stiffness go together (fix property/atom i_grain "
                         "d_stiffness reads both): give both or neither")
    if strength is not None and grain is None:
        raise ValueError("strength factors go with grain ids and stiffness factors (fix "
                         "property/atom i_grain d_stiffness d_strength reads all three): give "
                         "grain and stiffness too")
    if grain is not None:
        from .grains import check_grain_ids, check_stiffness_factors

        grain = check_grain_ids(grain)
        stiffness = check_stiffness_factors(stiffness)
        if len(grain) != lattice.n or len(stiffness) != lattice.n:
            raise ValueError(f"{len(grain)} grain ids and {len(stiffness)} stiffness factors "
                             f"for {lattice.n} particles: need one of each per particle")
        if strength is not None:
            strength = check_stiffness_factors(strength, "strength")
            if len(strength) != lattice.n:
                raise ValueError(f"{len(strength)} strength factors for {lattice.n} particles: "
                                 "need one per particle")
    ntypes = int(lattice.types.max(initial=1)) if atom_types is None else int(atom_types)
    if lattice.n and (lattice.types.min() < 1 or lattice.types.max() > ntypes):
        raise ValueError(f"atom types must lie in 1..{ntypes}")
    d = lattice.d
    density = mass / (4.0 / 3.0 * math.pi * (0.5 * d) ** 3)
    box = lattice.box.tolist()  # plain floats: repr gives round-trip digits
    lines = [
        f"LAMMPS data file: {lattice.n} particles of diameter {d!r} and mass {mass!r} "
        f"on a {lattice.dim}D close-packed lattice (bonded_lattice)",
        "",
        f"{lattice.n} atoms",
        f"{ntypes} atom types",
        "",
        f"{box[0][0]!r} {box[0][1]!r} xlo xhi",
        f"{box[1][0]!r} {box[1][1]!r} ylo yhi",
        f"{box[2][0]!r} {box[2][1]!r} zlo zhi",
    ]
    if lattice.tilt is not None:
        xy, xz, yz = (float(t) for t in lattice.tilt)
        lines.append(f"{xy!r} {xz!r} {yz!r} xy xz yz")
    lines += [
        "",
    ]
    types, positions = lattice.types.tolist(), lattice.positions.tolist()
    if atom_style == "atomic":
        lines += ["Masses", ""] + [f"{t} {mass!r}" for t in range(1, ntypes + 1)] + [""]
        lines += ["Atoms # atomic", ""]
        body = [f"{k + 1} {t} {x!r} {y!r} {z!r}"
                for k, (t, (x, y, z)) in enumerate(zip(types, positions))]
    else:
        lines += ["Atoms # sphere", ""]
        body = [f"{k + 1} {t} {d!r} {density!r} {x!r} {y!r} {z!r}"
                for k, (t, (x, y, z)) in enumerate(zip(types, positions))]
    if grain is not None:
        body += ["", GRAINS_SECTION, ""]
        if strength is None:
            body += [f"{k + 1} {g} {s!r}"
                     for k, (g, s) in enumerate(zip(grain.tolist(), stiffness.tolist()))]
        else:
            body += [f"{k + 1} {g} {s!r} {f!r}" for k, (g, s, f) in
                     enumerate(zip(grain.tolist(), stiffness.tolist(), strength.tolist()))]
    Path(path).write_text("\n".join(lines + body) + "\n")
