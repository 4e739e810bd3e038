#!/usr/bin/env bash
# Builds Tight-Inclusion (Wang et al. 2021, github.com/Continuous-Collision-Detection/Tight-Inclusion)
# from a local snapshot, OUTSIDE this repository, in double and in float, with the driver
# ti_queries.cpp next to this script. An optional benchmark peer: nothing in glcollide's build or
# tests needs it. Nothing is downloaded: TI's CMake fetches Eigen and spdlog with CPM, so this script
# compiles TI's sources with g++ directly against the Debian packages instead.
#
#   bench/peers/tight-inclusion/build.sh SNAPSHOT
#     SNAPSHOT: a Tight-Inclusion source tree (a checkout or an unpacked archive), or a git
#       directory without a work tree (e.g. the `fetch` tool's mirror .../repo; its HEAD is used).
#     Output: $GLCOLLIDE_PEER_DIR/tight-inclusion (default /tmp/glcollide-peers/tight-inclusion):
#       bin/ti_queries_double, bin/ti_queries_float, and source-commit.txt naming what was built.
#
# Debian packages: libeigen3-dev, libspdlog-dev (brings libfmt-dev), libgmp-dev (the driver's
# rationals), g++, pkg-config. Missing ones are installed with apt-get when run as root; otherwise
# the script stops and names them.
#
# Flags: -O3 -DNDEBUG -march=native -std=c++17, as TI's CMake gives its library in a Release build
# (its FindAVX module adds -march=native). Precision: TI's CMake option
# TIGHT_INCLUSION_WITH_DOUBLE_PRECISION (ON: Scalar = double; OFF: Scalar = float, and
# TIGHT_INCLUSION_FLOAT_WITH_DOUBLE_INPUT turns on, giving the double-input entry points its own
# benchmark calls). Here the same two configurations are written into config.hpp by hand.
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 TIGHT_INCLUSION_SNAPSHOT (source tree, or git dir without work tree)" >&2
  exit 2
fi
snapshot=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
out=${GLCOLLIDE_PEER_DIR:-/tmp/glcollide-peers}/tight-inclusion
mkdir -p "$out"

# --- Debian packages -----------------------------------------------------------------------------
missing=()
for pkg in libeigen3-dev libspdlog-dev libfmt-dev libgmp-dev g++ pkg-config; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -ne 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "tight-inclusion: installing ${missing[*]} (Debian packages)" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" >&2
  else
    echo "tight-inclusion: missing Debian packages: ${missing[*]} (apt-get install them as root)" >&2
    exit 1
  fi
fi

# --- the sources ---------------------------------------------------------------------------------
src=$out/src
rm -rf "$src"
mkdir -p "$src"
if [ -d "$snapshot/src/tight_inclusion" ]; then
  cp -r "$snapshot/." "$src/"
  commit=$(git -C "$snapshot" rev-parse HEAD 2>/dev/null || echo "unknown (not a git checkout)")
elif git --git-dir="$snapshot" rev-parse --verify HEAD >/dev/null 2>&1; then
  git --git-dir="$snapshot" archive HEAD | tar -x -C "$src"
  commit=$(git --git-dir="$snapshot" rev-parse HEAD)
else
  echo "tight-inclusion: $snapshot is neither a Tight-Inclusion source tree nor a git directory" >&2
  exit 1
fi
for f in src/tight_inclusion/ccd.cpp src/tight_inclusion/config.hpp.in LICENSE; do
  [ -f "$src/$f" ] || { echo "tight-inclusion: $snapshot has no $f: not a Tight-Inclusion snapshot" >&2; exit 1; }
done
version=$(sed -n 's/^[[:space:]]*VERSION "\([0-9.]*\)".*/\1/p' "$src/CMakeLists.txt" | head -n 1) # project(... VERSION "x.y.z")
printf 'Tight-Inclusion %s, commit %s\n' "${version:-unknown}" "$commit" >"$out/source-commit.txt"
cp "$src/LICENSE" "$out/LICENSE-tight-inclusion"

# TI's logger includes spdlog's bundled fmt; Debian's spdlog uses the system fmt instead.
shim=$out/shim
mkdir -p "$shim/spdlog/fmt/bundled"
echo '#include <fmt/ranges.h> // Debian spdlog: external fmt' >"$shim/spdlog/fmt/bundled/ranges.h"

# config.hpp as TI's configure_file writes it: $1 = the defines to turn on.
write_config() {
  local dir=$1
  shift
  mkdir -p "$dir/tight_inclusion"
  local sed_args=(-e "s/@PROJECT_NAME@/TightInclusion/" -e "s/@PROJECT_VERSION@/${version}/"
    -e "s/@PROJECT_VERSION_MAJOR@/${version%%.*}/" -e "s/@PROJECT_VERSION_MINOR@/$(echo "$version" | cut -d. -f2)/"
    -e "s/@PROJECT_VERSION_PATCH@/$(echo "$version" | cut -d. -f3)/")
  for define in "$@"; do sed_args+=(-e "s|^#cmakedefine $define\$|#define $define|"); done
  sed_args+=(-e 's|^#cmakedefine \(.*\)$|/* #undef \1 */|')
  sed "${sed_args[@]}" "$src/src/tight_inclusion/config.hpp.in" >"$dir/tight_inclusion/config.hpp"
}

# --- compile -------------------------------------------------------------------------------------
flags=(-std=c++17 -O3 -DNDEBUG -march=native -DNOMINMAX)
read -r -a spdlog_flags <<<"$(pkg-config --cflags spdlog)"
read -r -a spdlog_libs <<<"$(pkg-config --libs spdlog)"
mkdir -p "$out/bin"
for precision in double float; do
  cfg=$out/config-$precision
  if [ "$precision" = double ]; then
    write_config "$cfg" TIGHT_INCLUSION_WITH_DOUBLE_PRECISION
  else
    write_config "$cfg" TIGHT_INCLUSION_FLOAT_WITH_DOUBLE_INPUT
  fi
  obj=$out/obj-$precision
  mkdir -p "$obj"
  includes=(-I"$cfg" -I"$shim" -I"$src/src" -I/usr/include/eigen3 "${spdlog_flags[@]}")
  objects=()
  for unit in avx ccd interval interval_root_finder logger; do
    echo "tight-inclusion: compiling $unit.cpp ($precision)" >&2
    g++ "${flags[@]}" "${includes[@]}" -c "$src/src/tight_inclusion/$unit.cpp" -o "$obj/$unit.o"
    objects+=("$obj/$unit.o")
  done
  echo "tight-inclusion: linking bin/ti_queries_$precision" >&2
  g++ "${flags[@]}" "${includes[@]}" -DTI_QUERIES_PRECISION="\"$precision\"" "$here/ti_queries.cpp" "${objects[@]}" \
    -o "$out/bin/ti_queries_$precision" "${spdlog_libs[@]}" -lgmpxx -lgmp
done
echo "tight-inclusion: built $out/bin/ti_queries_double and $out/bin/ti_queries_float ($(cat "$out/source-commit.txt"))"
