#!/usr/bin/env bash
# Builds (if needed) and runs the collision-detection benchmark; writes Google Benchmark JSON to
# bench/results/<renderer-slug>-collision.json.
#
# Usage: bench/run_collision.sh [--device=<selector>] [extra --benchmark_* flags]
# Environment: BUILD_DIR (default <repo>/build-bench), OUT (default bench/results/<slug>-collision.json)
# Every case runs 3 timed iterations after one warm-up (the all-pairs and masked cases take
# seconds per iteration on llvmpipe).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$repo/build-bench}"
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$repo" -B "$build" -DGLCOLLIDE_BUILD_TESTS=OFF -DGLCOLLIDE_BUILD_BENCHMARKS=ON
fi
cmake --build "$build" --target glcollide_bench_collision -j "$(nproc)"
device_args=()
for a in "$@"; do
  [[ "$a" == --device=* ]] && device_args+=("$a")
done
slug="$("$build/bench/glcollide_bench_collision" "${device_args[@]}" --print-renderer-slug)"
out="${OUT:-$repo/bench/results/${slug}-collision.json}"
mkdir -p "$(dirname "$out")"
echo "renderer slug: $slug -> $out" >&2
"$build/bench/glcollide_bench_collision" --benchmark_out="$out" --benchmark_out_format=json "$@"
