#!/usr/bin/env bash
# `reproduce --resume` onto a folder that holds a finished
# reproduction and no journals (OUT/.runs) never replaces it. Other settings
# are refused (exit 2, naming the folder, the difference and what to do); the
# same settings are "already complete" and the folder is left byte-identical
# with its modification times.
source "$(dirname "$0")/lib.sh" "$@"
A=(reproduce --quick --no-figures --no-candidates --realizations 40 --refine-realizations 40
   --peak-halfwidth 1 --threads 2)

snapshot() {  # names, mtimes and contents of every file under $1 (but the writer lock's)
  (cd "$1" && find . -type f ! -name '.stickslip*.lock' | sort | while read -r f; do
     printf '%s %s %s\n' "$f" "$(stat -c %Y.%y "$f")" "$(cksum <"$f")"; done)
}

run_ok "${A[@]}" --seed 5 -o r
[[ -s r/report.md && -s r/reproduce.toml && ! -e r/.runs ]] || fail "a finished reproduce: $(ls -A r)"
before=$(snapshot r)
sleep 1.1  # so that a rewrite would change the modification times

"$BIN" "${A[@]}" --seed 9 -o r --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of reproduce --resume with other settings" "$?" "2"
for phrase in "'r'" "finished reproduction of other settings" "seed = 5 vs seed = 9" \
              "--overwrite" "another -o DIR"; do
  checks=$((checks + 1))
  grep -qF -- "$phrase" "$WORK/stderr" || fail "stderr lacks '$phrase': $(cat "$WORK/stderr")"
done
expect_eq "r after the refused --resume" "$(snapshot r)" "$before"
[[ ! -e r/.runs ]] || fail "the refused --resume left journals"

run_ok "${A[@]}" --seed 5 -o r --resume
checks=$((checks + 1))
grep -qF "already holds the finished reproduction with these settings" "$WORK/stderr" ||
  fail "no 'already complete' report: $(cat "$WORK/stderr")"
expect_eq "r after --resume with the same settings" "$(snapshot r)" "$before"

# A finished reproduction without its settings (an older version): refused.
cp -r r old && rm old/reproduce.toml
"$BIN" "${A[@]}" --seed 5 -o old --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume onto a reproduction without settings" "$?" "2"
checks=$((checks + 1))
grep -qF "reproduce.toml' is missing" "$WORK/stderr" || fail "no settings: $(cat "$WORK/stderr")"

# --overwrite with --resume replaces it, as asked.
run_ok "${A[@]}" --seed 9 -o r --resume --overwrite
checks=$((checks + 1))
grep -qF "seed = 9" r/reproduce.toml || fail "--resume --overwrite did not replace the reproduction"
finish
