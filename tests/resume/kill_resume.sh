#!/usr/bin/env bash
# Kill-and-resume: a sweep is killed with SIGKILL at random points several
# times (and once with SIGTERM, and its journal is damaged in between), then
# resumed with --resume until it completes; its outputs must equal the
# uninterrupted run's bit for bit. Also: a changed configuration is refused
# with exit code 5, and shards merged with `stickslip merge` give the same
# outputs.
#   kill_resume.sh STICKSLIP WORKDIR [MIN_KILLS]
set -uo pipefail
bin=$(realpath "$1"); work=$2; min_kills=${3:-5}
here=$(cd "$(dirname "$0")" && pwd)
compare="/usr/bin/python3 $here/compare_outputs.py"
rm -rf "$work"; mkdir -p "$work"
args=(sweep --lambda 0.1,1,5,20 --mu 0.5,2 --ta 100 --realizations 600 --block-size 15
      --records --threads 2 --seed 7)
fail() { echo "kill_resume: FAILED: $*" >&2; exit 1; }

"$bin" "${args[@]}" -o "$work/ref" 2>/dev/null || fail "reference run"

# --- kill -9 at random points, resume each time, until a run completes
out=$work/killed; kills=0; cycles=0; damaged=0
start=$(date +%s.%N)
"$bin" "${args[@]}" -o "$out" --checkpoint-interval 0 2>>"$work/log" & pid=$!
sleep 0.3; kill -9 $pid 2>/dev/null && kills=$((kills + 1)); { wait $pid; } 2>/dev/null
ref_time=$(/usr/bin/python3 -c "import time,sys; print(max(0.5, time.time() - float(sys.argv[1])))" "$start")
while :; do
  cycles=$((cycles + 1)); ((cycles > 60)) && fail "no completion after 60 cycles"
  # Damage the journal twice along the way: truncate one segment, flip a byte in another.
  if ((cycles == 3 || cycles == 5)); then
    seg=$(ls "$out"/.journal/seg-*.bin 2>/dev/null | head -n $cycles | tail -n 1)
    if [[ -n $seg ]]; then
      if ((cycles == 3)); then truncate -s 40 "$seg"; else
        printf '\xff' | dd of="$seg" bs=1 seek=60 conv=notrunc status=none; fi
      damaged=$((damaged + 1))
    fi
  fi
  sig=-9; ((cycles == 4)) && sig=-TERM
  "$bin" "${args[@]}" -o "$out" --resume --checkpoint-interval 0 2>>"$work/log" & pid=$!
  delay=$(/usr/bin/python3 -c "import random; print(round(random.uniform(0.05, 0.6), 3))")
  sleep "$delay"
  if kill $sig $pid 2>/dev/null; then
    { wait $pid; } 2>/dev/null; rc=$?
    if [[ -d $out/.journal ]] || ((rc != 0)); then
      kills=$((kills + 1))
      if [[ $sig == -TERM ]]; then
        ((rc == 143 || rc == 0)) || fail "SIGTERM exit code $rc"
        if ((rc == 143)); then
          grep -q "^stickslip: stopped: interrupted by signal 15 (SIGTERM): .* finished units are journaled" \
            "$work/log" || fail "SIGTERM: no 'stickslip: stopped:' report: $(tail -n 2 "$work/log")"
          echo "kill_resume: SIGTERM -> exit 143, finished units journaled"
        fi
      fi
      ((kills < min_kills)) && continue
    fi
  else
    { wait $pid; } 2>/dev/null; rc=$?
  fi
  # After enough kills let a resume run to the end.
  if [[ -d $out/.journal ]] || [[ ! -f $out/results.nc ]]; then
    "$bin" "${args[@]}" -o "$out" --resume 2>>"$work/log" || fail "final resume"
  fi
  break
done
$compare "$work/ref" "$out" || fail "resumed outputs differ from the uninterrupted run"
[[ -d $out/.journal ]] && fail "journal not removed after success"
grep -q "journal:" "$work/log" || ((damaged == 0)) || fail "journal damage not reported"
echo "kill_resume: survived $kills kills in $cycles resume cycles ($damaged damaged segments); outputs identical"

# --- a changed configuration is refused (exit 5); a plain rerun onto an
# unfinished journal is refused (exit 2). A shard leaves a journal behind.
mm=$work/mismatch
"$bin" "${args[@]}" --shard 0/2 -o "$mm" 2>/dev/null || fail "shard for the mismatch test"
"$bin" "${args[@]/600/601}" -o "$mm" --resume 2>"$work/mismatch.err"; rc=$?
((rc == 5)) || fail "changed configuration: exit $rc, expected 5"
grep -q "realizations: 600 vs 601" "$work/mismatch.err" || fail "mismatch message: $(cat "$work/mismatch.err")"
"$bin" "${args[@]}" -o "$mm" 2>"$work/nonresume.err"; rc=$?
((rc == 2)) || fail "unfinished journal without --resume: exit $rc, expected 2"
"$bin" "${args[@]}" -o "$mm" --resume 2>/dev/null || fail "completing a shard's journal with --resume"
$compare "$work/ref" "$mm" || fail "shard completed by --resume differs"
echo "kill_resume: changed configuration refused (exit 5); rerun onto a journal without --resume refused (exit 2)"

# --- shards + merge == single run; incomplete coverage is refused
for i in 0 1 2; do
  "$bin" "${args[@]}" --shard $i/3 -o "$work/shard$i" 2>/dev/null || fail "shard $i/3"
  [[ -f $work/shard$i/results.nc ]] && fail "a shard wrote final outputs"
done
"$bin" merge -o "$work/partial" "$work/shard0" "$work/shard2" 2>"$work/merge.err"; rc=$?
((rc == 2)) || fail "merge of incomplete shards: exit $rc, expected 2"
grep -q "units are missing (unit indices 1, 4, 7, 10, 13, ...; they are shard 1/3's)" "$work/merge.err" ||
  fail "the incomplete merge does not name the missing shard: $(cat "$work/merge.err")"
[[ -e $work/partial ]] && fail "failed merge left $work/partial"
"$bin" merge -o "$work/merged" "$work/shard0" "$work/shard1" "$work/shard2" "$work/shard1" 2>/dev/null \
  || fail "merge"
$compare "$work/ref" "$work/merged" || fail "merged shards differ from the single run"
echo "kill_resume: 3 shards merged == single run; incomplete merge refused (exit 2)"
rm -rf "$work"
