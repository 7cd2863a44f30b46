#!/usr/bin/env bash
# Command-line syntax errors read like every other error,
# "stickslip: error: ...", suggest the nearest subcommand or flag, say
# plainly that a flag was repeated, and exit 2 (invalid input), the
# documented code, instead of CLI11's 105 .. 114.
source "$(dirname "$0")/lib.sh" "$@"

# expect_parse_error PHRASES ARGS...: exit 2, stderr starts with the house
# prefix and contains each phrase (separated by '|').
expect_parse_error() {
  local phrases=$1; shift
  "$BIN" "$@" >"$WORK/stdout" 2>"$WORK/stderr"
  local rc=$?
  checks=$((checks + 1))
  [[ $rc -eq 2 ]] || fail "'$*' -> exit $rc, expected 2: $(cat "$WORK/stderr")"
  [[ $(head -c 18 "$WORK/stderr") == "stickslip: error: " ]] ||
    fail "'$*' -> not in the house form: $(cat "$WORK/stderr")"
  local phrase
  IFS='|' read -r -a list <<<"$phrases"
  for phrase in "${list[@]}"; do
    grep -qF -- "$phrase" "$WORK/stderr" || fail "'$*' -> stderr lacks '$phrase': $(cat "$WORK/stderr")"
  done
}

expect_parse_error "unknown subcommand 'swep'|did you mean sweep?" swep
expect_parse_error "unknown subcommand 'simulat'|did you mean simulate?" simulat --mu 5
expect_parse_error "a subcommand is required|simulate, sweep, reproduce, merge"
expect_parse_error "unknown flag '--lamda'|did you mean --lambda?" sweep --lamda 1,2 -o x
expect_parse_error "unknown flag '--realisations'|did you mean --realizations?" sweep --realisations 5 -o x
expect_parse_error "unknown flag '--trajectroy'|did you mean --trajectory?" simulate --trajectroy 0.1
expect_parse_error "unknown flag '--zzzzzz'" simulate --zzzzzz
expect_parse_error "--mu is given 2 times|give each flag once" simulate --mu 5 --mu 6
expect_parse_error "--lambda is given 2 times" sweep --lambda 1 --switch-rate 2 -o x
expect_parse_error "--output" sweep --lambda 1
expect_parse_error "--mu needs a value (X)" simulate --mu
expect_parse_error "--seed needs a value (S)" sweep --seed --lambda 1 -o x
expect_parse_error "--format" simulate --format xml
expect_parse_error "--switch-times" simulate --switch-times 1 --switch-times-file x
[[ ! -e x ]] || fail "a parse error created x"

# --help and --version still succeed.
run_ok --version
run_ok sweep --help
finish
