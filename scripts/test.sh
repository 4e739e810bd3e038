#!/usr/bin/env bash
# Sets up and runs every test: installs the Debian packages, builds, runs ctest (unit tests and
# the GL tests, on llvmpipe when there is no GPU: a GL test that gets no context fails), then the
# same suite built with clang + ASan + UBSan and a short run of every fuzz target
# (scripts/test-sanitizers.sh; GLCOLLIDE_SKIP_SANITIZERS=1 skips that part for a quick local loop).
# A test that did not run is listed; with GLCOLLIDE_FAIL_ON_SKIP=1 (CI) any skip that
# tests/skips/allowed.txt does not allow fails the run (scripts/check-skips.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
GLCOLLIDE_CMAKE_ARGS="${GLCOLLIDE_CMAKE_ARGS:-} -DGLCOLLIDE_WARNINGS_AS_ERRORS=ON -DGLCOLLIDE_LINE_TABLES_ONLY=ON" scripts/build.sh
build_dir=${GLCOLLIDE_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" 2>&1 | tee "$build_dir/ctest.log"
scripts/check-skips.sh "$build_dir/ctest.log" || [ "${GLCOLLIDE_FAIL_ON_SKIP:-0}" != 1 ]
# CI has 90 minutes for the whole of .ci/run: each stage says how long it took.
echo "test.sh: dependencies, build and ctest took ${SECONDS} s"
if [ "${GLCOLLIDE_SKIP_SANITIZERS:-0}" != 1 ]; then
  scripts/test-sanitizers.sh
fi
