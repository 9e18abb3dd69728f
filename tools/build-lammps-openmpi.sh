#!/usr/bin/env bash
# Build LAMMPS 4 Feb 2025 from Debian's source package with Debian's Open MPI,
# as a shared library with the PLUGIN, BPM, GRANULAR and MOLECULE packages,
# and install it into a cache folder outside the clone, keyed by version:
#
#   ${BONDED_LATTICE_CACHE:-$HOME/.cache/bonded-lattice}/lammps-20250204-openmpi/
#       bin/lmp  lib/liblammps.so*  include/lammps/*.h  lib/cmake/LAMMPS/
#       source/lammps-<version>/    (the unpacked source: src/ headers, python/ module)
#       BUILT                       (stamp: written last, holds the configuration)
#
# A later run finds the stamp and only prints the prefix (last line of output);
# the Open MPI packages are checked (and installed if missing) every time.
#
# The source comes from the Debian release after bookworm (trixie), through
# apt's own source client with a temporary sources list, lists directory and
# cache: nothing under /etc/apt or /var/lib/apt is changed.  Missing build
# tools (openmpi-bin, libopenmpi-dev, cmake, g++, patch, xz-utils) are installed from
# the machine's own apt sources when running as root.
#
# Environment: BONDED_LATTICE_CACHE (cache root), BONDED_LATTICE_JOBS
# (parallel build jobs, default 2), BONDED_LATTICE_DEBIAN_SUITE (default trixie),
# BONDED_LATTICE_DEBIAN_MIRROR (default http://deb.debian.org/debian).
set -euo pipefail

UPSTREAM=20250204                     # LAMMPS "4 Feb 2025"
SUITE=${BONDED_LATTICE_DEBIAN_SUITE:-trixie}
MIRROR=${BONDED_LATTICE_DEBIAN_MIRROR:-http://deb.debian.org/debian}
KEYRING=/usr/share/keyrings/debian-archive-keyring.gpg
JOBS=${BONDED_LATTICE_JOBS:-2}
CACHE=${BONDED_LATTICE_CACHE:-$HOME/.cache/bonded-lattice}
PREFIX=$CACHE/lammps-$UPSTREAM-openmpi
PACKAGES="PLUGIN BPM GRANULAR MOLECULE"

say() { echo "build-lammps-openmpi: $*" >&2; }
die() { say "ERROR: $*"; exit 1; }

# --- tools ------------------------------------------------------------------
need=()
for pkg in openmpi-bin libopenmpi-dev cmake g++ patch xz-utils; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || need+=("$pkg")
done
if (( ${#need[@]} )); then
  if [[ $(id -u) -ne 0 ]]; then
    die "missing Debian packages: ${need[*]}; install them (sudo apt-get install ${need[*]}) and run again"
  fi
  say "installing ${need[*]} from the machine's apt sources"
  apt-get update -q >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${need[@]}" >&2
fi
MPICXX=$(command -v mpicxx.openmpi) || die "mpicxx.openmpi not found after installing libopenmpi-dev"
MPICC=$(command -v mpicc.openmpi) || die "mpicc.openmpi not found after installing libopenmpi-dev"
# the configuration the stamp records; a different one (e.g. another Open MPI) rebuilds
CONFIG="lammps=$UPSTREAM suite=$SUITE mpi=$("$MPICXX" --showme:version 2>&1 | sed -n 's/.*Open MPI \([0-9.]*\).*/openmpi-\1/p') \
packages=$PACKAGES shared=on"

if [[ -f $PREFIX/BUILT ]] && grep -qxF "config: $CONFIG" "$PREFIX/BUILT" \
   && [[ -x $PREFIX/bin/lmp ]]; then
  say "reusing $PREFIX (built $(sed -n 's/^date: //p' "$PREFIX/BUILT"))"
  echo "$PREFIX"
  exit 0
fi

[[ -r $KEYRING ]] || die "$KEYRING (package debian-archive-keyring) is needed to check the $SUITE sources"

# --- source -----------------------------------------------------------------
work=$(mktemp -d "${TMPDIR:-/tmp}/bonded-lattice-apt.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lists/partial" "$work/parts" "$work/cache/archives/partial" "$work/src"
echo "deb-src [signed-by=$KEYRING] $MIRROR $SUITE main" > "$work/sources.list"
# apt downloads as the unprivileged user _apt when it can reach the folders
chmod 755 "$work"
if [[ $(id -u) -eq 0 ]] && id _apt >/dev/null 2>&1; then
  chown _apt "$work/lists/partial" "$work/cache/archives/partial" "$work/src"
fi
APT_OPTS=(-o "Dir::Etc::SourceList=$work/sources.list" -o "Dir::Etc::SourceParts=$work/parts"
          -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache"
          -o "Dir::Cache::pkgcache=" -o "Dir::Cache::srcpkgcache=")
say "reading the $SUITE source index from $MIRROR (temporary apt lists in $work)"
apt-get "${APT_OPTS[@]}" update -q >&2
version=$(apt-cache "${APT_OPTS[@]}" showsrc lammps | sed -n 's/^Version: //p' | grep "^$UPSTREAM" | sort -V | tail -1)
[[ -n $version ]] || die "Debian $SUITE carries no lammps source package of upstream version $UPSTREAM \
(it has: $(apt-cache "${APT_OPTS[@]}" showsrc lammps | sed -n 's/^Version: //p' | tr '\n' ' ')); \
set BONDED_LATTICE_DEBIAN_SUITE to a release that does, or BONDED_LATTICE_DEBIAN_MIRROR to snapshot.debian.org"
# Only the two tarballs are fetched, not the .dsc: some mirrors do not carry the
# .dsc files, and apt checks the tarballs against the SHA256 sums of the signed
# Sources index either way.  They are unpacked as dpkg-source does for a
# "3.0 (quilt)" package: the upstream tarball, debian/ on top, then the patch series.
say "downloading lammps $version (source package: upstream and Debian tarballs)"
t0=$SECONDS
(cd "$work/src" && apt-get "${APT_OPTS[@]}" source -q --tar-only "lammps=$version" >&2 \
                && apt-get "${APT_OPTS[@]}" source -q --diff-only "lammps=$version" >&2)
orig=$(find "$work/src" -maxdepth 1 -name "lammps_*.orig.tar.*" | head -1)
debtar=$(find "$work/src" -maxdepth 1 -name "lammps_*.debian.tar.*" | head -1)
[[ -n $orig && -n $debtar ]] || die "apt-get source left no lammps_*.orig.tar.* and lammps_*.debian.tar.* in $work/src"
say "download: $((SECONDS - t0)) s, $(( $(stat -c %s "$orig") / 1000000 )) MB"
srcdir=$work/src/lammps-$version
mkdir -p "$srcdir"
tar -xf "$orig" -C "$srcdir" --strip-components=1
tar -xf "$debtar" -C "$srcdir"
if [[ -f $srcdir/debian/patches/series ]]; then
  while read -r patchfile _; do
    [[ -z $patchfile || $patchfile == \#* ]] && continue
    patch -d "$srcdir" -p1 -s -N < "$srcdir/debian/patches/$patchfile" >&2 \
      || die "Debian patch $patchfile does not apply to the upstream source"
  done < "$srcdir/debian/patches/series"
fi
[[ -f $srcdir/cmake/CMakeLists.txt ]] || die "the unpacked source in $srcdir has no cmake/CMakeLists.txt"

# --- build ------------------------------------------------------------------
rm -rf "$PREFIX"
mkdir -p "$PREFIX/source"
mv "$srcdir" "$PREFIX/source/"
srcdir=$PREFIX/source/$(basename "$srcdir")
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
pkg_flags=()
for p in $PACKAGES; do pkg_flags+=("-DPKG_$p=on"); done
say "configuring with Open MPI ($MPICXX), packages: $PACKAGES"
t0=$SECONDS
cmake -S "$srcdir/cmake" -B "$work/build" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$PREFIX" -DCMAKE_INSTALL_LIBDIR=lib \
  -DCMAKE_INSTALL_RPATH='$ORIGIN/../lib' \
  -DBUILD_SHARED_LIBS=on -DBUILD_MPI=on -DBUILD_OMP=off -DLAMMPS_SIZES=smallbig \
  -DMPI_CXX_COMPILER="$MPICXX" -DMPI_C_COMPILER="$MPICC" \
  -DWITH_JPEG=off -DWITH_PNG=off -DWITH_FFMPEG=off \
  "${pkg_flags[@]}" >&2
cmake --build "$work/build" -j "$JOBS" >&2
cmake --install "$work/build" >&2
build_s=$((SECONDS - t0))
say "build and install: $build_s s with $JOBS jobs"
# keep of the source what later steps use: src/version.h and python/ (LAMMPS' Python
# module), cmake/, debian/ and the licence; examples, docs, potentials go (400 MB)
find "$srcdir" -mindepth 1 -maxdepth 1 \
  ! -name src ! -name python ! -name cmake ! -name debian ! -name LICENSE ! -name README \
  -exec rm -rf {} +

"$PREFIX/bin/lmp" -h > "$work/lmp-help.txt" || die "$PREFIX/bin/lmp -h failed: $(tail -3 "$work/lmp-help.txt")"
for p in $PACKAGES; do
  grep -qw "$p" "$work/lmp-help.txt" || die "$PREFIX/bin/lmp lacks the $p package (lmp -h)"
done
{
  echo "config: $CONFIG"
  echo "debian: lammps $version from $MIRROR $SUITE"
  echo "build seconds: $build_s"
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
} > "$PREFIX/BUILT"
say "installed in $PREFIX"
echo "$PREFIX"
