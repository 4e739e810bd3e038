#!/usr/bin/env bash
# Determinism: the same colliding scene simulated twice gives byte-identical exported frames.
# tests/data/scene/colliding_spheres.json: two icospheres meet within the first frames, so the
# collision passes (octree broad phase, robust tri-tri, contact response) are exercised; the test
# also checks from --stats that contacts actually happened.
# usage: determinism_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
scene=$src/tests/data/scene/colliding_spheres.json
. "$(dirname "$0")/check_lib.sh"

for run in 1 2; do
  timeout 120 "$bin" run "$scene" --frames 6 --export "$work/run$run" --every 3 --stats "$work/stats$run.json" --quiet \
    >"$work/out$run.txt" 2>"$work/err$run.txt"
  check "run $run exits 0" test $? -eq 0
done
check "contacts happened" grep -Eq '"contacts": *[1-9]' "$work/stats1.json"
frames=(frame_000000.obj frame_000003.obj frame_000006.obj)
check "run 1 exported 3 frames" test "$(ls "$work/run1" | wc -l)" -eq 3
check "run 2 exported 3 frames" test "$(ls "$work/run2" | wc -l)" -eq 3
for f in "${frames[@]}"; do
  check "$f exists" test -s "$work/run1/$f"
  check "$f byte-identical" cmp "$work/run1/$f" "$work/run2/$f"
done
# The bodies moved: the last frame differs from the first.
check "bodies moved" bash -c "! cmp -s '$work/run1/frame_000000.obj' '$work/run1/frame_000006.obj'"

[ $failures -eq 0 ]
