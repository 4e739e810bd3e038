#!/usr/bin/env bash
# `glcollide render --video` (issue 25, item 3): an MP4 that ffprobe reads as H.264 with every K-th
# frame at 1/(K·dt) frames per second, padded to even sizes, and nothing else left behind; without
# ffmpeg on PATH, one clear error and a non-zero exit before any simulation. Needs ffmpeg and
# ffprobe (Debian's ffmpeg package; scripts/install-deps.sh installs it).
# usage: render_video_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
. "$(dirname "$0")/check_lib.sh"
check "ffprobe is installed (scripts/install-deps.sh installs ffmpeg)" command -v ffprobe

mkdir "$work/run"
(cd "$work/run" && "$bin" render "$src/scenes/two_tet_bodies.json" --frames 10 --every 2 --size 65x48 \
  --video clip.mp4 --quiet >"$work/out.txt" 2>"$work/err.txt")
check "render --video exits 0" test $? -eq 0
check "summary on stdout" grep -q "wrote 6 frames to clip.mp4" "$work/out.txt"
check "nothing on stderr with --quiet" test ! -s "$work/err.txt"
check "only the video is left (no PNGs, no output folder)" test "$(ls "$work/run")" = "clip.mp4"
probe() { ffprobe -v error -select_streams v:0 -count_frames -show_entries "stream=$1" -of default=nw=1:nk=1 \
  "$work/run/clip.mp4"; }
check "H.264" test "$(probe codec_name)" = "h264"
check "6 frames (0, 2, ..., 10)" test "$(probe nb_read_frames)" = "6"
check "30 fps (every 2nd frame of dt = 1/60 s)" test "$(probe r_frame_rate)" = "30/1"
check "65x48 padded to 66x48" test "$(probe width),$(probe height)" = "66,48"

# ffmpeg fails (a file name it cannot write): exit 1, an error naming ffmpeg, no partial video.
mkdir "$work/fail"
(cd "$work/fail" && "$bin" render "$src/scenes/two_tet_bodies.json" --frames 2 --size 32x32 --video clip.unknownext \
  --quiet >/dev/null 2>"$work/err3.txt")
check "ffmpeg failing: exit 1" test $? -eq 1
check "ffmpeg failing: the error says so" grep -q "glcollide: error: --video: ffmpeg failed" "$work/err3.txt"
check "ffmpeg failing: no partial video left" test -z "$(ls "$work/fail")"

# No ffmpeg: the binary by its path, a PATH where no ffmpeg is.
mkdir "$work/none"
(cd "$work/none" && PATH=/nonexistent "$bin" render "$src/scenes/two_tet_bodies.json" --frames 2 --video x.mp4 \
  >"$work/out2.txt" 2>"$work/err2.txt")
status=$?
check "without ffmpeg: exit 1" test $status -eq 1
check "without ffmpeg: the error names ffmpeg" grep -q "glcollide: error: --video needs the ffmpeg program" "$work/err2.txt"
check "without ffmpeg: nothing written" test -z "$(ls "$work/none")"
check "without ffmpeg: no simulation ran" test ! -s "$work/out2.txt"
exit $((failures > 0))
