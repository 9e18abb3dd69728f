"""The sections of docs/validation.md, in the page's order."""

from __future__ import annotations

from .blocks import SERIES, STRAIN, UNITS
from .compression_curve import COMPRESSION_CURVE, COMPRESSION_CURVE_3D
from .elastic_strain import ELASTIC_STRAIN
from .energy import ENERGY
from .friction import CALIBRATION, ENVELOPE
from .maps import FAILURE_MAP
from .schedule import SCHEDULE
from .section import Section

__all__ = ["SECTIONS", "section_names"]

SECTIONS: list[Section] = [UNITS, SERIES, FAILURE_MAP, STRAIN, SCHEDULE, ENERGY, ENVELOPE,
                           CALIBRATION, ELASTIC_STRAIN, COMPRESSION_CURVE, COMPRESSION_CURVE_3D]


def section_names() -> list[str]:
    return [s.name for s in SECTIONS]
