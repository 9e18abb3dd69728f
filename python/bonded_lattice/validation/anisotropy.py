"""Section ``anisotropy``: E, nu, Tu and Cu against the lattice's orientation to the load.

Liu et al. (2013, para. 55) validate the conversion formulas with the load at 90 degrees to
the close-packed rows (and, by the unit's symmetry, at 30 and 150 degrees) and report that
"E and Tu are a bit lower along other directions".  This section measures the dependence:

- 2D: the papers' block (N particles across) with its lattice turned by 0 to 30 degrees
  (:func:`bonded_lattice.lattice.block_2d`; the lattice repeats every 60 degrees and has
  mirror planes at 0 and 30, so 0-30 covers every direction), plus one angle outside that
  range whose mirror image lies inside it, as a measured check of the range;
- 3D: the 2017 paper's block loaded across its close-packed layers (orientation 0) and
  along its close-packed rows (orientation 90, :func:`bonded_lattice.lattice.turned_block_3d`).

A turned lattice has stepped ends, which the papers' platens would touch at a few
particles only, so every run here holds the end layers (``ends="layers"``,
:func:`bonded_lattice.experiment.choose_ends`); the papers' orientation is also run with
the papers' platens, to show what the choice of ends changes there.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..conversion import rock_to_bond
from ..experiment import build_lattice, end_band_particles, end_contacts
from ..lattice import LAYER_SPACING
from ..periodic import paper_cell, periodic_cell, stiffness_matrix
from ..plotting import damaged_particles
from .anisotropy_doc import anisotropy_doc
from .runner import Validation, rock_for
from .section import Section

__all__ = ["ANGLES_2D", "ANISOTROPY", "MIRROR_2D", "SIZES_2D", "SIZE_3D", "affine_tu_2d",
           "end_damage_fraction", "lattice_direction", "mirror_angle"]

# the study's orientations: 2D every 5 degrees over one symmetry interval, 3D two axes
ANGLES_2D = (0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0)
# outside 0-30: its mirror image inside (the lattice's period is 60 degrees, mirror planes
# at 0 and 30), as a measured check that 0-30 covers every direction
MIRROR_2D = 40.0
ORIENTATIONS_3D = (0.0, 90.0)
# 15 particles across (247 at 0 degrees): the smallest of the papers' blocks whose E at the
# papers' orientation is within 0.2% of the formula and whose Tu and Cu are within 1 and 1.5
# points of the larger blocks' (the series section); N = 4 and 8 are still in the
# small-size regime.  30 (1033 particles) repeats the sweep to show how much of the
# orientation dependence is the block's edges (it shrinks with size if so).
SIZES_2D = (15, 30)
# 3D: 8 elements along y, 580 elements (the largest within this study's run budget)
SIZE_3D = 8
TESTS = ("elastic", "tension", "compression")
D = 1.0e-3   # the runs' particle diameter (RockTest's default)
PROPERTIES = {"E": "elastic", "nu": "elastic", "Tu": "tension", "Cu": "compression"}


def mirror_angle(angle: float) -> float:
    """The angle in [0, 30] with the same lattice up to a mirror image: the hexagonal
    lattice repeats every 60 degrees and is symmetric about 0 and 30."""
    a = math.fmod(angle, 60.0)
    a = a + 60.0 if a < 0 else a
    return a if a <= 30.0 else 60.0 - a


def lattice_direction(angle: float) -> float:
    """The loading direction in the 2013 paper's lattice frame (degrees from its rows, in
    [0, 180)) for a 2D lattice turned by ``angle`` (our load is along y, 90 degrees from
    the x axis; the rows are at ``angle`` from x)."""
    return math.fmod(math.fmod(90.0 - angle, 180.0) + 180.0, 180.0)


def affine_tu_2d(angle: float, E: float, nu: float, Xb: float, d: float) -> float:
    """Tensile strength of an unbounded 2D lattice turned by ``angle`` degrees (load along
    y): the uniaxial stress at which the most stretched bond reaches ``Xb``.

    A perfect lattice deforms affinely (every particle is a centre of symmetry), so under
    the stress s the bond at phi degrees from x stretches by d s (sin^2 phi - nu cos^2 phi)
    / E; the bonds lie at angle, angle + 60 and angle + 120 degrees.  A ValueError names a
    bad E, nu, Xb or d.
    """
    for name, value in (("E", E), ("Xb", Xb), ("d", d)):
        if not (value > 0 and math.isfinite(value)):
            raise ValueError(f"{name} = {value} is out of range: need 0 < {name} < inf")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu = {nu} is out of range: need -1 < nu < 0.5")
    phi = np.radians(angle + np.array([0.0, 60.0, 120.0]))
    stretch = float(np.max(np.sin(phi) ** 2 - nu * np.cos(phi) ** 2))
    return E * Xb / (d * stretch)


def bulk_3d_elastic(E: float, nu: float, Tu: float, Cu: float, mu_i: float) -> dict:
    """E and nu of an unbounded face-centred cubic lattice with the 3D bonds of a rock
    (:func:`bonded_lattice.periodic.stiffness_matrix`; the same bonds' angles to the layers
    as the paper's hcp, which is not a Bravais lattice), relative to the rock's: loaded
    across the close-packed layers and along a close-packed row (the mean of the two
    lateral Poisson's ratios, in the layer and across it)."""
    bond = rock_to_bond(E, nu, Tu, Cu, mu_i, D, 3)
    S = np.linalg.inv(stiffness_matrix(periodic_cell(3, D, paper_cell(3, 4)), bond.Kn,
                                       bond.Ks))
    # paper_cell: rows along x, layers in xy, z across them
    return {"E_across_layers": 1.0 / S[2, 2] / E - 1.0,
            "nu_across_layers": -0.5 * (S[0, 2] + S[1, 2]) / S[2, 2] / nu - 1.0,
            "E_along_rows": 1.0 / S[0, 0] / E - 1.0,
            "nu_along_rows": -0.5 * (S[1, 0] + S[2, 0]) / S[0, 0] / nu - 1.0}


def end_damage_fraction(folder: Path, dim: int, d: float, reach: float = 2.0) -> float | None:
    """Of the particles that lost bonds in a strength run, the fraction whose centres lie
    within ``reach`` diameters of either end along the loading axis (None without damage
    or without the run's dumps)."""
    if not (folder / "dump.initial").exists() or not (folder / "dump.final").exists():
        return None
    damage = damaged_particles(folder / "dump.initial", folder / "dump.final", dim)
    h = np.array(damage["y"])
    if len(h) == 0:
        return None
    lo, hi = damage["bounds"][2], damage["bounds"][3]
    near = (h <= lo + reach * d) | (h >= hi - reach * d)
    return float(np.count_nonzero(near) / len(h))


def _set(v: Validation, dim: int, n: int, orientation: float, ends: str) -> dict:
    """The three tests of one block and orientation; the row of the section's table."""
    rock = rock_for(dim)
    tag = f"{dim}d/aniso_n{n}_o{orientation:g}_{ends}"
    runs = {test: v.run(f"{tag}_{test}", rock, dim, test, n, orientation=orientation,
                        ends=ends)
            for test in TESTS}
    lattice = build_lattice(dim, n, D, orientation)
    errors = {p: runs[test]["relative_error"][p] for p, test in PROPERTIES.items()}
    near_ends = {p: end_damage_fraction(v.folder(f"{tag}_{test}"), dim, lattice.d)
                 for p, test in PROPERTIES.items() if test != "elastic"}
    measured = {p: runs[test]["measured"][p] for p, test in PROPERTIES.items()}
    return {"dim": dim, "n": n, "orientation_deg": orientation, "ends": ends,
            "particles": runs["elastic"]["particles"],
            "end_band_particles": end_band_particles(lattice),
            "end_contacts": end_contacts(lattice),
            # the stress area: width (2D) or area (3D) between the outer centres, in d^(dim-1)
            "loaded_area_d": lattice.loaded_area() / lattice.d ** (dim - 1),
            "height_d": lattice.height / lattice.d,
            "relative_error": errors, "measured": measured,
            "damage_near_ends": near_ends, "runs": runs}


def _spread(rows: list[dict]) -> dict:
    """Per property: the range of the errors over ``rows`` and the angles of its ends."""
    out = {}
    for p in PROPERTIES:
        errs = [r["relative_error"][p] for r in rows]
        lo, hi = min(errs), max(errs)
        out[p] = {"min": lo, "max": hi, "spread": hi - lo,
                  "min_at_deg": rows[errs.index(lo)]["orientation_deg"],
                  "max_at_deg": rows[errs.index(hi)]["orientation_deg"],
                  "below_papers": sum(e < rows[0]["relative_error"][p] for e in errs[1:])}
    return out


def anisotropy_run(v: Validation) -> dict:
    """Every run of the section and the numbers its text quotes."""
    data: dict = {"angles_2d": list(ANGLES_2D), "mirror_2d": MIRROR_2D,
                  "mirror_of": mirror_angle(MIRROR_2D), "sizes_2d": list(SIZES_2D),
                  "size_3d": SIZE_3D, "tests": list(TESTS), "two_d": {}, "three_d": {}}
    rock = rock_for(2)
    bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, D, 2)
    data["affine_Tu_error_curve"] = {
        "angle_deg": [float(a) for a in range(0, 31)],
        "error": [affine_tu_2d(float(a), rock.E, rock.nu, bond.Xb, D) / rock.Tu - 1.0
                  for a in range(0, 31)]}
    for n in SIZES_2D:
        rows = [_set(v, 2, n, a, "layers") for a in ANGLES_2D]
        mirror = _set(v, 2, n, MIRROR_2D, "layers")
        platens = _set(v, 2, n, 0.0, "platens")
        for r in rows + [mirror, platens]:
            r["lattice_direction_deg"] = lattice_direction(r["orientation_deg"])
            r["affine_Tu_error"] = affine_tu_2d(r["orientation_deg"], rock.E, rock.nu, bond.Xb,
                                                D) / rock.Tu - 1.0
        inside = next(r for r in rows if r["orientation_deg"] == mirror_angle(MIRROR_2D))
        along = next(r for r in rows if r["orientation_deg"] == 30.0)
        data["two_d"][str(n)] = {
            # at 30 degrees the side columns are straight chains along the load: half a
            # column spacing (sqrt3/2 d between columns) outside each outer centre carries load
            "side_columns_over_width": 0.5 * math.sqrt(3.0) / along["loaded_area_d"],
            "rows": rows, "mirror": mirror, "papers_platens": platens,
            "spread": _spread(rows),
            "mirror_difference": {p: mirror["relative_error"][p] - inside["relative_error"][p]
                                  for p in PROPERTIES},
            "platens_minus_layers": {p: platens["relative_error"][p]
                                     - rows[0]["relative_error"][p] for p in PROPERTIES}}
    rows3 = [_set(v, 3, SIZE_3D, o, "layers") for o in ORIENTATIONS_3D]
    platens3 = _set(v, 3, SIZE_3D, 0.0, "platens")
    rock3 = rock_for(3)
    turned = build_lattice(3, SIZE_3D, D, 90.0)
    ext = (turned.bounds[:2, 1] - turned.bounds[:2, 0]) / D
    data["three_d"] = {
        "bulk_fcc": bulk_3d_elastic(rock3.E, rock3.nu, rock3.Tu, rock3.Cu, rock3.mu_i),
        # orientation 90: the side faces are row planes (x, sqrt3/2 d apart) and layers (y,
        # sqrt(2/3) d apart) of straight chains along the load; with half a spacing outside
        # each outer centre the load-bearing area exceeds the one between the outer centres
        "side_chains_area": (ext[0] + 0.5 * math.sqrt(3.0)) * (ext[1] + LAYER_SPACING)
        / (ext[0] * ext[1]) - 1.0,
        "rows": rows3, "papers_platens": platens3,
        "rows_minus_layers": {p: rows3[1]["relative_error"][p] - rows3[0]["relative_error"][p]
                              for p in PROPERTIES},
        "platens_minus_layers": {p: platens3["relative_error"][p]
                                 - rows3[0]["relative_error"][p] for p in PROPERTIES}}
    return data


ANISOTROPY = Section("anisotropy", anisotropy_run, anisotropy_doc)
