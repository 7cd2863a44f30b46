# Laws for uncertain parameters: every bad law exits 2 with a message naming
# the parameter, the law and what is wrong (the domain, for a law whose
# support leaves it), and writes nothing (expect_fail: no -o DIR created).
# The same for TOML keys, `simulate` without --realization, and `peak`.
source "$(dirname "$0")/lib.sh"

# expect_bad "phrase|..." ARGS...: expect_fail, and the exit status is 2.
expect_bad() {
  expect_fail "$@"
  local phrases=$1
  shift
  local args=("$@")
  [[ ${args[0]} == sweep ]] && args+=(-o "$WORK/not_created")
  "$BIN" "${args[@]}" >/dev/null 2>&1
  expect_eq "exit status of '${args[*]}'" "$?" 2
  [[ -e $WORK/not_created ]] && fail "'${args[*]}' created its output directory"
}

base=(sweep --k 40 --lambda 1,3.8 --realizations 20)
# unknown law, missing / extra / repeated / positional arguments
expect_bad "--mu: gama(mean=5,cv=0.2)|unknown law 'gama'|known laws: uniform" \
  "${base[@]}" --mu 'gama(mean=5,cv=0.2)'
expect_bad "--mu: gamma(mean=5)|cv is missing|gamma(mean=M,cv=C)" "${base[@]}" --mu 'gamma(mean=5)'
expect_bad "--mu: gamma(mean=5,cv=0.2,sd=1)|gamma has no argument 'sd'" \
  "${base[@]}" --mu 'gamma(mean=5,cv=0.2,sd=1)'
expect_bad "--mu: gamma(mean=5,mean=6)|mean is given twice" "${base[@]}" --mu 'gamma(mean=5,mean=6)'
expect_bad "--mu: gamma(5,0.2)|must be named" "${base[@]}" --mu 'gamma(5,0.2)'
expect_bad "--mu: uniform(1,2,3)|3 arguments|uniform takes 2" "${base[@]}" --mu 'uniform(1,2,3)'
expect_bad "--mu: uniform(min=3,max=2)|A < B" "${base[@]}" --mu 'uniform(min=3,max=2)'
expect_bad "--k: gamma(mean=40,cv=nan)|not a finite number" sweep --k 'gamma(mean=40,cv=nan)'
expect_bad "--mu: gamma(mean=5,cv=0.2|" "${base[@]}" --mu 'gamma(mean=5,cv=0.2'
# supports that leave the parameter's domain
expect_bad "--m: normal(mean=1,sd=0.1)|can give values <= 0|m must be > 0" \
  "${base[@]}" --m 'normal(mean=1,sd=0.1)'
expect_bad "--lambda: uniform(min=-1,max=2)|lambda must be > 0" sweep --lambda 'uniform(-1,2)'
expect_bad "--c: normal(mean=0.1,sd=0.01)|c must be >= 0" "${base[@]}" --c 'normal(mean=0.1,sd=0.01)'
expect_bad "--mu-k: uniform(min=1,max=6)|can exceed mu_s = 5|mu_k must be <= mu_s" \
  "${base[@]}" --mu-s 5 --mu-k 'uniform(1,6)'
expect_bad "--mu-k: uniform(min=1,max=4)|can exceed --mu-s: uniform(min=3,max=5)|mu_k must be <= mu_s" \
  "${base[@]}" --mu-s 'uniform(3,5)' --mu-k 'uniform(1,4)'
expect_bad "--mu: gamma(mean=5,cv=0.2)|has no effect|one of them is given" "${base[@]}" --mu 'gamma(mean=5,cv=0.2)' --mu-s 6
# TOML keys: the key and its position instead of the flag
cat >bad.toml <<'TOML'
[model]
k = 40
mu = "gamma(mean=5)"
TOML
expect_bad "model.mu at bad.toml:3:6|gamma(mean=5)|cv is missing" sweep --config bad.toml
cat >domain.toml <<'TOML'
[model]
m = "normal(mean=1,sd=0.1)"
TOML
expect_bad "--m: normal(mean=1,sd=0.1)|m must be > 0" sweep --config domain.toml
# a sensitivity study's resolved config is not a sweep's
cat >study.toml <<'TOML'
[model]
mu = "uniform(2,7)"
[sweep]
sensitivity_statistic = "R"
TOML
expect_bad "--config: 'study.toml'|sensitivity_statistic|stickslip sensitivity" sweep --config study.toml
expect_bad "--lambda: normal(mean=1,sd=0.5)|lambda must be > 0" sweep --lambda 'normal(mean=1,sd=0.5)'
expect_bad "--mu-k: uniform(min=4,max=6)|can exceed mu_s = 5" sweep --mu-k 'uniform(4,6)'
# a law and a [grid] axis for one parameter, whichever table comes first
printf '[grid]\nlambda = [1, 2]\n[model]\nlambda = "uniform(1,2)"\n' >both.toml
expect_bad "model.lambda at both.toml:4:10|a law or a [grid] axis, not both" sweep --config both.toml
printf '[model]\nlambda = "uniform(1,2)"\n[grid]\nlambda = [1, 2]\n' >both2.toml
expect_bad "lambda|a law or a [grid] axis, not both" sweep --config both2.toml
# simulate: a law needs --realization; fixed inputs do not go with it
expect_bad "--realization|a realization index R|--mu is gamma(mean=5,cv=0.2)" \
  simulate --mu 'gamma(mean=5,cv=0.2)'
expect_bad "--x0|not with a law|--mu is gamma(mean=5,cv=0.2)" \
  simulate --mu 'gamma(mean=5,cv=0.2)' --realization 3 --x0 0.1
expect_bad "--m: normal(mean=1,sd=0.1)|m must be > 0" simulate --m 'normal(mean=1,sd=0.1)' --realization 0
# peak locates the maximum of one model
expect_bad "invalid --mu|'gamma(mean=5,cv=0.2)'|does not take laws" \
  peak --mu 'gamma(mean=5,cv=0.2)'
# the refusals came before any output file: no simulate -o file either
"$BIN" simulate --mu 'gamma(mean=5)' --realization 1 -o ep.csv >/dev/null 2>&1
[[ -e ep.csv ]] && fail "a refused simulate wrote ep.csv"
finish
