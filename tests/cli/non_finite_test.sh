#!/usr/bin/env bash
# glcollide run on a scene that diverges on purpose (explicit substeps far below the stability
# limit for the second body only): a warning naming frame, substep, object and node on stderr at
# the first non-finite state, the record in --stats, exit 3. A stable run of the same kind exits 0.
# usage: non_finite_test.sh GLCOLLIDE_BINARY
set -u
bin=$1
. "$(dirname "$0")/check_lib.sh"
scene() { # scene FILE STIFFNESS_OF_SECOND_BODY
  cat >"$1" <<JSON
{
  "format_version": 1,
  "name": "diverging",
  "effects": ["springs"],
  "time": {"dt": 0.016666666666666666, "substeps": 1, "frames": 20},
  "objects": [
    {"name": "soft box", "generator": {"type": "tet_box", "size": [0.5, 0.5, 0.5], "resolution": [2, 2, 2]},
     "transform": {"translate": [-1, 0, 0], "rotate_deg": [15, 0, 10]}, "mass": 50, "springs": {"stiffness": 10}},
    {"name": "stiff box", "generator": {"type": "tet_box", "size": [0.5, 0.5, 0.5], "resolution": [2, 2, 2]},
     "transform": {"translate": [1, 0, 0], "rotate_deg": [15, 0, 10]}, "mass": 0.5, "springs": {"stiffness": $2}}
  ]
}
JSON
}

scene "$work/diverging.json" 1e6
"$bin" run "$work/diverging.json" --stats "$work/stats.json" --quiet >"$work/out.txt" 2>"$work/err.txt"
rc=$?
check "diverging scene exits 3" test $rc -eq 3
check "warning names frame, substep, object and node" \
  grep -Eq "^glcollide: warning: non-finite position at frame [0-9]+ substep 1 of 1, object 'stiff box' \(1\) node [0-9]+: the simulation diverged" "$work/err.txt"
check "warning printed once" test "$(grep -c 'non-finite position' "$work/err.txt")" -eq 1
check "error line at the end" grep -q "^glcollide: error: the state became non-finite" "$work/err.txt"
check "stats record the first non-finite state" grep -q '"object_name": "stiff box"' "$work/stats.json"
check "stats say not finite" grep -q '"finite": false' "$work/stats.json"

scene "$work/stable.json" 1
"$bin" run "$work/stable.json" --stats "$work/stable_stats.json" --quiet >/dev/null 2>"$work/stable_err.txt"
rc=$?
check "stable scene exits 0" test $rc -eq 0
check "stable scene warns about nothing" test ! -s "$work/stable_err.txt"
check "stable stats: non_finite null" grep -q '"non_finite": null' "$work/stable_stats.json"

echo "cli non-finite: $failures check(s) failed"
exit $((failures > 0))
