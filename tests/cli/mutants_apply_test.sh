#!/usr/bin/env bash
# Every deliberate bug of tests/mutants/ still applies to the tree (scripts/mutants.sh, which CI
# does not run, refuses a stale one only when someone runs it): a change to the code a mutant
# mutates must update the mutant with it. Needs git and a checkout (a clone of the repository).
set -euo pipefail
src=$1
cd "$src"
[ -d .git ] || git rev-parse --git-dir >/dev/null 2>&1 || { echo "FAIL: $src is not a git checkout"; exit 1; }
stale=0
for m in tests/mutants/*.patch; do
  if ! git apply --check --unidiff-zero "$m" 2>/dev/null; then
    echo "stale mutant: $m (git apply --check fails)"
    stale=$((stale + 1))
  fi
  grep -q '^# Kills: ' "$m" || { echo "mutant without a '# Kills:' line: $m"; stale=$((stale + 1)); }
done
[ "$stale" -eq 0 ] || { echo "FAIL: $stale mutants to update"; exit 1; }
echo "all $(ls tests/mutants/*.patch | wc -l) mutants apply"
