# `sweep` rejects bad flags, grids and TOML files before any work: non-zero
# exit, a message naming the key and the value, and nothing written to DIR
# (DIR is not even created). expect_fail adds -o DIR and checks that.
source "$(dirname "$0")/lib.sh"

# non-finite and <= 0 values, as fixed values and inside grids
for p in m k g mu V lambda ta; do
  expect_fail "--$p|'nan'|finite" sweep --$p nan --realizations 10
  expect_fail "--$p|'inf'|finite" sweep --$p inf --realizations 10
  expect_fail "--$p|'1,nan'|not finite" sweep --$p 1,nan --realizations 10
  expect_fail "$p (|0|> 0" sweep --$p 0 --realizations 10
  expect_fail "--$p|'1,-2'|entry #2 = -2" sweep --$p 1,-2 --realizations 10
done
# bad grid specifications
expect_fail "--lambda|''|empty list" sweep --lambda ''
expect_fail "--lambda|'0.1,,2'|empty entry" sweep --lambda 0.1,,2
expect_fail "--lambda|'log:0.1:30:0'|n >= 1" sweep --lambda log:0.1:30:0
expect_fail "--mu|'lin:0.5:7:-1'|n >= 1" sweep --mu lin:0.5:7:-1
expect_fail "--mu|'lin:0.5:7:2.5'|whole number" sweep --mu lin:0.5:7:2.5
expect_fail "--lambda|'log:0:30:4'|a = 0" sweep --lambda log:0:30:4
expect_fail "--lambda|'log:nan:30:4'|not finite" sweep --lambda log:nan:30:4
expect_fail "--lambda|'-0.1,0.5'|entry #1 = -0.1" sweep --lambda=-0.1,0.5
expect_fail "--lambda|'lin:1:2'|4 fields" sweep --lambda lin:1:2
expect_fail "--lambda|'0.1,0.5x'|trailing" sweep --lambda 0.1,0.5x
# run settings
expect_fail "--realizations|'0'" sweep --realizations 0
expect_fail "--realizations|'-5'" sweep --realizations -5
expect_fail "--seed|'-1'" sweep --seed -1
expect_fail "--block-size|'0'" sweep --block-size 0
expect_fail "--bins|'0'" sweep --bins 0
expect_fail "--threads|'two'" sweep --threads two --realizations 10
expect_fail "lambda * ta|max_events" sweep --lambda 1000 --max-events 100
expect_fail "max_events|'9007199254740993'|2^53" sweep --max-events 9007199254740993
# unknown flags; -o is required
expect_fail "--bogus" sweep --bogus 1
expect_fail "--lamda" sweep --lamda 1
"$BIN" sweep --realizations 10 >/dev/null 2>"$WORK/stderr"
expect_eq "exit status without -o is non-zero" "$([[ $? -ne 0 ]] && echo yes)" yes
grep -qF -- "--output" "$WORK/stderr" || fail "missing -o is not reported: $(cat "$WORK/stderr")"

# bad TOML files: syntax errors with file:line:col, unknown keys, wrong types
printf '[model]\nm = 1\nk = \n' >syntax.toml
expect_fail "syntax.toml:3:|syntax error" sweep --config syntax.toml
printf '[grid\nlambda = [1]\n' >syntax2.toml
expect_fail "syntax2.toml:1:|syntax error" sweep --config syntax2.toml
printf '[model]\nmass = 2\n' >unknown_key.toml
expect_fail "'model.mass'|unknown_key.toml:2:1" sweep --config unknown_key.toml
printf '[grids]\nlambda = [1]\n' >unknown_table.toml
expect_fail "'grids'|unknown_table.toml:1:" sweep --config unknown_table.toml
printf '[sweep]\nrealizations = "many"\n' >wrong_type.toml
expect_fail "sweep.realizations|wrong_type.toml:2:16|an integer from 1 to 2^40|a string" sweep --config wrong_type.toml
printf '[model]\nmu = true\n' >wrong_type2.toml
expect_fail "model.mu|a number|a boolean" sweep --config wrong_type2.toml
printf '[grid]\nlambda = "log:0.1:30:0"\n' >bad_grid.toml
expect_fail "grid.lambda|bad_grid.toml:2:|n >= 1" sweep --config bad_grid.toml
printf '[grid]\nmu = []\n' >empty_grid.toml
expect_fail "grid.mu|empty" sweep --config empty_grid.toml
printf '[grid]\nlambda = [0.5, -2]\n' >negative_rate.toml
expect_fail "grid.lambda[1]|-2|> 0" sweep --config negative_rate.toml
printf '[model]\nk = -4\n' >bad_value.toml
expect_fail "k (stiffness)|-4|> 0" sweep --config bad_value.toml
expect_fail "missing.toml" sweep --config missing.toml

# -o pointing at a file is refused before the run, and the file is kept
echo keep >a_file
"$BIN" sweep --realizations 10 -o a_file >/dev/null 2>"$WORK/stderr"
expect_eq "exit status for -o FILE" "$?" 2
expect_eq "the file is untouched" "$(cat a_file)" keep
# a grid whose point count overflows 64 bits must not wrap to 0 points
expect_fail "number of grid points|<= 1e7" sweep --lambda lin:1:2:65536 --mu lin:1:2:65536 \
  --k lin:1:2:65536 --m lin:1:2:65536 --realizations 1
# a directory or a device is not a config file
expect_fail "not a regular file" sweep --config /tmp
expect_fail "not a regular file" sweep --config /dev/zero
finish
