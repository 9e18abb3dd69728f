"""Measure E, nu and strength from a test deck's thermo output.

The decks of :mod:`bonded_lattice.decks` print ``v_strain`` (axial strain: a
least-squares slope of all particles' displacements), ``v_lateral`` (the same
for the lateral displacements), ``v_gauge`` (lateral strain of mid-height
gauges on the side faces) and ``v_stress`` (Pa, tension positive).

Poisson's ratio comes from the gauges, as in a laboratory test: the all-particle
fit includes the platens' end zones and the free faces' surface relaxation and
converges slowly (3D: -3.8% at 5461 elements, -2.1% at 37681), while the gauges
are within 1% from about 10^4 elements (docs/validation.md).  Under a constant platen speed the first elastic wave
needs a few crossings to load the block evenly, so the elastic fits skip the
start of the curve.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .runner import Thermo


@dataclass(frozen=True)
class Measured:
    """What a test measured (SI units; strength is positive)."""

    E: float
    nu: float                   # from the mid-height gauges
    strength: float | None      # Tu (tension), Cu (compression), peak axial stress (confined)
    strain_at_peak: float | None
    broken_tension: int
    broken_shear: int
    c_open: float | None = None         # micro-crack onset stress (compression tests)
    first_break: float | None = None    # stress at the first broken bond (strength tests)
    nu_all: float | None = None         # from the all-particle lateral fit


# Micro-cracks have opened (C_open) once this fraction of the initial bonds has
# broken in tension: a few bonds at the boundary break earlier (Liu et al. 2017,
# Fig. 5, point A3), so the very first break would mark a boundary effect.
C_OPEN_FRACTION = 0.01


def crack_onset(stress: np.ndarray, broken_tension: np.ndarray, intact0: float,
                fraction: float = C_OPEN_FRACTION) -> tuple[float | None, float | None]:
    """C_open and the stress at the first break, both positive (None if nothing broke).

    stress: axial stress magnitude; broken_tension: bonds broken in tension so far;
    intact0: bonds at the start.  C_open is the stress at the last row before the
    tension-broken count first exceeds ``fraction`` of the initial bonds, i.e. the
    stress the block carried when its micro-cracks formed.
    """
    broken = np.asarray(broken_tension)
    if broken.max(initial=0) <= 0:
        return None, None
    ifirst = int(np.argmax(broken > 0))
    first = float(stress[max(ifirst - 1, 0)])
    many = broken > fraction * intact0
    if not many.any():
        return None, first
    iopen = int(np.argmax(many))
    return float(stress[max(iopen - 1, 0)]), first


# Elastic windows as fractions of the peak |stress|.  In compression the
# lattice's bonds across the load open at C_open, about a third of Cu
# (Liu 2013 eq. 23: C_open/Tu = 0.75/nu - 1; docs/theory.md), so strength tests fit below a
# quarter of the peak; the elastic test never breaks and uses its whole curve.
STRENGTH_WINDOW = (0.1, 0.25)
ELASTIC_WINDOW = (0.2, 1.0)


def _elastic_window(strain: np.ndarray, stress: np.ndarray,
                    window: tuple[float, float]) -> np.ndarray:
    """Mask of the points with |stress| between the window's fractions of the peak.

    Only the rows before |stress| first exceeds the upper fraction count: once
    micro-cracks open, the stress can fall back into the window at much larger
    strains (3D compression, about 30% of Cu).
    """
    mag = np.abs(stress)
    peak = mag.max()
    lo, hi = window
    above = np.nonzero(mag > hi * peak)[0]
    end = int(above[0]) if len(above) else len(mag)
    idx = np.arange(len(stress))
    return (idx < end) & (mag >= lo * peak) & (strain != 0)


def youngs_modulus(strain: np.ndarray, stress: np.ndarray,
                   window: tuple[float, float] = STRENGTH_WINDOW) -> float:
    """Slope of a straight-line fit of stress against strain in the elastic window."""
    mask = _elastic_window(strain, stress, window)
    if mask.sum() < 3:
        raise ValueError("too few thermo points in the elastic part of the curve: "
                         "print thermo more often or load more slowly")
    slope, _ = np.polyfit(strain[mask], stress[mask], 1)
    return float(slope)


def poisson_ratio(strain: np.ndarray, lateral: np.ndarray, stress: np.ndarray,
                  window: tuple[float, float] = STRENGTH_WINDOW) -> float:
    """-d(lateral strain)/d(axial strain) over the elastic window."""
    mask = _elastic_window(strain, stress, window)
    if mask.sum() < 3:
        raise ValueError("too few thermo points in the elastic part of the curve")
    slope, _ = np.polyfit(strain[mask], lateral[mask], 1)
    return float(-slope)


def plane_strain_from_in_plane(E2: float, nu2: float) -> tuple[float, float]:
    """E and nu of the 2D lattice's formulas from the in-plane (2D) modulus and ratio.

    The 2D conversion formulas (Liu et al. 2013, eq. 14) treat the lattice as a
    slice in plane strain, while a 2D uniaxial test measures the in-plane
    E2 = E/(1-nu^2) and nu2 = nu/(1-nu); this inverts those relations.
    """
    nu = nu2 / (1.0 + nu2)
    return E2 * (1.0 + 2.0 * nu2) / (1.0 + nu2) ** 2, nu


def measure(thermo: Thermo, test: str, dim: int) -> Measured:
    """E, nu and (for strength tests) the peak stress of one test run.

    In 2D, E and nu are returned in the plane-strain convention of the
    conversion formulas (see :func:`plane_strain_from_in_plane`).
    """
    strain, lateral, stress = thermo["v_strain"], thermo["v_lateral"], thermo["v_stress"]
    window = ELASTIC_WINDOW if test == "elastic" else STRENGTH_WINDOW
    if test == "confined":
        # the confinement preloads the block: fit on the axial stress change
        stress = stress - stress[0]
    gauge = thermo.get("v_gauge", lateral)
    E2 = youngs_modulus(strain, stress, window)
    nu = poisson_ratio(strain, gauge, stress, window)
    nu_all = poisson_ratio(strain, lateral, stress, window)
    E = E2
    if dim == 2:
        E, nu = plane_strain_from_in_plane(E2, nu)
        nu_all = plane_strain_from_in_plane(E2, nu_all)[1]
    strength = strain_at_peak = opening = first = None
    if test in ("tension", "compression", "confined"):
        signed = thermo["v_stress"] if test == "tension" else -thermo["v_stress"]
        ipeak = int(np.argmax(signed))
        strength, strain_at_peak = float(signed[ipeak]), float(strain[ipeak])
        # only rows up to the peak: after it the block is falling apart
        upto = slice(0, ipeak + 1)
        opening, first = crack_onset(signed[upto], thermo["c_bonds[2]"][upto],
                                     float(thermo["c_bonds[1]"][0]))
        if test == "tension":
            opening = None   # micro-cracks open in compression; in tension the first break fails it
    return Measured(E=E, nu=nu, strength=strength, strain_at_peak=strain_at_peak,
                    broken_tension=int(thermo["c_bonds[2]"][-1]),
                    broken_shear=int(thermo["c_bonds[3]"][-1]), c_open=opening,
                    first_break=first, nu_all=nu_all)


def coulomb_envelope(sigma3: np.ndarray, sigma1: np.ndarray) -> tuple[float, float]:
    """Cu and mu_i from peak axial stresses of confined tests.

    Fits the Coulomb envelope sigma1 = Cu + q sigma3 (compression positive);
    q = (sqrt(1 + mu_i^2) + mu_i)^2 gives mu_i = (q - 1) / (2 sqrt(q)).
    """
    sigma3, sigma1 = np.asarray(sigma3, float), np.asarray(sigma1, float)
    if len(sigma3) < 2 or np.ptp(sigma3) <= 0:
        raise ValueError("the envelope needs at least two different confining stresses")
    q, cu = np.polyfit(sigma3, sigma1, 1)
    if q <= 1:
        raise ValueError(f"envelope slope q = {q:.4g} <= 1: no internal friction can be fitted")
    return float(cu), float((q - 1) / (2 * np.sqrt(q)))


def elastic_from_dump(dump: str | Path, thermo: Thermo, test: str, dim: int,
                      height_fraction: float = 0.5) -> tuple[float, float]:
    """E and nu from a trajectory dump (read with MDAnalysis) and the platen stress.

    An independent check of :func:`measure`: the strains are least-squares fits of
    the displacements of the middle ``height_fraction`` of the block in every dump
    frame (:func:`bonded_lattice.dumps.strains_from_dump`), the stress is the
    thermo row of the same step.  Frames beyond the elastic window are left out.
    2D values are converted to the plane-strain convention like :func:`measure`.
    """
    from .dumps import strains_from_dump

    strains = strains_from_dump(dump, dim, height_fraction)
    steps = np.asarray(thermo["Step"]).astype(np.int64)
    row = {int(s): i for i, s in enumerate(steps)}
    keep = [k for k, s in enumerate(strains["step"]) if int(s) in row]
    if len(keep) < 3:
        raise ValueError(f"{dump}: fewer than 3 dump frames on thermo steps; dump every "
                         "multiple of the thermo interval")
    idx = np.array([row[int(strains["step"][k])] for k in keep])
    stress = np.asarray(thermo["v_stress"])[idx]
    if test == "confined":
        stress = stress - thermo["v_stress"][0]
    axial = strains["axial"][keep]
    lateral = strains["lateral"][keep]
    window = ELASTIC_WINDOW if test == "elastic" else STRENGTH_WINDOW
    E2 = youngs_modulus(axial, stress, window)
    nu = poisson_ratio(axial, lateral, stress, window)
    if dim == 2:
        return plane_strain_from_in_plane(E2, nu)
    return E2, nu
