#!/usr/bin/env bash
# The whole test suite built with clang, AddressSanitizer and UndefinedBehaviorSanitizer (GL
# tests on llvmpipe included), then every fuzz target for a short run (scripts/fuzz.sh).
# scripts/test.sh runs it after the normal build; alone: scripts/test-sanitizers.sh [FUZZ_SECONDS].
# The install test is left to the normal build (a consumer built without the sanitizer flags
# cannot link sanitized static libraries). Leaks inside the GL driver are suppressed by library name (tests/sanitizers/lsan.supp); leaks
# in glcollide's code are not.
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds=${1:-${GLCOLLIDE_FUZZ_SECONDS:-60}}
build_dir=${GLCOLLIDE_SANITIZE_BUILD_DIR:-build-sanitize}
CC=clang CXX=clang++ cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGLCOLLIDE_SANITIZE=address,undefined -DGLCOLLIDE_BUILD_FUZZERS=ON \
  -DGLCOLLIDE_WARNINGS_AS_ERRORS=ON -DGLCOLLIDE_INSTALL=OFF -DGLCOLLIDE_LINE_TABLES_ONLY=ON
cmake --build "$build_dir" -j "$(nproc)"
echo "test-sanitizers.sh: the sanitized build took ${SECONDS} s"
supp="$PWD/tests/sanitizers"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$supp/ubsan.supp"
# Keep Mesa's driver loaded until the leak check so its allocations are named (lsan.supp).
mesa_driver=$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null | head -1 || true)
# The "long" label (whole scene runs and CCD sweeps, 10 s to minutes each; tests/CMakeLists.txt
# lists them) runs in the normal build only: it checks physics, which the sanitizers do not change,
# its time goes to llvmpipe's uninstrumented shaders, and CI's time did not hold it twice.
LD_PRELOAD="${mesa_driver}${LD_PRELOAD:+:$LD_PRELOAD}" \
  ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" -LE long 2>&1 | tee "$build_dir/ctest.log"
scripts/check-skips.sh "$build_dir/ctest.log" || [ "${GLCOLLIDE_FAIL_ON_SKIP:-0}" != 1 ]
echo "test-sanitizers.sh: build and sanitized ctest took ${SECONDS} s"
# Repeatable fuzzing: 30,000 inputs per target from seed 1 (about 1-10 s each on llvmpipe's 2-core
# machine); FUZZ_SECONDS is a safety net: a target it stops before its 30,000 runs fails.
# scripts/fuzz.sh alone explores further with a random seed.
GLCOLLIDE_FUZZ_RUNS=${GLCOLLIDE_FUZZ_RUNS:-30000} scripts/fuzz.sh "$fuzz_seconds" "$build_dir"
echo "test-sanitizers.sh: build, ctest and fuzzing took ${SECONDS} s"
