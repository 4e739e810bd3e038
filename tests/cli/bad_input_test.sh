#!/usr/bin/env bash
# Every bad input in tests/data/bad/ must fail cleanly: exit status 1 (not a crash, not a hang),
# and exactly one line on stderr, "glcollide: error: ...", containing every substring that
# tests/data/bad/expected.txt lists for it (the file, the JSON pointer or line, what is wrong).
# .json cases run `glcollide run FILE --frames 1 --quiet`; .csv cases `glcollide query tritri --in FILE`.
# usage: bad_input_test.sh GLCOLLIDE_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
dir=$src/tests/data/bad
manifest=$dir/expected.txt
. "$(dirname "$0")/check_lib.sh" # $work and the failure counter (this script reports with fail())
cases=0
fail() { echo "FAIL $1: $2"; failures=$((failures + 1)); }

while IFS= read -r line || [ -n "$line" ]; do
  case $line in ''|'#'*) continue ;; esac
  IFS=$'\t' read -r -a fields <<<"$line"
  file=${fields[0]}
  cases=$((cases + 1))
  if [ "${#fields[@]}" -lt 2 ]; then fail "$file" "manifest line has no expected substring"; continue; fi
  if [ ! -f "$dir/$file" ]; then fail "$file" "file missing"; continue; fi
  if [[ $file == *.csv ]]; then
    timeout 60 "$bin" query tritri --in "$dir/$file" >"$work/out" 2>"$work/err"
  else
    timeout 60 "$bin" run "$dir/$file" --frames 1 --quiet >"$work/out" 2>"$work/err"
  fi
  rc=$?
  err=$(cat "$work/err")
  ok=1
  if [ $rc -eq 124 ]; then fail "$file" "timed out after 60 s"; continue; fi
  if [ $rc -ne 1 ]; then fail "$file" "exit status $rc, expected 1 (0: accepted; >128: signal)"; ok=0; fi
  nlines=$(wc -l <"$work/err")
  if [ "$nlines" -ne 1 ]; then fail "$file" "$nlines lines on stderr, expected 1"; ok=0; fi
  if [[ $err != "glcollide: error: "* ]]; then fail "$file" "stderr does not start with 'glcollide: error: '"; ok=0; fi
  for ((k = 1; k < ${#fields[@]}; k++)); do
    if [[ $err != *"${fields[k]}"* ]]; then fail "$file" "stderr lacks '${fields[k]}'"; ok=0; fi
  done
  if [ $ok -eq 1 ]; then echo "ok   $file"; else echo "     stderr: $err"; fi
done <"$manifest"

# Every .json/.csv file in the folder must be a listed case (a new file cannot be forgotten).
for f in "$dir"/*.json "$dir"/*.csv; do
  name=$(basename "$f")
  grep -q "^$name"$'\t' "$manifest" || fail "$name" "not listed in expected.txt"
done

echo "$cases cases, $failures failures"
if [ "$cases" -lt 40 ]; then echo "FAIL: fewer than 40 cases"; exit 1; fi
[ $failures -eq 0 ]
