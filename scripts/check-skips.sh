#!/usr/bin/env bash
# Fails when a ctest log lists a test that did not run (skipped or disabled) and that
# tests/skips/allowed.txt does not allow. Usage: scripts/check-skips.sh CTEST_LOG
set -euo pipefail
cd "$(dirname "$0")/.."
log=$1
allowed=$(grep -Ev '^\s*(#|$)' tests/skips/allowed.txt | paste -sd '|')
# ctest ends its output with "The following tests did not run:" and lines "<tab>N - NAME (Reason)".
not_run=$(sed -n '/^The following tests did not run:/,/^[^[:space:]]/p' "$log" |
  sed -n 's/^\s*[0-9]\+ - \(.*\) (\([A-Za-z ]*\))$/\1\t\2/p')
unexpected=0
while IFS=$'\t' read -r name reason; do
  [ -n "$name" ] || continue
  if [ -n "$allowed" ] && printf '%s\n' "$name" | grep -Eqx "$allowed"; then
    echo "check-skips: $name ($reason): allowed by tests/skips/allowed.txt"
  else
    echo "check-skips: error: $name did not run ($reason) and tests/skips/allowed.txt does not allow it" >&2
    unexpected=$((unexpected + 1))
  fi
done <<<"$not_run"
if [ "$unexpected" -ne 0 ]; then
  echo "check-skips: $unexpected test(s) skipped without being allowed" >&2
  exit 1
fi
