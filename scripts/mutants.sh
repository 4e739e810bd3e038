#!/usr/bin/env bash
# Checks that the tests can fail: applies each deliberate bug in tests/mutants/*.patch, one at a
# time, to a scratch copy of the tree, rebuilds it and runs the tests its "# Kills:" line names.
# A mutant that no named test notices (they all pass) is a blind spot, and the script fails.
#
#   scripts/mutants.sh            every mutant
#   scripts/mutants.sh NAME...    the mutants whose file name contains one of the NAMEs
#
# A mutant file is a unified diff (git apply) after a header of "# " lines:
#   # Mutant: what the deliberate bug does (one line)
#   # Kills: a ctest -R regex of the tests that must notice it
#   # Why: the property those tests hold (optional, any number of lines)
# The scratch copy lives in $GLCOLLIDE_MUTANT_DIR (default /tmp/glcollide-mutants) and its build
# is kept between runs, so a mutant costs one incremental build. Project habit (issue 21): every
# new test of a hard property comes with the mutant it kills.
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$(pwd)
scratch=${GLCOLLIDE_MUTANT_DIR:-${TMPDIR:-/tmp}/glcollide-mutants}
tree=$scratch/tree
build=$scratch/build
export LP_NUM_THREADS=${LP_NUM_THREADS:-$(nproc)}

mutants=()
for patch in tests/mutants/*.patch; do
  [ -e "$patch" ] || continue
  if [ $# -eq 0 ]; then
    mutants+=("$patch")
  else
    for want in "$@"; do
      case "$(basename "$patch")" in *"$want"*) mutants+=("$patch") ;; esac
    done
  fi
done
if [ ${#mutants[@]} -eq 0 ]; then
  echo "mutants: no mutant matches ${*:-tests/mutants/*.patch}" >&2
  exit 2
fi

header() { # header FIELD FILE: the value of "# FIELD:" in a mutant's header
  sed -n "s/^# $1: *//p" "$2" | head -n 1
}

# The scratch copy of the tracked and untracked-but-not-ignored files is updated by content: a
# file is copied (with a new modification time) only when it differs, so the kept build
# recompiles exactly what changed since the last run. Copying modification times instead would
# hide a change made while an earlier scratch build was running.
mkdir -p "$tree" "$build"
git -C "$source_dir" ls-files -z --cached --others --exclude-standard >"$scratch/files"
while IFS= read -r -d '' f; do
  [ -f "$source_dir/$f" ] || continue # deleted in the work tree, not yet in the index
  if ! cmp -s "$source_dir/$f" "$tree/$f"; then
    mkdir -p "$tree/$(dirname "$f")"
    cp "$source_dir/$f" "$tree/$f"
  fi
done <"$scratch/files"
# Files that left the source tree leave the copy too.
(cd "$tree" && find . -type f -printf '%P\0') | while IFS= read -r -d '' f; do
  [ -e "$source_dir/$f" ] || rm -f "$tree/$f"
done

cmake -S "$tree" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$scratch/configure.log" 2>&1 ||
  { cat "$scratch/configure.log" >&2; exit 1; }

build_tree() {
  cmake --build "$build" -j "$(nproc)" >"$scratch/build.log" 2>&1
}
run_tests() { # run_tests REGEX: ctest's status (0: all named tests passed)
  ctest --test-dir "$build" -R "$1" --no-tests=error --timeout 900 >"$scratch/ctest.log" 2>&1
}

# The unmutated tree must pass every named test, or a "kill" would mean nothing.
build_tree || { tail -n 40 "$scratch/build.log" >&2; echo "mutants: the unmutated tree does not build" >&2; exit 1; }
all_kills=$(for m in "${mutants[@]}"; do header Kills "$m"; done | paste -sd '|')
if ! run_tests "$all_kills"; then
  tail -n 40 "$scratch/ctest.log" >&2
  echo "mutants: the unmutated tree fails the named tests" >&2
  exit 1
fi

survivors=0
for m in "${mutants[@]}"; do
  name=$(basename "$m" .patch)
  kills=$(header Kills "$m")
  if [ -z "$kills" ]; then
    echo "mutants: $m has no '# Kills:' line" >&2
    exit 2
  fi
  # A regex that names no test would "kill" every mutant (ctest fails on no tests): refuse it.
  if ! ctest --test-dir "$build" -N -R "$kills" | grep -qE '^\s*Test +#'; then
    echo "mutants: $m: '# Kills: $kills' matches no test (a ctest -R regex; alternatives with |)" >&2
    exit 2
  fi
  if ! git -C "$tree" apply --unidiff-zero "$source_dir/$m" 2>"$scratch/apply.log"; then
    cat "$scratch/apply.log" >&2
    echo "mutants: $m no longer applies: update it with the code it mutates" >&2
    exit 2
  fi
  verdict=
  if ! build_tree; then
    verdict="does not build (a mutant must compile: fix it)"
    survivors=$((survivors + 1))
  elif run_tests "$kills"; then
    verdict="SURVIVED: every test matching '$kills' passed"
    survivors=$((survivors + 1))
  else
    failed=$(grep -E '^\s+[0-9]+ - ' "$scratch/ctest.log" | sed -E 's/^\s*[0-9]+ - //; s/ \(Failed\)$//' | paste -sd ',' | cut -c1-160)
    verdict="killed by ${failed:-the named tests}"
  fi
  git -C "$tree" apply -R --unidiff-zero "$source_dir/$m"
  printf '%-44s %s\n' "$name" "$verdict"
done
build_tree || true # leave the scratch build unmutated for the next run

if [ "$survivors" -ne 0 ]; then
  echo "mutants: $survivors of ${#mutants[@]} not killed" >&2
  exit 1
fi
echo "mutants: all ${#mutants[@]} killed"
