#!/usr/bin/env bash
# Installs a glcollide build into a fresh prefix, then configures, builds and runs the consumer
# project in tests/install/consumer against it: the package is relocatable, find_package(glcollide)
# finds every dependency, the public headers stand alone, and the result runs.
# usage: consumer_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/glcollide-install.XXXXXX") # removed on success, kept after a failure
prefix="$work/prefix"
step() { echo "== $*"; }
fail() { echo "FAIL: $* (files kept in $work)" >&2; exit 1; }

# The consumer is compiled like the libraries were (same compiler and flags: an ASan build's
# libraries need -fsanitize at link time too), with warnings as errors on its own code.
cache() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
cxx=$(cache CMAKE_CXX_COMPILER)
cxx_flags=$(cache CMAKE_CXX_FLAGS)
build_type=$(cache CMAKE_BUILD_TYPE)

step "install into $prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { cat "$work/install.log"; fail "cmake --install"; }

step "check the installed tree"
config=$(find "$prefix" -name glcollideConfig.cmake -printf '%h\n' | head -n 1)
test -n "$config" || fail "no glcollideConfig.cmake under $prefix"
libdir=$(dirname "$(dirname "$config")") # <libdir>/cmake/glcollide: lib, or lib/<multiarch> for /usr
for f in "$config"/glcollideConfigVersion.cmake "$config"/glcollideTargets.cmake \
         "$libdir"/libglcollide_engine.a "$libdir"/libglcollide_gl.a \
         "$prefix"/include/glcollide/{engine,headless_context,scene,error}.hpp; do
  test -f "$f" || fail "missing $f"
done
if [ "$(cache GLCOLLIDE_BUILD_CLI)" = ON ]; then test -x "$prefix/bin/glcollide" || fail "missing bin/glcollide"; fi
# Public headers may include only other public headers (or system/third-party ones).
for inc in $(grep -ho '#include [<"]glcollide/[^>"]*' "$prefix"/include/glcollide/*.hpp | sed 's/#include [<"]//' | sort -u); do
  test -f "$prefix/include/$inc" || fail "public header includes $inc, which is not installed"
done
# Nothing in the package may point back into the source or build tree.
if grep -rlF -e "$src/" -e "$build/" "$config"; then fail "package refers to the source or build tree"; fi

step "configure the consumer"
cmake -S "$src/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE="$build_type" \
  -DCMAKE_CXX_FLAGS="$cxx_flags -Wall -Wextra -Wshadow -Wconversion -Werror" \
  >"$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "consumer configure"; }
grep -F "glcollide " "$work/configure.log" || true
grep -qF "from $config" "$work/configure.log" || { cat "$work/configure.log"; fail "found a glcollide other than $prefix"; }

step "build the consumer"
cmake --build "$work/consumer" >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "consumer build"; }

step "run the consumer"
"$work/consumer/glcollide_consumer" || fail "consumer exited with $?"
rm -rf "$work"
echo "ok"
