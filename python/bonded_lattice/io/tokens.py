"""Tokens of the text readers: numbers, integers and errors that name the file and line."""

from __future__ import annotations

import math
import re
from pathlib import Path


def line_error(path: str | Path, line: int, text: str) -> ValueError:
    """A ``ValueError`` whose message starts with the file and the line."""
    return ValueError(f"{path}, line {line}: {text}")


def parse_numbers(tokens: list[str], path: str | Path, line: int, what: str) -> list[float]:
    """The tokens as finite floats, or a :func:`line_error` about ``what``."""
    try:
        values = [float(t) for t in tokens]
    except ValueError:
        raise line_error(path, line, f"{what}: {' '.join(tokens)!r} are not all numbers") from None
    if not all(math.isfinite(v) for v in values):
        raise line_error(path, line, f"{what}: {' '.join(tokens)!r} contains a non-finite number")
    return values


def parse_integers(tokens: list[str], path: str | Path, line: int, what: str) -> list[int]:
    """The tokens as integers >= 0, or a :func:`line_error` about ``what``."""
    if not all(re.fullmatch(r"[0-9]+", t) for t in tokens):
        raise line_error(path, line, f"{what}: {' '.join(tokens)!r} are not all integers >= 0")
    return [int(t) for t in tokens]


def is_number(token: str) -> bool:
    """Whether the token reads as a float."""
    try:
        float(token)
    except ValueError:
        return False
    return True
