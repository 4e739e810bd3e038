#!/usr/bin/env bash
# Makes docs/gallery.md: a strip of small frames of every shipped scene (scenes/*.json), rendered by
# `glcollide render` (frames 0, K, 2K, 3K at 160x120), so the gallery shows what the engine does
# now. A scene that does not finish within the time limit is listed as too slow here, with the
# limit, rather than shown with pictures it did not make.
# usage: scripts/gallery.sh [GLCOLLIDE_BINARY] [SECONDS_PER_SCENE]   (defaults: build/src/glcollide, 240)
# Environment: GALLERY_FRAMES (3K, default 30), GALLERY_ONLY (space-separated scene names to redo;
# the others keep their images and lines from the last docs/gallery.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-${GLCOLLIDE_BUILD_DIR:-build}/src/glcollide}
limit=${2:-240}
frames=${GALLERY_FRAMES:-30}
every=$((frames / 3))
out=docs/gallery
[ -x "$bin" ] || { echo "gallery.sh: $bin is not an executable (build first)" >&2; exit 1; }
mkdir -p "$out"
device=$("$bin" info 2>/dev/null | sed -n 's/^GL renderer: //p' | head -1)
commit=$(git rev-parse --short HEAD)
rows=()
for scene in scenes/*.json; do
  name=$(basename "$scene" .json)
  if [ -n "${GALLERY_ONLY:-}" ] && [[ " $GALLERY_ONLY " != *" $name "* ]]; then
    old=$(grep -F "| \`scenes/$name.json\` |" docs/gallery.md 2>/dev/null || true)
    if [ -n "$old" ]; then
      rows+=("$old")
      continue
    fi
  fi
  rm -f "$out/$name"_*.png
  tmp=$(mktemp -d)
  start=$(date +%s)
  if timeout "$limit" "$bin" render "$scene" --frames "$frames" --every "$every" --size 160x120 --out "$tmp" \
    --quiet >/dev/null 2>"$tmp/err.txt"; then
    seconds=$(($(date +%s) - start))
    cells=""
    for f in 0 $every $((2 * every)) $((3 * every)); do
      cp "$tmp/$(printf 'frame_%06d.png' "$f")" "$out/${name}_$f.png"
      cells+=" ![${name} frame $f](gallery/${name}_$f.png)"
    done
    row="| \`scenes/$name.json\` |$cells | ${seconds} s |"
  else
    rc=$?
    why="failed: $(head -1 "$tmp/err.txt")"
    [ $rc -eq 124 ] && why="too slow to render here: not done within ${limit} s"
    row="| \`scenes/$name.json\` | $why | — |"
  fi
  rm -rf "$tmp"
  rows+=("$row")
  echo "gallery: $name: ${row##*|  }" >&2
done
{
  echo "# Gallery"
  echo
  echo "Every shipped scene (\`scenes/*.json\`), frames 0, $every, $((2 * every)) and $frames as \`glcollide render\` draws"
  echo "them at 160x120 (\`render SCENE --frames $frames --every $every --size 160x120\`), made by \`scripts/gallery.sh\`"
  echo "on ${device:-an unknown renderer} at commit $commit. The last column is the wall time of that render"
  echo "(simulation included) on this machine; a scene that did not finish within the script's limit is"
  echo "listed as too slow here instead of shown. Regenerate with \`scripts/gallery.sh\`."
  echo
  echo "| scene | frames | render |"
  echo "|---|---|---:|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "Notes. \`hanging_cloth\` has no ground: \`render\` draws its grid just under the lowest initial node, so"
  echo "the cloth, swinging down from its two pinned corners, passes below the grid and only the corners"
  echo "stay in sight (\`render\`'s framing, not the simulation). The armadillo piles (207,552 faces, exact"
  echo "narrow phase) did not render 30 frames in 7 minutes on llvmpipe with 2 cores; a GPU is for them."
  echo "Single scenes are redone with \`GALLERY_ONLY=\"name ...\" scripts/gallery.sh\`."
} >docs/gallery.md
echo "gallery: wrote docs/gallery.md and $(ls "$out"/*.png 2>/dev/null | wc -l) images ($(du -sh "$out" | cut -f1))" >&2
