#!/usr/bin/env bash
# End-to-end checks of `glcollide query tritri`: a small CSV with answers derived by hand (both
# precisions where fast is known to be right, robust where it matters), stdout and --out, and
# one-line errors naming file and line, with a non-zero exit, for bad rows.
# usage: query_test.sh GLCOLLIDE_BINARY
set -u
bin=$1
. "$(dirname "$0")/check_lib.sh"

# Triangle A is the unit right triangle in z = 0. Expected answers in the comments.
cat >"$work/pairs.csv" <<'CSV'
# a0 a1 a2 b0 b1 b2 (x,y,z each)
0,0,0, 1,0,0, 0,1,0,   0.25,0.25,-1, 0.25,0.25,1, 1,1,1
0,0,0, 1,0,0, 0,1,0,   0.25,0.25,0.5, 0.25,0.25,1, 1,1,1

 0, 0, 0,  1, 0, 0,  0, 1, 0,  1, 0, 0,  2, 0, 1,  2, 1, 0
0,0,0,1,0,0,0,1,0,2,2,2,3,2,2,2,3,2
0,0,0,1,0,0,0,1,0,0.25,0.25,0,0.25,0.25,0,0.25,0.25,0
0,0,0,1,0,0,0,1,0,0.25,0.25,1e-45,0.25,0.25,1,1,1,1
CSV
expected=$'1\n0\n1\n0\n1\n0'  # pierce, above, shared vertex, far, point on face, one denormal step above

out=$("$bin" query tritri --in "$work/pairs.csv" 2>"$work/err.txt")
check "robust exits 0" test $? -eq 0
check "robust answers on stdout" test "$out" = "$expected"
check "nothing on stderr" test ! -s "$work/err.txt"

"$bin" query tritri --in "$work/pairs.csv" --precision robust --out "$work/result.csv" >"$work/summary.txt"
check "--out exits 0" test $? -eq 0
check "--out file has the answers" test "$(cat "$work/result.csv")" = "$expected"
check "summary names counts" grep -q "6 pairs, 3 intersecting (robust precision" "$work/summary.txt"

out=$("$bin" query tritri --in "$work/pairs.csv" --precision fast)
check "fast exits 0" test $? -eq 0
# Fast is right on the clear-cut rows 1, 2, 4 (its epsilon decides the others).
check "fast on clear-cut rows" test "$(echo "$out" | sed -n '1p;2p;4p' | tr -d '\n')" = "100"
check "fast answers every row" test "$(echo "$out" | wc -l)" -eq 6

# Bad rows: exit 1, one line naming file:line and the problem.
bad() { # bad NAME LINE_NUMBER PATTERN CSV_TEXT
  printf '%s' "$4" >"$work/bad.csv"
  "$bin" query tritri --in "$work/bad.csv" >/dev/null 2>"$work/bad.txt"
  local rc=$?
  check "$1 exits 1" test $rc -eq 1
  check "$1 names line $2" grep -q "bad.csv:$2: $3" "$work/bad.txt"
  check "$1 is one line" test "$(wc -l <"$work/bad.txt")" -eq 1
}
row='0,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,2'
bad "short row" 3 "expected 18 numbers" $'# c\n'"$row"$'\n1,2,3\n'
bad "non-number" 1 "field 2 'abc' is not a number" '0,abc,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,2'
bad "nan" 2 "field 18 'nan' is not finite" $'\n0,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,nan'
bad "out of float range" 1 "field 1 '1e39' is outside float range" '1e39,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,2'

"$bin" query tritri --in "$work/missing.csv" >/dev/null 2>"$work/missing.txt"
check "missing input exits 1" test $? -eq 1
check "missing input named" grep -q "missing.csv" "$work/missing.txt"
"$bin" query tritri --in "$work/pairs.csv" --precision exact >/dev/null 2>&1
check "unknown precision rejected" test $? -ne 0

echo "$failures failure(s)"
test $failures -eq 0
