# Sourced by the CLI test scripts: a scratch folder `$work` removed on exit, a failure counter and
# `check NAME COMMAND...`, which runs COMMAND and prints "ok   NAME" or "FAIL NAME" (counting it).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # check NAME CONDITION...
  local name=$1; shift
  if "$@"; then echo "ok   $name"; else echo "FAIL $name"; failures=$((failures + 1)); fi
}
