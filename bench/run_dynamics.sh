#!/usr/bin/env bash
# Builds (if needed) and runs the dynamics benchmark; writes Google Benchmark JSON to
# bench/results/<renderer-slug>-dynamics.json, the slug coming from the binary itself
# (GL_RENDERER "llvmpipe (LLVM ...)" -> llvmpipe, "NVIDIA H100 80GB HBM3/PCIe/SSE2" -> nvidia-h100).
#
# Usage: bench/run_dynamics.sh [--device=<selector>] [extra --benchmark_* flags]
# Environment:
#   BUILD_DIR  build tree (default: <repo>/build-bench; configured here if it has no cache)
#   MIN_TIME   --benchmark_min_time in seconds of GPU time per repetition (default 2)
#   REPS       --benchmark_repetitions (default 5; the JSON keeps every repetition plus
#              mean/median/stddev/cv aggregates)
#   OUT        output file (default: bench/results/<slug>-dynamics.json)
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$repo/build-bench}"
min_time="${MIN_TIME:-2}"
reps="${REPS:-5}"

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$repo" -B "$build" -DGLCOLLIDE_BUILD_TESTS=OFF -DGLCOLLIDE_BUILD_BENCHMARKS=ON
fi
cmake --build "$build" --target glcollide_bench_dynamics -j "$(nproc)"
bin="$build/bench/glcollide_bench_dynamics"

# --device must reach the slug query too, or the file could be named after another device.
device_args=()
for a in "$@"; do
  [[ "$a" == --device=* ]] && device_args+=("$a")
done
slug="$("$bin" "${device_args[@]}" --print-renderer-slug)"
out="${OUT:-$repo/bench/results/${slug}-dynamics.json}"
mkdir -p "$(dirname "$out")"

echo "renderer slug: $slug -> $out" >&2
"$bin" \
  --benchmark_min_time="$min_time" \
  --benchmark_repetitions="$reps" \
  --benchmark_out="$out" \
  --benchmark_out_format=json \
  "$@"
