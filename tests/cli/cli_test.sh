#!/usr/bin/env bash
# End-to-end checks of the glcollide CLI: what `run` promises (--export, --stats, the composed
# pipeline on stdout), `info`, and a clear one-line error with a non-zero exit on bad input.
# usage: cli_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
. "$(dirname "$0")/check_lib.sh"

# run with no scene: the built-in default scene, exporting OBJ and stats.
"$bin" run --frames 4 --export "$work/obj" --every 2 --stats "$work/stats.json" --quiet >"$work/out.txt" 2>"$work/err.txt"
check "default run exits 0" test $? -eq 0
check "pipeline printed" grep -q "pipeline (per substep): SpringUpdate NodeUpdate" "$work/out.txt"
check "frames 0,2,4 exported" test -f "$work/obj/frame_000000.obj" -a -f "$work/obj/frame_000002.obj" -a -f "$work/obj/frame_000004.obj"
check "frame 1 not exported (--every 2)" test ! -f "$work/obj/frame_000001.obj"
check "OBJ has 1024 vertices" test "$(grep -c '^v ' "$work/obj/frame_000004.obj")" -eq 1024
check "OBJ has 1922 faces" test "$(grep -c '^f ' "$work/obj/frame_000004.obj")" -eq 1922
check "stats has 4 frames" test "$(grep -c '"frame":' "$work/stats.json")" -eq 4
for key in kinetic_energy_J potential_energy_J total_energy_J wall_ms dispatches_per_substep gpu_ms SpringUpdate NodeUpdate; do
  check "stats has $key" grep -q "\"$key\"" "$work/stats.json"
done
check "no progress with --quiet" test ! -s "$work/err.txt"

# --frame-step: the same frames from one FrameStep dispatch per frame.
"$bin" run --frames 4 --frame-step --quiet --stats "$work/fs.json" >"$work/out3.txt" 2>&1
check "frame-step run exits 0" test $? -eq 0
check "frame-step pipeline" grep -q "pipeline (per substep): FrameStep" "$work/out3.txt"
check "frame-step: one dispatch per frame" grep -q "0.0151515 dispatches per substep" "$work/out3.txt"

# PLY export of a tet scene with ground.
"$bin" run "$src/scenes/falling_tet_body.json" --frames 2 --export "$work/ply" --format ply --quiet >"$work/out2.txt" 2>&1
check "tet scene exits 0" test $? -eq 0
check "PLY header" grep -q "^element face" "$work/ply/frame_000002.ply"
check "ground scene pipeline" grep -q "pipeline (per substep): SpringUpdate NodeUpdate" "$work/out2.txt"

# --broad-phase: two colliding spheres under the octree and the BVH find the same candidate and
# intersecting pairs in every frame (both exact: the same float face boxes).
for bp in octree bvh; do
  "$bin" run "$src/tests/data/scene/colliding_spheres.json" --frames 4 --broad-phase $bp --stats "$work/bp_$bp.json" --quiet >"$work/bp_$bp.txt" 2>&1
  check "--broad-phase $bp exits 0" test $? -eq 0
  grep -o '"\(candidate\|max_intersecting\)_pairs": *[0-9]*' "$work/bp_$bp.json" >"$work/bp_$bp.counts"
done
check "bvh pipeline printed" grep -q "pipeline (per substep): .*BvhBuild BvhRefit BvhTraverse TriTri" "$work/bp_bvh.txt"
check "bvh stats has node visits" grep -q '"bvh_node_visits"' "$work/bp_bvh.json"
check "octree and bvh counts equal" cmp -s "$work/bp_octree.counts" "$work/bp_bvh.counts"
check "counts for 4 frames" test "$(wc -l <"$work/bp_bvh.counts")" -eq 8
check "the spheres have candidates" grep -q '"candidate_pairs": *[1-9]' "$work/bp_bvh.counts"
"$bin" run --frames 1 --broad-phase bvh --quiet >"$work/bp_none.txt" 2>&1
check "--broad-phase without collisions exits 1" test $? -eq 1
check "--broad-phase without collisions says why" grep -q "lists neither 'collisions' nor 'self_collisions'" "$work/bp_none.txt"
"$bin" run "$src/scenes/two_tet_bodies.json" --frames 1 --broad-phase kd --quiet >"$work/bp_bad.txt" 2>&1
check "unknown --broad-phase exits 1" test $? -eq 1
check "unknown --broad-phase names the choices" grep -q 'unknown broad phase "kd"; expected "octree", "masked", "all_pairs" or "bvh"' "$work/bp_bad.txt"

# Progress goes to stderr when not quiet.
"$bin" run --frames 3 >/dev/null 2>"$work/progress.txt"
check "progress on stderr" grep -q "100%" "$work/progress.txt"

# info
"$bin" info >"$work/info.txt" 2>&1
check "info exits 0" test $? -eq 0
check "info names renderer and limits" grep -q "GL renderer:" "$work/info.txt"
grep -q "max_work_group_invocations" "$work/info.txt"; check "info lists compute limits" test $? -eq 0

# Bad input: one line naming the file and JSON pointer, exit 1, no crash.
printf '{"format_version": 1, "effects": ["gravity", "gravitty"], "objects": []}' >"$work/bad.json"
"$bin" run "$work/bad.json" >/dev/null 2>"$work/bad.txt"
rc=$?
check "bad scene exits 1" test $rc -eq 1
check "bad scene names file and pointer" grep -q "bad.json: /effects/1" "$work/bad.txt"
"$bin" run "$work/missing.json" >/dev/null 2>"$work/missing.txt"
check "missing scene exits 1" test $? -eq 1
check "missing scene named" grep -q "missing.json" "$work/missing.txt"
"$bin" run --device 42 --frames 1 >/dev/null 2>"$work/dev.txt"
check "missing device exits 1" test $? -eq 1
check "missing device is explained" grep -qi "device" "$work/dev.txt"
"$bin" run --frames 0 >/dev/null 2>"$work/frames.txt"
check "--frames 0 rejected" test $? -ne 0

echo "cli: $failures check(s) failed"
exit $((failures > 0))
