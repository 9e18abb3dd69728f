"""What a section of the validation is: a name in the results file, the runs that make its
data, and the Markdown (with figures) made from that data alone."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from .doc import DocContext
from .runner import Validation

__all__ = ["Section"]


@dataclass(frozen=True)
class Section:
    """name: key in the results file; run: the runs, returning JSON-ready data; doc: that
    data as lines of Markdown (the first a heading) and figures; slow: runs only with
    ``--slow`` (its data stays in the results file otherwise)."""

    name: str
    run: Callable[[Validation], dict]
    doc: Callable[[dict, DocContext], list[str]]
    slow: bool = False
