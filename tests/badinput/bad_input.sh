#!/usr/bin/env bash
# Bad-input suite (the table is docs/bad-input.md). Every case must
# end with the documented exit code and message, never a crash (exit >= 128),
# a hang (timeout) or a partial/wrong file; recoverable cases are resumed and
# must then equal the clean run bit for bit.
#   bad_input.sh STICKSLIP WORKDIR
set -uo pipefail
bin=$(realpath "$1"); work=$2
here=$(cd "$(dirname "$0")" && pwd)
compare="/usr/bin/python3 $here/../resume/compare_outputs.py"
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
cases=0; failures=0
bad() { echo "bad_input: FAILED: $*" >&2; failures=$((failures + 1)); }

# expect CODE PATTERN DIR -- ARGS...: exit code CODE, stderr matches PATTERN
# (grep -E), DIR absent afterwards (when DIR is not "-").
expect() {
  local code=$1 pattern=$2 dir=$3; shift 4
  cases=$((cases + 1))
  timeout 120 "$bin" "$@" >out.txt 2>err.txt; local rc=$?
  if ((rc != code)); then bad "$* -> exit $rc, expected $code: $(head -c 400 err.txt)"; return; fi
  grep -qE -- "$pattern" err.txt || bad "$* -> message does not match '$pattern': $(head -c 400 err.txt)"
  if [[ $dir != - && -e $dir ]]; then bad "$* -> left $dir behind"; rm -rf "$dir"; fi
}

A=(--lambda 0.1,1,5 --mu 0.5,2 --ta 20 --realizations 200 --block-size 20 --threads 1)
"$bin" sweep "${A[@]}" -o ref 2>/dev/null || { echo "bad_input: reference run failed"; exit 1; }

# 1. non-finite numbers (flags, TOML, grids, switch times)
expect 2 "--lambda.*'nan'.*finite" o -- sweep --lambda nan -o o
expect 2 "--mu.*'inf'.*finite" o -- sweep --mu inf -o o
expect 2 "out of the range of a double" o -- sweep --ta 1e400 -o o
expect 2 "not finite" o -- sweep --lambda 0.1,-nan -o o
printf '[model]\nmu = nan\n' >nan.toml
expect 2 "model.mu|nan" o -- sweep --config nan.toml -o o
printf '[grid]\nlambda = [0.5, inf]\n' >inf.toml
expect 2 "grid.lambda|inf" o -- sweep --config inf.toml -o o
printf '0.5\nnan\n' >switch_nan.txt
expect 2 "switch_nan.txt:2" - -- simulate --switch-times-file switch_nan.txt
expect 2 "checkpoint-interval.*finite" o -- sweep --checkpoint-interval nan -o o

# 2. zero and negative parameters and settings
expect 2 "k \(stiffness\).*0.*> 0" o -- sweep --k 0 -o o
expect 2 "m \(mass\).*-1.*> 0" o -- sweep --m=-1 -o o
expect 2 "V \(belt speed\)|--V" o -- sweep --V 0 -o o
expect 2 "--lambda.*entry #2" o -- sweep --lambda 1,-2 -o o
expect 2 "--realizations.*'0'" o -- sweep --realizations 0 -o o
expect 2 "--block-size.*'0'" o -- sweep --block-size 0 -o o
expect 2 "--bins.*'0'" o -- sweep --bins 0 -o o
expect 2 "--seed.*'-1'" o -- sweep --seed -1 -o o
expect 2 "checkpoint-interval.*-1" o -- sweep --checkpoint-interval=-1 -o o
expect 2 "--shard \(i\)" o -- sweep --shard 3/2 -o o
expect 2 "--peak-halfwidth.*0.*1e-4 \.\. 10" rp -- reproduce --quick --peak-halfwidth 0 -o rp
expect 2 "--peak-halfwidth.*nan" rp -- reproduce --quick --peak-halfwidth nan -o rp
expect 2 "--shard \(n\)" o -- sweep --shard 0/0 -o o
expect 2 "--shard.*i/n" o -- sweep --shard 1 -o o

# 3. absurd sizes that would exhaust memory or time
expect 2 "n <= 1000000" o -- sweep --lambda lin:0.1:1:100000000 -o o
# (9 million points: with the derivatives every point is kept to the end;
# the default statistics stream to the outputs and need one window.)
expect 2 "estimated memory" o -- sweep --lambda lin:0.1:10:3000 --mu lin:0.1:10:3000 --realizations 1 --statistics all -o o
expect 2 "raw records" o -- sweep --lambda lin:0.1:10:1000 --realizations 1000000 --records -o o
expect 2 "realizations.*2\^40" o -- sweep --realizations 1099511627777 -o o
expect 2 "lambda \* ta" o -- sweep --lambda 1e6 --ta 1e6 -o o
expect 2 "bins.*100000" o -- sweep --bins 1000000 -o o
# the joint (D, X) histogram holds bins^2 counts: allowed bins, one point (was exit 70, bad_alloc);
# only the family statistics hold it
expect 2 "estimated memory.*bins" o -- sweep --bins 100000 --realizations 1 --ta 1 --statistics family -o o
expect 2 "--block-size.*2\^24" o -- sweep --block-size 99999999 -o o
expect 2 "--threads" o -- sweep --threads 100000 -o o
expect 2 "records" o -- sweep --lambda lin:0.1:1:1000 --realizations 100000 --records -o o
expect 4 "bound on events" o -- sweep --lambda 0.05,0.1 --ta 30 --realizations 50 --max-events 10 -o o

# 4. unwritable output folders
touch a_file
expect 2 "-o \(output directory\)" - -- sweep "${A[@]}" -o a_file
[[ -s a_file ]] && bad "a_file was written to"
expect 3 "Not a directory|cannot" - -- sweep "${A[@]}" -o a_file/sub
expect 3 "cannot|No such file|Permission|Read-only" - -- sweep "${A[@]}" -o /proc/stickslip-out
expect 3 "cannot|No such file|Permission|Read-only" - -- sweep "${A[@]}" --shard 0/2 -o /sys/stickslip-out

# 5. disk full during a write (RLIMIT_FSIZE; stickslip ignores SIGXFSZ, so
#    writes fail with EFBIG), then recovery with --resume
limit_run() { local kb=$1; shift; (ulimit -f "$kb"; exec timeout 120 "$bin" "$@") >out.txt 2>err.txt; }
for kb in 2 60 100; do
  cases=$((cases + 1)); rm -rf full
  limit_run $kb sweep "${A[@]}" --checkpoint-interval 0 -o full; rc=$?
  ((rc == 3)) || bad "disk full at ${kb} KiB: exit $rc, expected 3: $(head -c 300 err.txt)"
  [[ -e full/results.nc || -e full/summary.json || -e full/summary.csv ]] && bad "disk full at ${kb} KiB left outputs"
  ls full/*.tmp full/.journal/.tmp-* >/dev/null 2>&1 && bad "disk full at ${kb} KiB left temporaries"
  "$bin" sweep "${A[@]}" --resume -o full 2>err.txt || bad "resume after disk full at ${kb} KiB failed"
  $compare ref full >/dev/null || bad "resume after disk full at ${kb} KiB differs"
done
cases=$((cases + 1)); rm -rf shards full-merge
"$bin" sweep "${A[@]}" --shard 0/1 -o shards 2>/dev/null
limit_run 60 merge -o full-merge shards; rc=$?
((rc == 3)) || bad "merge onto a full disk: exit $rc, expected 3"
[[ -e full-merge/results.nc ]] && bad "merge onto a full disk left results.nc"

# 6. truncated, corrupt and foreign journal files: reported, units recomputed
make_journal() {  # a complete journal in $1 (a shard covering every unit)
  rm -rf "$1"; "$bin" sweep "${A[@]}" --shard 0/1 --checkpoint-interval 0 -o "$1" 2>/dev/null
}
damage_case() {  # NAME COMMAND: damage the journal with COMMAND, resume, compare
  local name=$1; shift
  cases=$((cases + 1))
  make_journal j
  (cd j/.journal && eval "$*")
  timeout 120 "$bin" sweep "${A[@]}" --resume -o j >out.txt 2>err.txt; local rc=$?
  ((rc == 0)) || { bad "journal $name: exit $rc: $(head -c 300 err.txt)"; return; }
  grep -q "journal:" err.txt || bad "journal $name: damage not reported"
  $compare ref j >/dev/null || bad "journal $name: resumed outputs differ"
}
segs='ls seg-*.bin'
damage_case "truncated segment" 'truncate -s 30 $($segs | head -1)'
damage_case "truncated last record" 'f=$($segs | sed -n 2p); truncate -s $(( $(stat -c %s $f) - 9 )) $f'
damage_case "flipped byte (CRC)" 'f=$($segs | sed -n 3p); printf "\x5a" | dd of=$f bs=1 seek=$(( $(stat -c %s $f) - 20 )) conv=notrunc status=none'
damage_case "empty segment" ': > $($segs | sed -n 4p)'
damage_case "random garbage segment" 'head -c 3000 /dev/urandom > seg-zzzz-garbage.bin'
damage_case "directory named like a segment" 'mkdir seg-dir.bin'
damage_case "corrupt header" 'printf "garbage" > header.bin'
damage_case "missing header" 'rm header.bin'
damage_case "record length beyond the file" '/usr/bin/python3 -c "
import struct, sys
f = sys.argv[1]; d = bytearray(open(f, \"rb\").read())
body = struct.unpack_from(\"<Q\", d, 8)[0]
struct.pack_into(\"<I\", d, 20 + body, 0x7fffffff)
open(f, \"wb\").write(d)" $($segs | sed -n 5p)'
# a segment from another configuration, copied in
cases=$((cases + 1)); rm -rf other
"$bin" sweep "${A[@]/200/100}" --shard 0/1 --checkpoint-interval 0 -o other 2>/dev/null
make_journal j; cp other/.journal/seg-*-000000.bin j/.journal/seg-zzz-foreign.bin
"$bin" sweep "${A[@]}" --resume -o j 2>err.txt || bad "foreign segment: resume failed"
grep -q "another configuration" err.txt || bad "foreign segment not reported"
$compare ref j >/dev/null || bad "foreign segment: outputs differ"
# the journal path is a file, not a directory
cases=$((cases + 1)); rm -rf jf; mkdir jf; touch jf/.journal
timeout 60 "$bin" sweep "${A[@]}" -o jf 2>err.txt; rc=$?
((rc == 3)) || bad "journal path is a file: exit $rc"
# a changed configuration
cases=$((cases + 1)); make_journal j
timeout 60 "$bin" sweep "${A[@]/0.5,2/0.5,3}" --resume -o j 2>err.txt; rc=$?
((rc == 5)) || bad "changed configuration: exit $rc, expected 5"
grep -q "grid axis mu value #2: 2 vs 3" err.txt || bad "changed configuration message: $(cat err.txt)"

# 7. merge inputs: no journal, mismatched, incomplete, duplicates
make_journal m0
"$bin" sweep "${A[@]}" --shard 0/2 -o h0 2>/dev/null; "$bin" sweep "${A[@]}" --shard 1/2 -o h1 2>/dev/null
expect 2 "holding a journal" merged -- merge -o merged ref
expect 3 "cannot|No such file|Permission|Read-only" - -- merge -o /proc/stickslip-merged m0
expect 5 "different configuration" merged -- merge -o merged h0 other
expect 2 "work units are missing" merged -- merge -o merged h0
cases=$((cases + 1))
"$bin" merge -o merged h0 h1 m0 2>err.txt || bad "merge with duplicates failed"
grep -q "more than one journal" err.txt || bad "duplicates not reported"
$compare ref merged >/dev/null || bad "merge with duplicates differs"
expect 2 "merged/results.nc' already exists.*--overwrite" - -- merge -o merged h0 h1 m0
$compare ref merged >/dev/null || bad "a refused merge changed merged/"
cases=$((cases + 1))
"$bin" merge --overwrite -o merged h0 h1 m0 2>err.txt || bad "merge --overwrite failed: $(cat err.txt)"

# 8. What a new user hit: existing results, duplicate grid values, missing inputs,
#    command-line syntax, partial simulate outputs
cp -r ref ref_copy
expect 2 "ref_copy/results.nc' already exists.*--overwrite" - -- sweep "${A[@]}" -o ref_copy
cmp -s ref/summary.csv ref_copy/summary.csv || bad "a refused sweep changed ref_copy"
expect 2 "grid axis lambda.*#1 and #2" o -- sweep --lambda 1,1 -o o
expect 2 "input file 'nope.toml' does not exist" o -- sweep --config nope.toml -o o
expect 2 "input file 'nope.txt' does not exist" - -- simulate --switch-times-file nope.txt
expect 2 "unknown subcommand 'swep'; did you mean sweep" o -- swep -o o
expect 2 "unknown flag '--lamda'.*did you mean --lambda" o -- sweep --lamda 1,2 -o o
expect 2 "--mu is given 2 times" - -- simulate --mu 5 --mu 6
expect 2 "--events-file: '/tmp'.*not a directory" ef -- simulate --events --events-file /tmp -o ef/ep.csv
expect 3 "No such file or directory" tf -- simulate --trajectory 0.1 --trajectory-file /proc/nope/t.csv -o tf/ep.csv
printf '[sweep]\nrealizations = 100.5\n' >real.toml
expect 2 "sweep.realizations at real.toml:2:.*1 to 2\^40" o -- sweep --config real.toml -o o
printf '[initial]\nx0 = [1.0, -1.0]\n' >x0.toml
expect 2 "initial.x0 at x0.toml:2:.*lo = 1 > hi = -1" o -- sweep --config x0.toml -o o

echo "bad_input: $cases cases, $failures failures"
((failures == 0)) && rm -rf "$work"
((failures == 0))
