# Helpers for the CLI tests. Each test script is run by ctest as
#   bash SCRIPT path/to/stickslip
# in a fresh temporary directory, and exits non-zero if any check failed.
set -u
BIN=${1:?usage: $0 path/to/stickslip}
PY=${STICKSLIP_PYTHON:-/usr/bin/python3}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/stickslip-cli.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
checks=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

pass() { checks=$((checks + 1)); }

# expect_fail "phrase1|phrase2" ARGS...: the command exits non-zero and its
# stderr contains every phrase (fixed strings). For `sweep`, -o DIR is added
# and DIR must not exist afterwards.
expect_fail() {
  local phrases=$1
  shift
  local out_dir=""
  local args=("$@")
  if [[ ${args[0]} == sweep ]]; then
    out_dir="$WORK/out_$checks"
    args+=(-o "$out_dir")
  fi
  "$BIN" "${args[@]}" >"$WORK/stdout" 2>"$WORK/stderr"
  local rc=$?
  checks=$((checks + 1))
  if [[ $rc -eq 0 ]]; then
    fail "expected a non-zero exit: ${args[*]}"
    return
  fi
  local phrase
  IFS='|' read -r -a list <<<"$phrases"
  for phrase in "${list[@]}"; do
    if ! grep -qF -- "$phrase" "$WORK/stderr"; then
      fail "stderr of '${args[*]}' lacks '$phrase': $(cat "$WORK/stderr")"
    fi
  done
  if [[ -n $out_dir && -e $out_dir ]]; then
    fail "'${args[*]}' failed but created $out_dir"
  fi
}

# run_ok ARGS...: the command succeeds (stdout to $WORK/stdout).
run_ok() {
  "$BIN" "$@" >"$WORK/stdout" 2>"$WORK/stderr"
  local rc=$?
  checks=$((checks + 1))
  [[ $rc -eq 0 ]] || fail "exit $rc from '$*': $(cat "$WORK/stderr")"
  return $rc
}

# expect_eq WHAT ACTUAL EXPECTED
expect_eq() {
  checks=$((checks + 1))
  [[ "$2" == "$3" ]] || fail "$1: got '$2', expected '$3'"
}

finish() {
  echo "$checks checks, $failures failures"
  [[ $failures -eq 0 ]]
  exit $?
}
