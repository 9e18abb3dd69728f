"""The sections of docs/validation.md, in the page's order."""

from __future__ import annotations

from .anisotropy import ANISOTROPY
from .blocks import SERIES, UNITS
from .compression_curve import COMPRESSION_CURVE, COMPRESSION_CURVE_3D
from .elastic_strain import ELASTIC_STRAIN
from .energy import ENERGY
from .friction import CALIBRATION, ENVELOPE
from .grips import GRIPS
from .ladder import LADDER
from .loading import LOADING_3D
from .maps import FAILURE_MAP
from .platen_strain import PLATEN_STRAIN
from .platens import PLATENS
from .section import Section

__all__ = ["SECTIONS", "section_names"]

SECTIONS: list[Section] = [UNITS, SERIES, LADDER, PLATENS, GRIPS, PLATEN_STRAIN, LOADING_3D, FAILURE_MAP, COMPRESSION_CURVE,
                           COMPRESSION_CURVE_3D, ELASTIC_STRAIN, ENERGY, ENVELOPE,
                           CALIBRATION, ANISOTROPY]


def section_names() -> list[str]:
    return [s.name for s in SECTIONS]
