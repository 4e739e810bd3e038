#!/usr/bin/env bash
# The program binary cache end to end (README, GLCOLLIDE_CACHE_DIR): a colliding scene run twice
# into a fresh cache folder compiles every program in the first run and none in the second
# (--stats "setup"); two processes filling one cold folder at once both succeed and leave it
# usable; `off` writes nothing; `info` names the folder.
# usage: program_cache_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
scene=$src/tests/data/scene/colliding_spheres.json
. "$(dirname "$0")/check_lib.sh"

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

# info names the folder, or says it is off.
GLCOLLIDE_CACHE_DIR=$work/cache "$bin" info >"$work/info.txt" 2>&1
check "info names the cache folder" grep -q "^program cache: $work/cache (the driver offers" "$work/info.txt"
GLCOLLIDE_CACHE_DIR=off "$bin" info >"$work/info_off.txt" 2>&1
check "info says off" grep -q "^program cache: off (GLCOLLIDE_CACHE_DIR=off)" "$work/info_off.txt"
GLCOLLIDE_CACHE_DIR=$work/cache "$bin" info --json >"$work/info.json" 2>&1
check "info --json names the folder" python3 -c "
import json, sys
j = json.load(open('$work/info.json'))['program_cache']
sys.exit(0 if j['folder'] == '$work/cache' and j['binary_formats'] >= 0 else 1)"

echo "program cache: $failures check(s) failed"
exit $((failures > 0))
