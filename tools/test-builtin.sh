#!/usr/bin/env bash
# The built-in leg: BONDED_LATTICE compiled into LAMMPS 4 Feb 2025 (Debian's
# source, Open MPI) through cmake/bonded_lattice_builtin.cmake, in both
# configurations of tools/build-lammps-builtin.sh (cached):
#
#   shared   liblammps.so with the PLUGIN package: the Python module's LAMMPS
#   static   a static lmp without the PLUGIN package: the decks' `lmp`
#
# Checks, then the test suite with BONDED_LATTICE_BUILT_IN=1
#   - the package's sources compile against LAMMPS' serial MPI stubs (a LAMMPS built
#     without MPI; compile only); (so that
# tests/integration/test_plugin_loads.py expects compiled-in styles):
#   - 400 steps of inputs/in.tension2d on 2 ranks give the same thermo output with
#     the static and the shared built-in LAMMPS, and with the plugin in the same
#     LAMMPS release (the Open MPI leg's LAMMPS and plugin);
#   - `plugin load` of that plugin into the shared built-in LAMMPS registers
#     nothing and warns, and the run uses the compiled-in styles.
#
#   tools/test-builtin.sh [pytest arguments]      (default: the fast suite)
#
# Creates .venv-builtin and build/builtin-plugin in the clone.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
JOBS=${BONDED_LATTICE_JOBS:-2}
say() { echo "test-builtin: $*" >&2; }
die() { say "ERROR: $*"; exit 1; }

# nothing of a wheel environment that may be active (its lmp, mpirun, mpicxx)
if [[ -n ${VIRTUAL_ENV:-} ]]; then
  PATH=$(tr ':' '\n' <<< "$PATH" | grep -vxF "$VIRTUAL_ENV/bin" | paste -sd: -)
  unset VIRTUAL_ENV PYTHONHOME
fi
unset LAMMPS_PLUGIN_PATH

t0=$SECONDS
shared=$(tools/build-lammps-builtin.sh shared | tail -1)
static=$(tools/build-lammps-builtin.sh static | tail -1)
[[ -x $shared/lmp && -f $shared/liblammps.so ]] || die "no shared built-in LAMMPS in '$shared'"
[[ -x $static/lmp ]] || die "no static built-in LAMMPS in '$static'"
say "built-in LAMMPS ready in $((SECONDS - t0)) s: $shared, $static"

# the package's sources against LAMMPS' serial MPI stubs, as a LAMMPS built without MPI
# compiles them (compile only, a few seconds): the stubs reject what MPI accepts, such as
# a const send buffer; with the configuration header of the static build
src_tree=$(find "$(tools/build-lammps-openmpi.sh | tail -1)/source" -mindepth 1 -maxdepth 1 -type d -name "lammps-*" | head -1)
stubs_log=build/builtin-stubs.log
mkdir -p build
find src/BONDED_LATTICE -name "*.cpp" ! -name bonded_lattice_plugin.cpp -print0 \
  | xargs -0 -P "$JOBS" -I{} g++ -std=c++17 -fsyntax-only -fopenmp -DLAMMPS_SMALLBIG \
      -I"$static/bonded_lattice" -I"$static/bonded_lattice/OPENMP" -I"$src_tree/src" \
      -I"$src_tree/src/OPENMP" -I"$src_tree/src/STUBS" {} > "$stubs_log" 2>&1 \
  || { grep -m5 "error" "$stubs_log" >&2; die "the package does not compile against LAMMPS' MPI stubs (see $stubs_log)"; }
say "the package's sources compile against LAMMPS' serial MPI stubs"

# the plugin in the same LAMMPS release (the Open MPI leg's LAMMPS), for comparison
openmpi=$(tools/build-lammps-openmpi.sh | tail -1)
src=$(find "$openmpi/source" -mindepth 1 -maxdepth 1 -type d -name "lammps-*" | head -1)
mpicxx=$(command -v mpicxx.openmpi)
mpirun=$(command -v mpirun.openmpi)
mkdir -p build
log=build/builtin-plugin.log
{ cmake -S . -B build/builtin-plugin -DCMAKE_BUILD_TYPE=Release -DMPI_CXX_COMPILER="$mpicxx" \
        -DLAMMPS_HEADER_DIR="$openmpi/include/lammps" -DLAMMPS_LIBRARY="$openmpi/lib/liblammps.so" \
  && cmake --build build/builtin-plugin -j "$JOBS"; } > "$log" 2>&1 \
  || { tail -30 "$log" >&2; die "the plugin build against $openmpi failed (see $log)"; }
plugin=$repo/build/builtin-plugin/bondedlatticeplugin.so

if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMP_NUM_THREADS=1

work=$(mktemp -d "${TMPDIR:-/tmp}/bonded-lattice-builtin.XXXXXX")
trap 'rm -rf "$work"' EXIT
run_with() {   # run_with <name> <LD_LIBRARY_PATH> <lmp> [deck lines]
  local name=$1 libs=$2 lmp=$3
  shift 3
  mkdir -p "$work/$name"
  { printf '%s\n' "$@"; echo "include $repo/inputs/in.tension2d"; } > "$work/$name/in.deck"
  (cd "$work/$name" && env LD_LIBRARY_PATH="$libs" "$mpirun" --oversubscribe -np 2 "$lmp" \
      -in in.deck -log none -var steps 400 -var thermoevery 20 -var dumpevery 400 > out.txt 2>&1) \
    || { tail -20 "$work/$name/out.txt" >&2; die "the $name run failed"; }
  grep -q "^Loop time of .* on 2 procs for 400 steps" "$work/$name/out.txt" \
    || { tail -20 "$work/$name/out.txt" >&2; die "the $name run did not reach its end"; }
  sed -n '/^ *Step /,/^Loop time/p' "$work/$name/out.txt" | grep -v "^Loop time" > "$work/$name/thermo.txt"
  [[ -s $work/$name/thermo.txt ]] || die "the $name run printed no thermo table"
}
run_with static "" "$static/lmp" "bonded_lattice"
grep -q "compiled into LAMMPS" "$work/static/out.txt" || die "the static lmp's bonded_lattice command did not report the built-in mode"
run_with shared "$shared" "$shared/lmp"
run_with plugin "$openmpi/lib" "$openmpi/bin/lmp" "plugin load $plugin"
run_with both "$shared" "$shared/lmp" "plugin load $plugin" "bonded_lattice"
grep -q "BONDED_LATTICE is compiled into this LAMMPS: its styles are used and the plugin" "$work/both/out.txt" \
  || { tail -20 "$work/both/out.txt" >&2; die "plugin load into the built-in LAMMPS did not warn"; }
grep -q "compiled into LAMMPS" "$work/both/out.txt" || die "after plugin load the built-in command is gone"
# the same thermo output, and the same positions to the bit (the dump of step 400, %.17g)
for name in shared plugin both; do
  cmp -s "$work/static/thermo.txt" "$work/$name/thermo.txt" \
    || { diff "$work/static/thermo.txt" "$work/$name/thermo.txt" | head -10 >&2
         die "inputs/in.tension2d: the thermo output of the $name run differs from the static built-in run"; }
  cmp -s "$work/static/dump.tension2d.400" "$work/$name/dump.tension2d.400" \
    || die "inputs/in.tension2d: the positions at step 400 of the $name run differ from the static built-in run"
done
say "inputs/in.tension2d, 400 steps on 2 ranks: the same thermo output ($(($(wc -l < "$work/static/thermo.txt") - 1)) rows) and the same positions to the bit, built in (static, shared), as the plugin, and with the plugin loaded into the built-in LAMMPS (warned, not registered)"

t0=$SECONDS
tools/source-venv.sh .venv-builtin "$src"
# shellcheck disable=SC1091
. .venv-builtin/bin/activate
say "Python environment in $((SECONDS - t0)) s"

# the suite: the Python module runs the shared build, the decks the static lmp
export PYTHONPATH=$repo/python${PYTHONPATH:+:$PYTHONPATH}
export LD_LIBRARY_PATH=$shared${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export BONDED_LATTICE_LMP=$static/lmp
export BONDED_LATTICE_MPIRUN="$mpirun --oversubscribe"
export BONDED_LATTICE_BUILT_IN=1
t0=$SECONDS
python -m pytest "$@"
say "test suite in $((SECONDS - t0)) s"
