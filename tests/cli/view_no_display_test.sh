#!/usr/bin/env bash
# `glcollide view` with no window system (no DISPLAY, no WAYLAND_DISPLAY): one clear error naming
# what is missing and a non-zero exit, without opening anything; run and render need no display.
# usage: view_no_display_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
. "$(dirname "$0")/check_lib.sh"
env -u DISPLAY -u WAYLAND_DISPLAY "$bin" view "$src/tests/data/view/swinging_cloth.json" >"$work/out.txt" 2>"$work/err.txt"
check "exit 1" test $? -eq 1
check "the error says DISPLAY is not set and what to do" \
  grep -q "^glcollide: error: no display: DISPLAY is not set; view needs a window system (try xvfb-run" "$work/err.txt"
check "one line" test "$(wc -l <"$work/err.txt")" -eq 1
env -u DISPLAY -u WAYLAND_DISPLAY "$bin" run "$src/tests/data/view/swinging_cloth.json" --frames 2 --quiet >/dev/null 2>&1
check "run needs no display" test $? -eq 0
env -u DISPLAY -u WAYLAND_DISPLAY "$bin" render "$src/tests/data/view/swinging_cloth.json" --frames 1 --size 32x32 \
  --out "$work/png" --quiet >/dev/null 2>&1
check "render needs no display" test $? -eq 0
echo "view_no_display: $failures check(s) failed"
exit $((failures > 0))
