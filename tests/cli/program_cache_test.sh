#!/usr/bin/env bash
# The program binary cache end to end (docs/cli.md, GLCOLLIDE_CACHE_DIR): a colliding scene run twice
# into a fresh cache folder compiles every program in the first run and none in the second
# (--stats "setup"), and the robust self-check it needs runs once and is then remembered; two
# processes filling one cold folder at once both succeed and leave it usable; `off` writes
# nothing, and so does a driver offering no binary format (Mesa with MESA_SHADER_CACHE_DISABLE);
# `info` names the folder and the self-check's result; a bad GLCOLLIDE_SELF_CHECK is an
# error naming it.
# usage: program_cache_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
scene=$src/tests/data/scene/colliding_spheres.json
. "$(dirname "$0")/check_lib.sh"

# The driver must offer a program binary format, or there is nothing to cache. Mesa (llvmpipe in
# CI) offers its one format only while its own on-disk shader cache is enabled, which is Mesa's
# default but not with MESA_SHADER_CACHE_DISABLE set (docs/integration.md). CTest gives this
# script no environment of its own and .ci/run and scripts/test.sh set neither variable, so the
# default holds in CI; to hold wherever the script runs, it takes the choice out of the caller's
# hands: Mesa's cache on, in a fresh folder of its own rather than ~/.cache (the "no binary
# format" check below turns it off on purpose). A GPU driver offers its formats regardless.
unset MESA_SHADER_CACHE_DISABLE
export MESA_SHADER_CACHE_DIR=$work/mesa-shader-cache

# stats_check FILE PYTHON_EXPRESSION: the expression over s = the "setup" object is true.
stats_check() {
  python3 - "$1" "$2" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["setup"]
sys.exit(0 if eval(sys.argv[2]) else 1)
PY
}

export GLCOLLIDE_CACHE_DIR=$work/cache
for run in 1 2; do
  timeout 300 "$bin" run "$scene" --frames 1 --stats "$work/stats$run.json" --quiet >"$work/out$run.txt" 2>"$work/err$run.txt"
  check "run $run exits 0" test $? -eq 0
done
check "cold run: every program a miss" stats_check "$work/stats1.json" \
  's["program_cache"]["hits"] == 0 and s["program_cache"]["misses"] == len(s["programs"]) > 0'
check "cold run: folder reported" stats_check "$work/stats1.json" "s['program_cache']['folder'] == '$work/cache'"
check "cold run: compile_link_ms is the programs' sum" stats_check "$work/stats1.json" \
  'abs(s["compile_link_ms"] - sum(p["ms"] for p in s["programs"])) < 1e-6 * max(1.0, s["compile_link_ms"])'
check "warm run: 0 misses" stats_check "$work/stats2.json" \
  's["program_cache"]["misses"] == 0 and s["program_cache"]["hits"] == len(s["programs"]) > 0'
check "warm run: every program a hit" stats_check "$work/stats2.json" 'all(p["cache"] == "hit" for p in s["programs"])'
check "cold run: robust self-check ran and passed" stats_check "$work/stats1.json" \
  's["robust_self_check"]["status"] == "passed" and s["robust_self_check"]["cases"] >= 300 and not s["robust_self_check"]["remembered"]'
check "warm run: the pass is remembered" stats_check "$work/stats2.json" \
  's["robust_self_check"]["status"] == "passed" and s["robust_self_check"]["remembered"] and s["robust_self_check"]["cases"] == 0'
check "setup line on stdout" grep -q "^setup: .* programs in .* ms (program cache: 0 hits" "$work/out1.txt"
check "cache holds entries" test "$(ls "$work/cache"/*.bin | wc -l)" -gt 0

# Two processes filling one cold folder at once: both succeed, no temporary file is left, and
# the folder then serves a third run entirely.
export GLCOLLIDE_CACHE_DIR=$work/shared
timeout 300 "$bin" run "$scene" --frames 1 --quiet >/dev/null 2>"$work/errA.txt" &
pidA=$!
timeout 300 "$bin" run "$scene" --frames 1 --quiet >/dev/null 2>"$work/errB.txt" &
pidB=$!
wait $pidA; rcA=$?
wait $pidB; rcB=$?
check "concurrent run A exits 0" test $rcA -eq 0
check "concurrent run B exits 0" test $rcB -eq 0
check "no temporary file left" test "$(ls "$work/shared" | grep -c '\.tmp\.')" -eq 0
timeout 300 "$bin" run "$scene" --frames 1 --stats "$work/stats3.json" --quiet >/dev/null 2>&1
check "after concurrent fill: 0 misses" stats_check "$work/stats3.json" 's["program_cache"]["misses"] == 0'

# off: compiles, reports no folder, writes nothing.
GLCOLLIDE_CACHE_DIR=off timeout 300 "$bin" run "$scene" --frames 1 --stats "$work/stats_off.json" --quiet >/dev/null 2>&1
check "off run exits 0" test $? -eq 0
check "off: no hits, no folder" stats_check "$work/stats_off.json" \
  's["program_cache"]["hits"] == 0 and s["program_cache"]["folder"] is None'

# A driver offering no program binary format: Mesa offers none with its own shader cache disabled.
# Every program is then a miss, the note says why, and nothing is written.
GLCOLLIDE_CACHE_DIR=$work/noformat MESA_SHADER_CACHE_DISABLE=true timeout 300 "$bin" run "$scene" --frames 1 \
  --stats "$work/stats_noformat.json" --quiet >/dev/null 2>&1
check "no binary format: run exits 0" test $? -eq 0
check "no binary format: all misses, the note says why" stats_check "$work/stats_noformat.json" \
  's["program_cache"]["hits"] == 0 and s["program_cache"]["misses"] == len(s["programs"]) and "no program binary format" in s["program_cache"]["note"]'
check "no binary format: no entry written" test "$(ls "$work/noformat" 2>/dev/null | grep -c '\.bin$')" -eq 0

# info names the folder, or says it is off.
GLCOLLIDE_CACHE_DIR=$work/cache "$bin" info >"$work/info.txt" 2>&1
check "info names the cache folder and a binary format" \
  grep -q "^program cache: $work/cache (the driver offers [1-9][0-9]* program binary format" "$work/info.txt"
check "info reports the remembered self-check" grep -q "^robust self-check: passed (remembered in $work/cache/robust-self-check-" "$work/info.txt"
GLCOLLIDE_SELF_CHECK=off "$bin" info >"$work/info_sc_off.txt" 2>&1
check "info: self-check off" grep -q "^robust self-check: off" "$work/info_sc_off.txt"
GLCOLLIDE_SELF_CHECK=maybe "$bin" run "$scene" --frames 1 --quiet >/dev/null 2>"$work/sc_bad.txt"
check "bad GLCOLLIDE_SELF_CHECK exits 1" test $? -eq 1
check "bad GLCOLLIDE_SELF_CHECK is named" grep -q "GLCOLLIDE_SELF_CHECK: expected error, warn or off, got 'maybe'" "$work/sc_bad.txt"
GLCOLLIDE_CACHE_DIR=off "$bin" info >"$work/info_off.txt" 2>&1
check "info says off" grep -q "^program cache: off (GLCOLLIDE_CACHE_DIR=off)" "$work/info_off.txt"
GLCOLLIDE_CACHE_DIR=$work/cache "$bin" info --json >"$work/info.json" 2>&1
# At least one format: see the top (Mesa's shader cache is on; a GPU driver has its own).
check "info --json names the folder and at least one binary format" python3 -c "
import json, sys
j = json.load(open('$work/info.json'))['program_cache']
sys.exit(0 if j['folder'] == '$work/cache' and j['binary_formats'] >= 1 else 1)"

echo "program cache: $failures check(s) failed"
exit $((failures > 0))
