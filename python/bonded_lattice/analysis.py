"""Measure E, nu and strength from a test deck's thermo output.

The decks of :mod:`bonded_lattice.decks` print ``v_strain`` (axial strain from
the particles' extent), ``v_lateral`` (lateral strain) and ``v_stress``
(Pa, tension positive).  Under a constant platen speed the first elastic wave
needs a few crossings to load the block evenly, so the elastic fits skip the
start of the curve.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .runner import Thermo


@dataclass(frozen=True)
class Measured:
    """What a test measured (SI units; strength is positive)."""

    E: float
    nu: float
    strength: float | None      # Tu (tension), Cu (compression), peak axial stress (confined)
    strain_at_peak: float | None
    broken_tension: int
    broken_shear: int


# Elastic windows as fractions of the peak |stress|.  In compression the
# lattice's bonds across the load open at C_open, about a third of Cu
# (REFERENCE.md: C_open/Tu = 0.75/nu - 1), so strength tests fit below a
# quarter of the peak; the elastic test never breaks and uses its whole curve.
STRENGTH_WINDOW = (0.1, 0.25)
ELASTIC_WINDOW = (0.2, 1.0)


def _elastic_window(strain: np.ndarray, stress: np.ndarray,
                    window: tuple[float, float]) -> np.ndarray:
    """Mask of the points with |stress| between the window's fractions of the peak, before it."""
    mag = np.abs(stress)
    ipeak = int(np.argmax(mag))
    peak = mag[ipeak]
    idx = np.arange(len(stress))
    lo, hi = window
    return (idx <= ipeak) & (mag >= lo * peak) & (mag <= hi * peak) & (strain != 0)


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
    E = youngs_modulus(strain, stress, window)
    nu = poisson_ratio(strain, lateral, stress, window)
    if dim == 2:
        E, nu = plane_strain_from_in_plane(E, nu)
    strength = strain_at_peak = None
    if test in ("tension", "compression", "confined"):
        signed = thermo["v_stress"] if test == "tension" else -thermo["v_stress"]
        ipeak = int(np.argmax(signed))
        strength, strain_at_peak = float(signed[ipeak]), float(strain[ipeak])
    return Measured(E=E, nu=nu, strength=strength, strain_at_peak=strain_at_peak,
                    broken_tension=int(thermo["c_bonds[2]"][-1]),
                    broken_shear=int(thermo["c_bonds[3]"][-1]))


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
