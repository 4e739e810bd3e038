#!/usr/bin/env bash
# Regenerates the published benchmark report with one command: builds, runs a suite on this
# machine's device (bench/suites/full.json unless another is given) into bench/results/<device>/,
# then rebuilds docs/benchmarks.md and the headline tables of docs/benchmark-snapshots.md from every device's results.
# Extra arguments go to `glcollide bench` (e.g. --device cuda:0, --only broad_phase).
set -euo pipefail
cd "$(dirname "$0")/.."
suite=${1:-bench/suites/full.json}
shift || true
# Its own build folder (no tests), so the test build's cache is left alone.
export GLCOLLIDE_BUILD_DIR=${GLCOLLIDE_BUILD_DIR:-build-bench}
GLCOLLIDE_CMAKE_ARGS="${GLCOLLIDE_CMAKE_ARGS:-} -DGLCOLLIDE_BUILD_TESTS=OFF" scripts/build.sh
build_dir=$GLCOLLIDE_BUILD_DIR
"$build_dir/src/glcollide" bench --suite "$suite" --out 'bench/results/{device}' "$@"
python3 bench/make_report.py
