#!/usr/bin/env bash
# scripts/check-skips.sh on made-up ctest logs: a run with only allowed "did not run" entries
# passes; an unlisted skip (a parameterised name included) fails and is named.
set -euo pipefail
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
check() { "$src/scripts/check-skips.sh" "$1" >"$work/out" 2>&1; }

printf '100%% tests passed, 0 tests failed out of 3\n\nThe following tests did not run:\n\t272 - NoEglChild.CreateContext (Disabled)\n' >"$work/allowed.log"
check "$work/allowed.log" || { cat "$work/out"; echo "FAIL: an allowed entry was refused"; exit 1; }

printf 'The following tests did not run:\n\t272 - NoEglChild.CreateContext (Disabled)\n\t300 - Sizes/Foo.Bar/1  # GetParam() = 3 (Skipped)\n' >"$work/skip.log"
if check "$work/skip.log"; then cat "$work/out"; echo "FAIL: an unlisted skip passed"; exit 1; fi
grep -q 'Sizes/Foo.Bar/1  # GetParam() = 3 did not run (Skipped)' "$work/out" ||
  { cat "$work/out"; echo "FAIL: the skipped test is not named"; exit 1; }

printf '100%% tests passed, 0 tests failed out of 3\n' >"$work/none.log"
check "$work/none.log" || { cat "$work/out"; echo "FAIL: a log without skips was refused"; exit 1; }
echo "check-skips: ok"
