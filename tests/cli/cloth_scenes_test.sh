#!/usr/bin/env bash
# The shipped cloth self-collision scenes (decision 0019), CI-sized: the first FRAMES frames of
# scenes/cloth_on_sphere.json, cloth_stack.json and crumpled_cloth.json (the full runs are in
# docs/collisions.md). Each must make contacts (the cloth reached the sphere, the ground's cloths
# or itself) and report 0 intersecting face pairs in every substep: every frame's
# max_intersecting_pairs, the largest count collision detection found in one of its substeps.
# usage: cloth_scenes_test.sh GLCOLLIDE_BINARY SOURCE_DIR [FRAMES]
set -u
bin=$1
src=$2
frames=${3:-20}
. "$(dirname "$0")/check_lib.sh"

for scene in cloth_on_sphere cloth_stack crumpled_cloth; do
  timeout 120 "$bin" run "$src/scenes/$scene.json" --frames "$frames" --no-gpu-timing --quiet \
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
