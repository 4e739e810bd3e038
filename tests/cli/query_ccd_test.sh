#!/usr/bin/env bash
# End-to-end checks of `glcollide query ccd`: small CSVs whose answers are derived by hand (a
# vertex through a triangle, an edge across an edge, near misses, a minimum separation), both row
# formats, --toi, --out with its summary, and one-line errors naming file and line, with a
# non-zero exit, for bad rows and bad options.
# usage: query_ccd_test.sh GLCOLLIDE_BINARY
set -u
bin=$1
. "$(dirname "$0")/check_lib.sh"

# Vertex-face: the triangle (0,0,0) (1,0,0) (0,1,0) never moves. Rows 1-4 at t = 0, 5-8 at t = 1.
cat >"$work/vf.csv" <<'CSV'
# 1: the vertex falls through the interior point (1/4, 1/4, 0) at t = 1/2
0.25,0.25,-1
0,0,0
1,0,0
0,1,0
0.25,0.25,1
0,0,0
1,0,0
0,1,0
# 2: the vertex slides at height 1 above the triangle: never within 0
0.25, 0.25, 1
0, 0, 0
1, 0, 0
0, 1, 0
0.5, 0.5, 1
0, 0, 0
1, 0, 0
0, 1, 0
# 3: the vertex falls past the triangle's hypotenuse side, at (2, 2): never touches
2,2,-1
0,0,0
1,0,0
0,1,0
2,2,1
0,0,0
1,0,0
0,1,0
# 4: as integer pairs: the vertex rests 1/3 above the interior point (1/4, 1/4)
1,4,1,4,1,3
0,1,0,1,0,1
1,1,0,1,0,1
0,1,1,1,0,1
1,4,1,4,1,3
0,1,0,1,0,1
1,1,0,1,0,1
0,1,1,1,0,1
CSV

# Edge-edge: edge A from (-1,0,0) to (1,0,0) never moves.
cat >"$work/ee.csv" <<'CSV'
# 1: edge B, across A, falls from z = 1 to z = -1: crosses it at t = 1/2
-1,0,0
1,0,0
0,-1,1
0,1,1
-1,0,0
1,0,0
0,-1,-1
0,1,-1
# 2: edge B, parallel to A at height 1, moves sideways: never within 0
-1,0,0
1,0,0
-1,0,1
1,0,1
-1,0,0
1,0,0
-1,5,1
1,5,1
# 3: as integer pairs: edge B rests across A, 1/3 above it
-1,1,0,1,0,1
1,1,0,1,0,1
0,1,-1,1,1,3
0,1,1,1,1,3
-1,1,0,1,0,1
1,1,0,1,0,1
0,1,-1,1,1,3
0,1,1,1,1,3
CSV

out=$("$bin" query ccd --in "$work/vf.csv" --kind vf 2>"$work/err.txt")
check "vf exits 0" test $? -eq 0
check "vf answers on stdout" test "$out" = $'1\n0\n0\n0'
check "nothing on stderr" test ! -s "$work/err.txt"

out=$("$bin" query ccd --in "$work/vf.csv" --kind vf --toi)
check "--toi exits 0" test $? -eq 0
check "--toi: 1 with a time, 0 with time 1" test "$(echo "$out" | sed -n '2,4p')" = $'0,1\n0,1\n0,1'
# The crossing is at t = 1/2: the time of impact is never later, and at most the CCD's time
# tolerance (2^-12) plus its error bound earlier; 0.49 leaves ample room for both.
check "--toi: the crossing's time" awk -F, 'NR == 1 { exit !($1 == 1 && $2 > 0.49 && $2 <= 0.5) }' <<<"$out"

out=$("$bin" query ccd --in "$work/vf.csv" --kind vf --min-separation 0.34)
check "the resting vertex is within 0.34" test "$(echo "$out" | sed -n 4p)" = 1
out=$("$bin" query ccd --in "$work/vf.csv" --kind vf --min-separation 0.32)
check "the resting vertex is not within 0.32" test "$(echo "$out" | sed -n 4p)" = 0
check "min separation 0.32 keeps the sliding vertex apart" test "$(echo "$out" | sed -n 2p)" = 0

out=$("$bin" query ccd --in "$work/ee.csv" --kind ee --toi)
check "ee exits 0" test $? -eq 0
check "ee answers" test "$(echo "$out" | cut -d, -f1)" = $'1\n0\n0'
check "ee: the crossing's time" awk -F, 'NR == 1 { exit !($2 > 0.49 && $2 <= 0.5) }' <<<"$out"
out=$("$bin" query ccd --in "$work/ee.csv" --kind ee --min-separation 0.34)
check "ee: the resting edge is within 0.34" test "$(echo "$out" | sed -n 3p)" = 1

# Rounding: a vertex lies on a tilted triangle 1024 from the origin, exactly in rationals (the
# triangle's corner z = 1024 + 1/3 is not a float). Rounded to float the vertex is 1/32768 off the
# plane; the answer must still be 1 (docs/ccd.md, "query ccd").
cat >"$work/rounded.csv" <<'CSV'
8193,8,3,4,4097,4,1
1024,1,0,1,1024,1,1
1025,1,0,1,1024,1,1
1024,1,1,1,3073,3,1
8193,8,3,4,4097,4,1
1024,1,0,1,1024,1,1
1025,1,0,1,1024,1,1
1024,1,1,1,3073,3,1
CSV
"$bin" query ccd --in "$work/rounded.csv" --kind vf --out "$work/result.csv" >"$work/summary.txt"
check "--out exits 0" test $? -eq 0
check "the rounded touch is found" test "$(cat "$work/result.csv")" = 1
check "summary names counts" grep -q "^1 queries, 1 may collide, 0 capped (vf, budget 21844, 0 continued in up to 4 rounds, [0-9]* boxes, 1 rounded to float" "$work/summary.txt"
check "summary compares with the ground truth column" grep -q "against the file's ground truth: 0 false negatives, 0 false positives" "$work/summary.txt"
check "summary names the renderer" grep -q " | " "$work/summary.txt"

# Bad rows: exit 1, one line naming file:line and the problem.
bad() { # bad NAME LINE_NUMBER PATTERN CSV_TEXT [OPTIONS...]
  local name=$1 line=$2 pattern=$3 text=$4
  shift 4
  printf '%s' "$text" >"$work/bad.csv"
  "$bin" query ccd --in "$work/bad.csv" --kind ee "$@" >/dev/null 2>"$work/bad.txt"
  local rc=$?
  check "$name exits 1" test $rc -eq 1
  check "$name names line $line" grep -q "bad.csv:$line: $pattern" "$work/bad.txt"
  check "$name is one line" test "$(wc -l <"$work/bad.txt")" -eq 1
}
row='1,2,3,4,5,6'
rows7=$(printf '%s\n' "$row" "$row" "$row" "$row" "$row" "$row" "$row")
bad "short row" 3 "expected x,y,z as 6 integers.*got 2 fields" $'# c\n'"$row"$'\n1,2\n'
bad "non-integer" 1 "field 3 'x' is not an integer" '1,2,x,4,5,6'
bad "zero denominator" 2 "field 2 '0' is not a positive denominator" "$row"$'\n1,0,3,4,5,6\n'
bad "non-number" 1 "field 2 'nan' is not a decimal number" '1,nan,3'
bad "out of float range" 1 "field 3 '1e39' is outside float range" '1,2,1e39'
bad "ground truth" 1 "field 7 '2' (ground truth) is not 0 or 1" '1,2,3,4,5,6,2'
bad "truncated query" 10 "the file ends inside this query: 2 of its 8 rows" "$rows7"$'\n'"$row"$'\n\n'"$row"$'\n'"$row"$'\n'

"$bin" query ccd --in "$work/missing.csv" --kind vf >/dev/null 2>"$work/missing.txt"
check "missing input exits 1" test $? -eq 1
check "missing input named" grep -q "missing.csv" "$work/missing.txt"
"$bin" query ccd --in "$work/ee.csv" --kind ff >/dev/null 2>&1
check "unknown kind rejected" test $? -ne 0
"$bin" query ccd --in "$work/ee.csv" >/dev/null 2>&1
check "--kind required" test $? -ne 0
"$bin" query ccd --in "$work/ee.csv" --kind ee --min-separation -0.5 >/dev/null 2>"$work/opt.txt"
check "negative separation exits 1" test $? -eq 1
check "negative separation named" grep -q "min-separation: -0.5 is negative" "$work/opt.txt"
"$bin" query ccd --in "$work/ee.csv" --kind ee --min-separation 1e-3x >/dev/null 2>"$work/opt.txt"
check "non-number separation named" grep -q "min-separation: '1e-3x' is not a decimal number" "$work/opt.txt"
"$bin" query ccd --in "$work/ee.csv" --kind ee --budget 0 >/dev/null 2>"$work/opt.txt"
check "budget 0 exits 1" test $? -eq 1
check "budget 0 named" grep -q "budget: expected at least 1" "$work/opt.txt"

echo "$failures failure(s)"
test $failures -eq 0
