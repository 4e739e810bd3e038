#!/usr/bin/env bash
# Runs every libFuzzer target for a while (default 20 s each) from a copy of its seed corpus.
# Needs a build configured with -DGLCOLLIDE_BUILD_FUZZERS=ON (clang), as scripts/test-sanitizers.sh
# makes. Usage: scripts/fuzz.sh [SECONDS] [BUILD_DIR] [TARGET...]
# A finding stops that target with its input saved under $GLCOLLIDE_FUZZ_OUT (default
# build-sanitize/fuzz-findings); fix it, then keep the input in fuzz/regressions/<target>/ so
# ctest replays it (fuzz.replay.<target>) in every build.
# GLCOLLIDE_FUZZ_RUNS=N makes the run repeatable (CI): seed 1 and exactly N runs per target, so
# the same source and corpus meet the same inputs. SECONDS is then only a safety net: a target it
# stops before N runs (a slow or busy machine) FAILS, naming how far it got, instead of passing on
# fewer inputs. What stays machine-dependent: an input slower than -timeout (10 s) or above
# -rss_limit_mb is reported as a finding, and that depends on the machine's speed and memory.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
build_dir=${2:-${GLCOLLIDE_SANITIZE_BUILD_DIR:-build-sanitize}}
shift $(( $# > 2 ? 2 : $# ))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_json mesh_obj mesh_ply mesh_gltf mesh_glb mesh_msh mesh_tetgen tri_pair_csv bench_suite)
out=${GLCOLLIDE_FUZZ_OUT:-$build_dir/fuzz-findings}
mkdir -p "$out"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
repeatable=()
[ -n "${GLCOLLIDE_FUZZ_RUNS:-}" ] && repeatable=(-seed=1 -runs="$GLCOLLIDE_FUZZ_RUNS")
failed=()
for t in "${targets[@]}"; do
  bin="$build_dir/fuzz/fuzz_$t"
  [ -x "$bin" ] || { echo "fuzz.sh: $bin missing: configure with -DGLCOLLIDE_BUILD_FUZZERS=ON" >&2; exit 2; }
  work=$(mktemp -d)
  cp -r "fuzz/corpus/$t/." "$work/"
  [ -d "fuzz/regressions/$t" ] && cp -r "fuzz/regressions/$t/." "$work/"
  echo "== fuzz $t: ${GLCOLLIDE_FUZZ_RUNS:+$GLCOLLIDE_FUZZ_RUNS runs (seed 1), at most }${seconds}s from $(ls "$work" | wc -l) inputs"
  # -timeout: one input may take 10 s (a sanitized 7-subdivision sphere takes < 1 s);
  # -rss_limit_mb: libFuzzer's default 2 GiB (the scene fuzzer skips huge generators).
  if ! "$bin" "${repeatable[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
       -artifact_prefix="$out/$t-" -print_final_stats=1 "$work" >"$out/$t.log" 2>&1; then
    failed+=("$t")
    tail -40 "$out/$t.log" >&2
  fi
  grep -E "^stat::number_of_executed_units|^stat::new_units_added" "$out/$t.log" | tr '\n' ' '; echo
  if [ -n "${GLCOLLIDE_FUZZ_RUNS:-}" ]; then
    executed=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$out/$t.log" | tail -1)
    if [ -z "$executed" ] || [ "$executed" -lt "$GLCOLLIDE_FUZZ_RUNS" ]; then
      echo "fuzz.sh: $t: the ${seconds}s cap stopped the repeatable run after ${executed:-?} of $GLCOLLIDE_FUZZ_RUNS runs:" \
           "not the repeatable run; raise SECONDS" >&2
      [[ " ${failed[*]} " == *" $t "* ]] || failed+=("$t")
    fi
  fi
  rm -rf "$work"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: failed: ${failed[*]} (findings and logs under $out)" >&2
  exit 1
fi
echo "fuzz.sh: no findings"
