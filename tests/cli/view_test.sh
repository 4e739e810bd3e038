#!/usr/bin/env bash
# `glcollide view` (issue 25, item 1) under Xvfb with Mesa's llvmpipe: screenshots of what the window
# shows (the body's colour where the body is, the panel, different frames differ) and scripted input
# (--input) that pauses, steps one frame and pulls a node towards the cursor. Fails, not skips,
# when xvfb-run is missing (Debian's xvfb; scripts/install-deps.sh installs it).
# usage: view_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
. "$(dirname "$0")/check_lib.sh"
png="python3 $(dirname "$0")/png_tool.py"
swinging=$src/tests/data/view/swinging_cloth.json
still=$src/tests/data/view/still_cloth.json
if ! command -v xvfb-run >/dev/null; then
  echo "FAIL xvfb-run is not installed (Debian: apt-get install xvfb; scripts/install-deps.sh)"
  exit 1
fi
# view FRAMES SCENE [ARGS...]: the viewer in a 1280x800 window on a fresh Xvfb display, in $work.
view() {
  local frames=$1 scene=$2
  shift 2
  (cd "$work" && xvfb-run -a -s "-screen 0 1280x800x24" "$bin" view "$scene" --frames "$frames" "$@" \
    >"$work/out.txt" 2>"$work/err.txt")
}
# The panel sits at the top left (x < 368); the scene is drawn right of it.
scene_rect="380 0 1280 800"
panel_rect="10 10 360 790"
ge() { python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) else 1)" "$1" "$2"; }

# The picture: the cloth's blue where it hangs, the panel, frame 2 and frame 12 differ.
printf '2 screenshot early.png\n' >"$work/shots.txt"
view 12 "$swinging" --input "$work/shots.txt" --screenshot late.png
check "view --frames 12 --screenshot exits 0" test $? -eq 0
check "the screenshot is a 1280x800 PNG" test "$($png size "$work/late.png")" = "1280 800"
check "the input script's screenshot is written too" test -f "$work/early.png"
check "summary: 12 frames shown, 12 simulated" grep -q "12 frames shown, 12 simulated" "$work/out.txt"
check "nothing on stderr" test ! -s "$work/err.txt"
body=$($png count "$work/late.png" $scene_rect body)
check "the cloth's blue covers >= 1.5 % of the scene ($body)" ge "$body" 0.015
panel=$($png count "$work/late.png" $panel_rect panel)
check "the panel's dark background covers >= 40 % of its corner ($panel)" ge "$panel" 0.40
scene_panel=$($png count "$work/late.png" $scene_rect panel)
check "and no panel over the scene ($scene_panel)" test "$scene_panel" = "0.0000"
changed=$($png diff "$work/early.png" "$work/late.png" $scene_rect)
check "frames 2 and 12 differ (the cloth swings: $changed pixels)" test "$changed" -gt 1000

# Pause (space at frame 1, before any step): nothing moves, frames 3 and 8 are the same picture.
printf '# pause at once\n1 key space\n3 screenshot a.png\n8 screenshot b.png\n' >"$work/pause.txt"
view 8 "$swinging" --input "$work/pause.txt"
check "paused: exits 0" test $? -eq 0
check "paused: 8 frames shown, 0 simulated" grep -q "8 frames shown, 0 simulated" "$work/out.txt"
check "paused: frames 3 and 8 show the scene alike" test "$($png diff "$work/a.png" "$work/b.png" $scene_rect)" = 0

# Step: paused, then N at frame 4 and the right arrow at frame 6: exactly two engine frames.
printf '1 key space\n4 key n\n5 screenshot one.png\n6 key right\n' >"$work/step.txt"
view 8 "$swinging" --input "$work/step.txt" --screenshot two.png
check "stepping: exits 0" test $? -eq 0
check "stepping: 2 simulated, the scene at frame 2" grep -q "8 frames shown, 2 simulated (this scene at t = 0.0333 s, frame 2)" "$work/out.txt"
check "stepping: one frame more changes the picture" test "$($png diff "$work/one.png" "$work/two.png" $scene_rect)" -gt 0

# Pull: Ctrl + left drag from the still cloth's centre node (at the window's centre) 160 pixels to
# the right over 40 frames; the node follows the cursor's point: at the release it is far nearer
# the target than where it was grabbed.
printf '2 drag left 640 400 800 400 40 ctrl\n' >"$work/pull.txt"
view 43 "$still" --input "$work/pull.txt"
check "pull: exits 0" test $? -eq 0
line=$(grep "^pull: node 60 released" "$work/out.txt")
check "pull: the centre node (60) was grabbed and released" test -n "$line"
read -r grabbed released < <(echo "$line" | sed -E 's/.*released: ([0-9.]+) m .*, ([0-9.]+) m at the release/\1 \2/')
check "pull: the target moved away from the node (${grabbed:-?} m)" ge "${grabbed:-0}" 0.3
check "pull: the node came to within a third of that (${released:-?} m)" ge "$(python3 -c "print(${grabbed:-0} / 3)")" "${released:-1}"
# A drag without Ctrl orbits the camera: no pull, another picture; the wheel zooms, F frames all.
printf '1 screenshot still.png\n2 drag left 640 400 800 400 5\n' >"$work/orbit.txt"
view 8 "$still" --input "$work/orbit.txt" --screenshot orbited.png
check "orbit: exits 0, no node pulled" test $? -eq 0 -a -z "$(grep '^pull:' "$work/out.txt")"
check "orbit: the view turned" test "$($png diff "$work/still.png" "$work/orbited.png" $scene_rect)" -gt 1000
printf '2 scroll 3\n4 screenshot zoomed.png\n5 key f\n' >"$work/zoom.txt"
view 6 "$still" --input "$work/zoom.txt" --screenshot framed.png
check "zoom and frame all: exits 0" test $? -eq 0
check "zoom: the picture changed" test "$($png diff "$work/still.png" "$work/zoomed.png" $scene_rect)" -gt 1000
check "frame all: the picture changed again" test "$($png diff "$work/zoomed.png" "$work/framed.png" $scene_rect)" -gt 1000

# A bad scene opened from the script: the engine's error on stderr (and in the panel), the viewer runs on.
printf '2 open %s\n' "$src/tests/data/view/no_such_scene.json" >"$work/open.txt"
view 4 "$swinging" --input "$work/open.txt"
check "bad scene opened: still exits 0" test $? -eq 0
check "bad scene opened: the error names the file" grep -q "glcollide: view: could not open .*no_such_scene.json" "$work/err.txt"
check "bad scene opened: the first scene ran on (4 frames)" grep -q "view test: swinging cloth: 4 frames shown, 4 simulated" "$work/out.txt"
# A good one replaces the scene.
printf '2 open %s\n' "$still" >"$work/open2.txt"
view 4 "$swinging" --input "$work/open2.txt"
check "opening another scene: it is shown" grep -q "view test: still cloth: 4 frames shown" "$work/out.txt"

# Candidate face pairs (key C) over two boxes 5 mm apart, within the contact thickness: green lines.
printf '1 key space\n1 key c\n' >"$work/pairs.txt"
view 2 "$src/tests/data/view/touching_boxes.json" --input "$work/pairs.txt" --screenshot pairs.png
check "pairs: exits 0" test $? -eq 0
green=$($png count "$work/pairs.png" $scene_rect pairs)
check "pairs: the overlay's green lines are drawn ($green of the scene)" ge "$green" 0.001
printf '1 key space\n' >"$work/nopairs.txt"
view 2 "$src/tests/data/view/touching_boxes.json" --input "$work/nopairs.txt" --screenshot nopairs.png
check "pairs: none without the toggle" test "$($png count "$work/nopairs.png" $scene_rect pairs)" = "0.0000"

# Feature contacts (key K) of the same boxes: cyan lines between the closest points (5 mm long).
printf '1 key space\n1 key k\n' >"$work/contacts.txt"
view 2 "$src/tests/data/view/touching_boxes.json" --input "$work/contacts.txt" --screenshot contacts.png
check "contacts: exits 0" test $? -eq 0
cyan=$($png count "$work/contacts.png" $scene_rect contacts)
check "contacts: the overlay's cyan lines are drawn ($cyan of the scene)" test "$cyan" != "0.0000"
check "contacts: none without the toggle" test "$($png count "$work/nopairs.png" $scene_rect contacts)" = "0.0000"

# The broad phase's boxes (key B) of the same boxes: violet edges, the root level (-) and deeper (=).
printf '1 key space\n1 key b\n1 key -\n2 screenshot root.png\n3 key =\n3 key =\n' >"$work/boxes.txt"
view 3 "$src/tests/data/view/touching_boxes.json" --input "$work/boxes.txt" --screenshot deep.png
check "boxes: exits 0" test $? -eq 0
check "boxes: the overlay's violet edges are drawn" test "$($png count "$work/root.png" $scene_rect boxes)" != "0.0000"
check "boxes: another depth, another picture" test "$($png diff "$work/root.png" "$work/deep.png" $scene_rect)" -gt 0
check "boxes: none without the toggle" test "$($png count "$work/nopairs.png" $scene_rect boxes)" = "0.0000"

# One substep (key .): paused, three substeps of a frame, then N finishes that frame: one frame.
printf '1 key space\n2 screenshot s0.png\n3 key .\n3 screenshot s1.png\n4 key .\n5 key .\n6 key n\n' >"$work/substep.txt"
view 7 "$swinging" --input "$work/substep.txt"
check "substeps: exits 0" test $? -eq 0
check "substeps: one substep changes the picture" test "$($png diff "$work/s0.png" "$work/s1.png" $scene_rect)" -gt 0
check "substeps then N: the scene at frame 1" grep -q "7 frames shown, 1 simulated (this scene at t = 0.0167 s, frame 1)" "$work/out.txt"

# --broad-phase: every broad phase finds the same candidate pairs, so the BVH's picture is the octree's.
view 2 "$src/tests/data/view/touching_boxes.json" --broad-phase bvh --input "$work/pairs.txt" --screenshot bvh.png
check "--broad-phase bvh: exits 0" test $? -eq 0
check "--broad-phase bvh: the same picture as the scene's own broad phase" \
  test "$($png diff "$work/pairs.png" "$work/bvh.png" $scene_rect)" = 0
view 2 "$swinging" --broad-phase bvh
check "--broad-phase on a scene without collisions: opened as it is" test $? -eq 0
"$bin" view "$swinging" --broad-phase nonsense >/dev/null 2>"$work/bp.err"
check "--broad-phase nonsense: exit 1, explained" test $? -eq 1 -a -n "$(grep 'unknown broad phase "nonsense"' "$work/bp.err")"

# Bad input scripts: file:line, exit 1, before any window.
printf '1 key space\n\n2 jump 3\n' >"$work/bad1.txt"
printf '1 key nosuchkey\n' >"$work/bad2.txt"
printf '5 drag left 10 10 2000 10 3\n' >"$work/bad3.txt"
printf '9 key space\n' >"$work/bad4.txt"
printf 'x key space\n' >"$work/bad5.txt"
for n in 1 2 3 4 5; do
  (cd "$work" && "$bin" view "$swinging" --frames 8 --input "bad$n.txt" >/dev/null 2>"$work/bad$n.err")
  check "bad script $n: exit 1" test $? -eq 1
done
check "bad script 1 names file:line and the event" grep -q "^glcollide: error: bad1.txt:3: unknown event 'jump'" "$work/bad1.err"
check "bad script 2 names the key" grep -q "^glcollide: error: bad2.txt:1: unknown key 'nosuchkey'" "$work/bad2.err"
check "bad script 3: outside the window" grep -q "^glcollide: error: bad3.txt:1: position .* is outside the 1280x800 window" "$work/bad3.err"
check "bad script 4: after the last frame" grep -q "^glcollide: error: bad4.txt:1: frame 9 is after the last frame (--frames 8)" "$work/bad4.err"
check "bad script 5: not a frame number" grep -q "^glcollide: error: bad5.txt:1: expected a frame number" "$work/bad5.err"
"$bin" view "$swinging" --device cuda:0 >/dev/null 2>"$work/dev.err"
check "--device cuda:0: exit 1, explained" test $? -eq 1 -a -n "$(grep 'only auto and software' "$work/dev.err")"
"$bin" view "$swinging" --screenshot x.png >/dev/null 2>"$work/shot.err"
check "--screenshot without --frames: exit 1, explained" test $? -eq 1 -a -n "$(grep 'needs --frames' "$work/shot.err")"

echo "view: $failures check(s) failed"
exit $((failures > 0))
