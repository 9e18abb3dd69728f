#!/usr/bin/env bash
# Build LAMMPS 4 Feb 2025 (Debian's source, Open MPI) with BONDED_LATTICE compiled
# in (cmake/bonded_lattice_builtin.cmake), in one of two configurations:
#
#   tools/build-lammps-builtin.sh shared   liblammps.so + lmp, with the PLUGIN package
#   tools/build-lammps-builtin.sh static   liblammps.a, a static lmp, no PLUGIN package
#
# Both have BPM, GRANULAR, MOLECULE and OPENMP (with OpenMP threads).  The build
# folder is kept in the cache folder, keyed by LAMMPS version, MPI and configuration:
#
#   ${BONDED_LATTICE_CACHE:-$HOME/.cache/bonded-lattice}/lammps-20250204-builtin-<kind>/
#       build/      LAMMPS' CMake build folder: build/lmp, build/liblammps.so (shared)
#       BUILT       the configuration of the build folder
#
# The first run builds all of LAMMPS; a later run re-runs CMake and the build,
# so only the package's changed files are compiled and LAMMPS is re-linked.  The
# last line of output is the build folder.  The source comes from
# tools/build-lammps-openmpi.sh (which also checks the Open MPI packages).
#
# Environment: BONDED_LATTICE_CACHE, BONDED_LATTICE_JOBS (default 2), and those
# of tools/build-lammps-openmpi.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
say() { echo "build-lammps-builtin: $*" >&2; }
die() { say "ERROR: $*"; exit 1; }

kind=${1:-}
case $kind in
  shared) packages="PLUGIN BPM GRANULAR MOLECULE OPENMP"; shared=on ;;
  static) packages="BPM GRANULAR MOLECULE OPENMP"; shared=off ;;
  *) die "usage: tools/build-lammps-builtin.sh shared|static (got '${kind}')" ;;
esac
JOBS=${BONDED_LATTICE_JOBS:-2}
CACHE=${BONDED_LATTICE_CACHE:-$HOME/.cache/bonded-lattice}
UPSTREAM=20250204
dir=$CACHE/lammps-$UPSTREAM-builtin-$kind
build=$dir/build

# the source (and Open MPI), from the cached Open MPI build
openmpi=$(tools/build-lammps-openmpi.sh | tail -1)
src=$(find "$openmpi/source" -mindepth 1 -maxdepth 1 -type d -name "lammps-*" | head -1)
[[ -f $src/cmake/CMakeLists.txt ]] || die "no LAMMPS source with cmake/CMakeLists.txt in $openmpi/source"
MPICXX=$(command -v mpicxx.openmpi) || die "mpicxx.openmpi not found"
MPICC=$(command -v mpicc.openmpi) || die "mpicc.openmpi not found"

CONFIG="lammps=$(basename "$src") mpi=$("$MPICXX" --showme:version 2>&1 | sed -n 's/.*Open MPI \([0-9.]*\).*/openmpi-\1/p') \
packages=$packages shared=$shared omp=on"
mkdir -p "$dir"
# one build at a time in this folder (two clones may run CI at once)
exec 9> "$dir/lock"
flock 9
if [[ -f $dir/BUILT ]] && grep -qxF "config: $CONFIG" "$dir/BUILT" && [[ -d $build ]]; then
  say "updating the $kind build in $build (built first $(sed -n 's/^first: //p' "$dir/BUILT"))"
  first=$(sed -n 's/^first: //p' "$dir/BUILT")
else
  say "building LAMMPS $UPSTREAM with BONDED_LATTICE compiled in ($kind: $packages) in $build"
  rm -rf "$build" "$dir/BUILT"
  first=$(date -u +%Y-%m-%dT%H:%M:%SZ)
fi

pkg_flags=()
for p in $packages; do pkg_flags+=("-DPKG_$p=on"); done
log=$dir/cmake.log
t0=$SECONDS
# configure when the folder is new or the checkout moved; otherwise the build itself
# re-runs CMake when one of its inputs changed (a header or source file added or
# removed, cmake/*.cmake edited)
if [[ ! -f $build/CMakeCache.txt ]] || ! grep -qxF "repo: $repo" "$dir/BUILT" 2>/dev/null; then
  [[ -f $dir/BUILT ]] && sed -i '/^repo: /d' "$dir/BUILT"    # written again on success
  generator=()
  [[ -f $build/CMakeCache.txt ]] || { command -v ninja >/dev/null && generator=(-G Ninja); }
  cmake -S "$src/cmake" -B "$build" "${generator[@]}" \
    -DCMAKE_PROJECT_lammps_INCLUDE="$repo/cmake/bonded_lattice_builtin.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=$shared -DBUILD_MPI=on -DBUILD_OMP=on \
    -DLAMMPS_SIZES=smallbig -DMPI_CXX_COMPILER="$MPICXX" -DMPI_C_COMPILER="$MPICC" \
    -DWITH_JPEG=off -DWITH_PNG=off -DWITH_FFMPEG=off -Wno-dev -Wno-deprecated \
    "${pkg_flags[@]}" > "$log" 2>&1 || { tail -30 "$log" >&2; die "CMake failed (whole output in $log)"; }
  grep -q "BONDED_LATTICE .*: compiled into LAMMPS" "$log" \
    || die "CMake did not read cmake/bonded_lattice_builtin.cmake (see $log)"
fi
cmake --build "$build" -j "$JOBS" > "$dir/build.log" 2>&1 \
  || { grep -B2 -A12 -m3 "error" "$dir/build.log" >&2 || tail -30 "$dir/build.log" >&2
       die "the build failed (whole output in $dir/build.log)"; }
say "CMake and build: $((SECONDS - t0)) s with $JOBS jobs"

"$build/lmp" -h > "$dir/lmp-help.txt" 2>&1 || die "$build/lmp -h failed: $(tail -3 "$dir/lmp-help.txt")"
grep -qw "lattice/bond" "$dir/lmp-help.txt" || die "$build/lmp lacks pair style lattice/bond (lmp -h)"
for p in BONDED_LATTICE $packages; do
  grep -qw "$p" "$dir/lmp-help.txt" || die "$build/lmp lacks the $p package (lmp -h)"
done
if [[ $shared == off ]]; then
  ldd "$build/lmp" | grep -q liblammps && die "$build/lmp links a shared liblammps: not a static build"
fi
{
  echo "config: $CONFIG"
  echo "first: $first"
  echo "repo: $repo"
  echo "updated: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
} > "$dir/BUILT"
echo "$build"
