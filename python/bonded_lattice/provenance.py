"""Where a result comes from: the commit of the checkout and the machine it ran on.

Benchmarks and generated documents print these next to their numbers.
"""

from __future__ import annotations

import os
import platform
import subprocess
from pathlib import Path

__all__ = ["git_commit", "machine"]


def git_commit(root: str | Path, mark_changes: bool = False) -> str:
    """Short hash of the commit checked out in ``root`` ("unknown" outside git).

    With ``mark_changes`` a ``+`` is appended when tracked files differ from it.
    """
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, text=True,
                              capture_output=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    if mark_changes:
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=root, text=True, capture_output=True).stdout.strip()
        head += "+" if dirty else ""
    return head


def machine(load: bool = False) -> str:
    """CPU model, core count and system; with ``load`` also the load average now."""
    model = platform.processor() or "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    text = f"{model}, {os.cpu_count()} cores, {platform.system()} {platform.machine()}"
    if load and hasattr(os, "getloadavg"):
        text += "; load average " + ", ".join(f"{x:.2f}" for x in os.getloadavg())
    return text
