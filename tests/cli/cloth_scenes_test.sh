#!/usr/bin/env bash
# The shipped cloth self-collision scenes (decision 0019), CI-sized (about 25 s on llvmpipe):
# cloth_on_sphere.json and crumpled_cloth.json with their cloths coarsened to half the resolution
# (15 x 15 and 13 x 13 nodes; the shipped resolutions spend 7 s and 3 s per frame before the first
# contact, while the flat cloth falls), 20 frames each; cloth_stack.json as shipped, 16 frames (the
# middle cloth reaches the bottom one in frame 14). Each must make contacts and report 0
# intersecting face pairs in every substep: every frame's max_intersecting_pairs, the largest count
# collision detection found in one of its substeps. These short runs end before the phases in
# which the scenes fold (and in which thickness 0.01 gave intersecting pairs): cli.cloth_scenes_long
# (cloth_scenes_long_test.sh) runs the scenes as shipped through them. The full runs are in
# docs/collisions.md.
# usage: cloth_scenes_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
. "$(dirname "$0")/check_lib.sh"

sed 's/"resolution": \[30, 30\]/"resolution": [15, 15]/' "$src/scenes/cloth_on_sphere.json" >"$work/cloth_on_sphere.in.json"
sed 's/"resolution": \[26, 26\]/"resolution": [13, 13]/' "$src/scenes/crumpled_cloth.json" >"$work/crumpled_cloth.in.json"
cp "$src/scenes/cloth_stack.json" "$work/cloth_stack.in.json"
check "the sphere scene was coarsened" grep -q '"resolution": \[15, 15\]' "$work/cloth_on_sphere.in.json"
check "the crumpled scene was coarsened" grep -q '"resolution": \[13, 13\]' "$work/crumpled_cloth.in.json"

for entry in cloth_on_sphere:20 crumpled_cloth:20 cloth_stack:16; do
  scene=${entry%%:*}
  frames=${entry##*:}
  timeout 120 "$bin" run "$work/$scene.in.json" --frames "$frames" --no-gpu-timing --quiet \
    --stats "$work/$scene.json" >"$work/$scene.txt" 2>&1
  check "$scene: run exits 0" test $? -eq 0
  check "$scene: contacts and 0 intersecting face pairs in every substep" python3 - "$work/$scene.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
c = [f["collision"] for f in s["frames"]]
bad = [(i, x["max_intersecting_pairs"]) for i, x in enumerate(c) if x["max_intersecting_pairs"] != 0]
contacts = max(x["contacts"] for x in c)
print("%d frames x %d substeps, max contacts %d, frames with intersecting pairs: %s" %
      (len(c), s["substeps"], contacts, bad or "none"))
sys.exit(0 if contacts > 0 and not bad else 1)
PY
done

[ $failures -eq 0 ]
