#!/usr/bin/env bash
# `stickslip reproduce` killed with SIGKILL (several times, the first once its
# first journal segment exists, then at random points) and continued with
# --resume until it completes must write the same reproduction as an
# uninterrupted run; a rerun onto unfinished journals without --resume is
# refused (exit 2), and so is one onto a finished reproduction without
# --overwrite; `--shard i/n` runs of the main sweeps finished by
# --resume give the same reproduction too.
#   reproduce_resume.sh STICKSLIP WORKDIR
set -uo pipefail
bin=$(realpath "$1"); work=$2
here=$(cd "$(dirname "$0")" && pwd)
compare="/usr/bin/python3 $here/compare_reproductions.py"
rm -rf "$work"; mkdir -p "$work"
args=(reproduce --quick --no-figures --realizations 1200 --refine-realizations 1500 --threads 2
      --seed 11)
fail() { echo "reproduce_resume: FAILED: $*" >&2; exit 1; }

"$bin" "${args[@]}" -o "$work/ref" 2>/dev/null || fail "reference run"
[[ -e $work/ref/.runs ]] && fail "journals left after a finished reproduce"
# A finished reproduction is not replaced silently: exit 2 naming the file,
# the report untouched; --overwrite replaces it.
before=$(md5sum "$work/ref/report.md")
"$bin" "${args[@]}" -o "$work/ref" 2>"$work/again.err"; rc=$?
((rc == 2)) || fail "rerun onto a finished reproduction: exit $rc, expected 2"
grep -q "report.md.*--overwrite" "$work/again.err" || fail "refusal message: $(cat "$work/again.err")"
[[ $(md5sum "$work/ref/report.md") == "$before" ]] || fail "the refused rerun changed report.md"
"$bin" "${args[@]}" -o "$work/ref" --overwrite 2>/dev/null || fail "--overwrite"
echo "reproduce_resume: a finished reproduction is refused without --overwrite (exit 2) and replaced with it"

out=$work/killed
"$bin" "${args[@]}" -o "$out" --checkpoint-interval 0 2>>"$work/log" & pid=$!
for _ in $(seq 400); do  # kill once the first journal segment is on disk
  compgen -G "$out/.runs/*/.journal/seg-*" >/dev/null && break
  sleep 0.01
done
kill -9 $pid 2>/dev/null || fail "the run finished before the first kill (make it longer)"
{ wait $pid; } 2>/dev/null
[[ -f $out/report.md ]] && fail "a killed run wrote a report"
"$bin" "${args[@]}" -o "$out" 2>"$work/nonresume.err"; rc=$?
((rc == 2)) || fail "rerun onto unfinished journals without --resume: exit $rc, expected 2"
grep -q -- "--resume" "$work/nonresume.err" || fail "the refusal does not mention --resume"
kills=1
for delay in 0.2 0.5 0.35; do
  "$bin" "${args[@]}" -o "$out" --resume --checkpoint-interval 0 2>>"$work/log" & pid=$!
  sleep "$delay"
  kill -9 $pid 2>/dev/null && kills=$((kills + 1))
  { wait $pid; } 2>/dev/null
done
"$bin" "${args[@]}" -o "$out" --resume 2>>"$work/log" || fail "final --resume"
[[ -e $out/.runs ]] && fail "journals left after the resumed reproduce finished"
$compare "$work/ref" "$out" >/dev/null || { $compare "$work/ref" "$out"; fail "resumed reproduction differs"; }
echo "reproduce_resume: $kills kill -9, then --resume: identical reproduction"

sh=$work/sharded
for i in 0 1 2; do
  "$bin" "${args[@]}" --shard $i/3 -o "$sh" 2>>"$work/log" || fail "shard $i/3"
done
[[ -f $sh/report.md ]] && fail "a shard wrote a report"
"$bin" "${args[@]}" -o "$sh" --resume 2>"$work/sharded.log" || fail "--resume after the shards"
grep -q "concluded-sweep: [0-9]* units from the journal, 0 computed" "$work/sharded.log" \
  || { cat "$work/sharded.log"; fail "--resume recomputed the sharded main sweep"; }
$compare "$work/ref" "$sh" >/dev/null || { $compare "$work/ref" "$sh"; fail "sharded reproduction differs"; }
echo "reproduce_resume: 3 shards of the main sweeps + --resume: identical reproduction"

# Finished peak searches are kept in .runs: a resume uses them instead of
# searching again, and a kept file that is damaged or from another request is
# searched again; the reproduction is the same either way.
kept=$work/kept
"$bin" "${args[@]}" -o "$kept" --keep-journal 2>/dev/null || fail "--keep-journal run"
ls "$kept"/.runs/concluded-peak-mu-5.peak >/dev/null || fail "no kept peak search in .runs"
head -c 100 "$kept/.runs/concluded-peak-mu-0.5.peak" > "$work/cut" && mv "$work/cut" "$kept/.runs/concluded-peak-mu-0.5.peak"
"$bin" "${args[@]}" -o "$kept" --resume --overwrite 2>"$work/kept.log" || fail "--resume onto kept searches"
grep -q "concluded-peak-mu-5: the search kept in .* (not run again)" "$work/kept.log" \
  || { cat "$work/kept.log"; fail "the kept peak search was run again"; }
grep -q "concluded-peak-mu-0.5: .* is not this search's result; searching again" "$work/kept.log" \
  || { cat "$work/kept.log"; fail "a damaged kept peak search was used"; }
$compare "$work/ref" "$kept" >/dev/null || { $compare "$work/ref" "$kept"; fail "reproduction from kept peak searches differs"; }
echo "reproduce_resume: kept peak searches are reused on --resume, a damaged one searched again: identical reproduction"
rm -rf "$work"
