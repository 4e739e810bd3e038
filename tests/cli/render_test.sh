#!/usr/bin/env bash
# End-to-end checks of `glcollide render`: frame 0 and every K-th frame as PNGs of the requested
# size (read from the PNG signature and IHDR chunk), and one clear error line for bad options.
# usage: render_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
. "$(dirname "$0")/check_lib.sh"
# png_size FILE: prints "WIDTH HEIGHT" when FILE starts with the PNG signature and an IHDR chunk.
png_size() {
  local hex
  hex=$(od -An -v -tx1 -N24 "$1" | tr -d ' \n')
  [ "${hex:0:16}" = "89504e470d0a1a0a" ] || return 1 # \x89 P N G \r \n \x1a \n
  [ "${hex:24:8}" = "49484452" ] || return 1         # IHDR
  echo "$((16#${hex:32:8})) $((16#${hex:40:8}))"
}

"$bin" render "$src/scenes/two_tet_bodies.json" --frames 3 --every 1 --size 64x48 --out "$work/png" --quiet \
  >"$work/out.txt" 2>"$work/err.txt"
check "render exits 0" test $? -eq 0
for f in 0 1 2 3; do
  file="$work/png/frame_00000$f.png"
  check "frame $f written" test -f "$file"
  check "frame $f is a 64x48 PNG" test "$(png_size "$file")" = "64 48"
done
check "no frame 4 (--frames 3)" test ! -e "$work/png/frame_000004.png"
check "exactly 4 files" test "$(ls "$work/png" | wc -l)" -eq 4
check "summary on stdout" grep -q "wrote 4 PNG frames" "$work/out.txt"
check "nothing on stderr with --quiet" test ! -s "$work/err.txt"

# --every 2 over 4 frames: frames 0, 2, 4.
"$bin" render "$src/scenes/falling_tet_body.json" --frames 4 --every 2 --size 40x30 --samples 0 --out "$work/every" --quiet >/dev/null 2>&1
check "--every 2 exits 0" test $? -eq 0
check "--every 2 writes 0, 2, 4" test "$(ls "$work/every" | tr '\n' ' ')" = "frame_000000.png frame_000002.png frame_000004.png "

# Bad options: exit 1, one line on stderr naming the option, no files.
for size in 64by48 0x48 64x 64x48x2 99999999x2; do
  "$bin" render "$src/scenes/two_tet_bodies.json" --frames 1 --size "$size" --out "$work/bad" >/dev/null 2>"$work/bad.txt"
  rc=$?
  check "--size $size exits 1" test $rc -eq 1
  check "--size $size is explained" grep -q "^glcollide: error: --size: expected WIDTHxHEIGHT" "$work/bad.txt"
  check "--size $size: one line" test "$(wc -l <"$work/bad.txt")" -eq 1
done
check "no output folder after bad --size" test ! -e "$work/bad"
"$bin" render "$src/scenes/two_tet_bodies.json" --every 0 --out "$work/bad" >/dev/null 2>"$work/every0.txt"
check "--every 0 exits 1" test $? -eq 1
check "--every 0 is explained" grep -q -- "--every must be positive" "$work/every0.txt"

echo "render: $failures check(s) failed"
exit $((failures > 0))
