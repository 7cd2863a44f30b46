#!/usr/bin/env bash
# Fault injection: one table. Every row injects one kind of fault into real
# runs of the `stickslip` binary, trial after trial, and counts the trials
# with data lost: a trial counts as lost when any of its checks fails (the
# outputs after recovery differ from an uninterrupted run's, data, not
# metadata: tests/resume/compare_outputs.py and compare_reproductions.py; an
# exit code or message other than the documented one; earlier results
# changed; a hang). Each row must end with 0 lost.
#
#   fault_table.sh STICKSLIP [SCALE] [ROW...]
#
# SCALE multiplies the trial counts (1 = the full counts of docs/reliability.md,
# 0.06 = the short ctest version); every row runs at least one trial. ROW
# names run only those rows (see `rows` below). Prints a markdown table and
# then "N passed, N failed" (rows) as its last line; exits 1 if a row failed.
# Environment:
#   MPIRUN           mpirun to use (default: mpirun on PATH; MPI rows are
#                    skipped without it)
#   FAULT_SEED       seed of the random moments, offsets and sizes (default 1)
#   FAULT_WORK       working directory (default: a new one under $TMPDIR,
#                    removed at the end)
#   FAULT_SABOTAGE=1 alter one value of every results.nc before it is
#                    compared: then every row must fail (checks the checks)
#   STICKSLIP_PYTHON python3 with netCDF4 and numpy (default /usr/bin/python3)
set -uo pipefail
[[ $# -ge 1 ]] || { echo "usage: $0 STICKSLIP [SCALE] [ROW...]" >&2; exit 2; }
BIN=$(realpath "$1")
SCALE=${2:-1}
shift $(( $# >= 2 ? 2 : 1 ))
SELECTED=("$@")
HERE=$(cd "$(dirname "$0")" && pwd)
PY=${STICKSLIP_PYTHON:-/usr/bin/python3}
CMP_SWEEP="$HERE/../resume/compare_outputs.py"
CMP_REPRO="$HERE/../resume/compare_reproductions.py"
MPIRUN=${MPIRUN:-$(command -v mpirun || true)}
RANDOM=${FAULT_SEED:-1}
NICE=(nice -n 10)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
LAUNCH=("$MPIRUN" --allow-run-as-root --oversubscribe --mca btl self,vader
        --mca btl_vader_single_copy_mechanism none -np 2)

if [[ -n ${FAULT_WORK:-} ]]; then
  W=$FAULT_WORK; rm -rf "$W"; mkdir -p "$W"; keep_work=1
else
  W=$(mktemp -d "${TMPDIR:-/tmp}/stickslip-faults.XXXXXX"); keep_work=0
fi
W=$(realpath "$W")
# A private copy of the binary: a rebuild during the run does not mix two binaries.
cp "$BIN" "$W/stickslip" || exit 2
BIN=$W/stickslip
MNT=""
BG=()  # background processes started here, ended at exit if still running
cleanup() {
  local p
  for p in "${BG[@]}"; do kill -9 "$p" 2>/dev/null; done
  [[ -n $MNT ]] && umount "$MNT" 2>/dev/null
  ((keep_work)) || rm -rf "$W"
}
trap cleanup EXIT
cd "$W" || exit 2
FAILLOG=$W/failures.log; : >"$FAILLOG"

# ------------------------------------------------------------------ helpers
now_ms() { date +%s%3N; }
# rand_ms MAX: a uniform random integer in [0, MAX]
rand_ms() { echo $(( (RANDOM * 32768 + RANDOM) % ($1 + 1) )); }
# secs MS: MS milliseconds as seconds for sleep
secs() { printf '%d.%03d' $(($1 / 1000)) $(($1 % 1000)); }
# trials FULL: the number of trials of a row at this SCALE (at least 1)
trials() { "$PY" -c "import math,sys; print(max(1, math.ceil(float(sys.argv[1]) * int(sys.argv[2]))))" "$SCALE" "$1"; }
# bad TRIAL WHAT: record a failed check of the current trial
bad() { echo "$row_name trial $1: $2" >>"$FAILLOG"; trial_ok=0; }
sabotage() {  # DIR: FAULT_SABOTAGE=1 changes one value in the first results.nc under DIR
  [[ ${FAULT_SABOTAGE:-0} == 1 ]] || return 0
  "$PY" - "$1" <<'PY'
import os, sys, netCDF4, numpy as np
for d, _, names in sorted(os.walk(sys.argv[1])):
    if "results.nc" in names:
        with netCDF4.Dataset(os.path.join(d, "results.nc"), "a") as ds:
            for v in ds.variables.values():
                if v.size and np.issubdtype(v.dtype, np.number):
                    flat = np.asarray(v[...]).copy().reshape(-1)
                    flat[0] = flat[0] + 1
                    v[...] = flat.reshape(v.shape)
                    sys.exit(0)
PY
}
same_sweep() { sabotage "$2"; "$PY" "$CMP_SWEEP" "$1" "$2" >/dev/null 2>>"$W/compare.err"; }
same_repro() { sabotage "$2"; "$PY" "$CMP_REPRO" "$1" "$2" >/dev/null 2>>"$W/compare.err"; }
# same_study A B: two sensitivity outputs hold the same estimates (summary.json
# without its run metadata and timing) and the same sensitivity.nc variables.
same_study() {
  [[ ${FAULT_SABOTAGE:-0} == 1 ]] && echo '{}' >"$2/summary.json"
  "$PY" - "$1" "$2" >/dev/null 2>>"$W/compare.err" <<'PY'
import json, os, sys, netCDF4, numpy as np
a, b = sys.argv[1:]
def est(d):
    j = json.load(open(os.path.join(d, "summary.json")))
    j.pop("run", None); j.pop("elapsed_seconds", None)
    return j
def nc(d):
    with netCDF4.Dataset(os.path.join(d, "sensitivity.nc")) as ds:
        out = {}
        for k, v in ds.variables.items():
            x = np.asarray(v[...])
            out[k] = x.tolist() if x.dtype == object else x.tobytes()  # strings: by value
        return out
sys.exit(0 if est(a) == est(b) and nc(a) == nc(b) else 1)
PY
}
# run_bg ARGS...: start ARGS in the background (stderr in $W/bg.err); sets $pid
run_bg() { "$@" 2>"$W/bg.err" & pid=$!; BG+=("$pid"); }
# wait_rc PID: waits for PID (started by this shell); its exit status in $rc
wait_rc() { { wait "$1"; } 2>/dev/null; rc=$?; }
# wait_file GLOB [TRIES]: wait (0.05 s steps) until GLOB matches; 1 if never
wait_file() {
  local i
  for ((i = 0; i < ${2:-400}; i++)); do compgen -G "$1" >/dev/null && return 0; sleep 0.05; done
  return 1
}
# rank_pid MPIRUN_PID RANK: the pid of MPI rank RANK started by that mpirun
rank_pid() {
  local p
  for p in $(pgrep -P "$1"); do
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$2" && { echo "$p"; return 0; }
  done
  return 1
}

# Row bookkeeping: a row sets $n (trials run), $lost and $notes.
RESULTS=()
passed=0; failed=0; skipped=0
run_row() {  # NAME DESCRIPTION FUNCTION
  row_name=$1
  local desc=$2 fn=$3
  if ((${#SELECTED[@]})) && [[ " ${SELECTED[*]} " != *" $row_name "* ]]; then return; fi
  n=0; lost=0; notes=""; skip=""
  local t0; t0=$(now_ms)
  "$fn"
  local el=$(( ($(now_ms) - t0 + 500) / 1000 ))
  local verdict
  if [[ -n $skip ]]; then verdict="skipped: $skip"; skipped=$((skipped + 1))
  elif ((lost == 0 && n > 0)); then verdict=pass; passed=$((passed + 1))
  else verdict=FAIL; failed=$((failed + 1)); fi
  RESULTS+=("| $desc | $n | $lost | ${el} s | $verdict | $notes | \`tests/faults/fault_table.sh BIN $SCALE $row_name\` |")
  echo "fault_table: $row_name: $n trials, $lost lost, ${el} s, $verdict${notes:+ ($notes)}" >&2
}

# ------------------------------------------------------------------ configurations
A=(sweep --lambda 0.1,1,5,20 --mu 0.5,2 --ta 100 --realizations 600 --block-size 15 --records
   --threads 2 --seed 7)                                   # 320 units, ~0.5 s
R=(reproduce --quick --no-figures --no-candidates --realizations 100 --refine-realizations 100
   --threads 2 --seed 11)                                  # two parameter sets, ~4 s
D=(sweep --lambda 0.1,1,5,20 --mu 0.5,2 --ta 100 --realizations 600 --block-size 100 --records
   --threads 2 --checkpoint-interval 0)                    # 48 units, ~1.2 MB on disk
# (--records: a journal of every unit, which only grows, so that the room
# left on the disk decides the phase that fills it; the merged-prefix
# journal replaces its segments and its size goes up and down)
J=(sweep --lambda 0.1,1,5,20 --mu 0.5,2 --ta 100 --realizations 600 --block-size 60
   --threads 2 --seed 7)                                   # 80 units (merged-prefix journal)
M=(sweep --lambda log:0.1:30:20 --mu 0.5,5 --realizations 2400 --seed 5 --checkpoint-interval 0
   --threads 1)                                            # 960 units, ~4 s under mpirun -np 2 (600 ended before the fault on an idle machine)
S=(sensitivity --k 40 --ta 20 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --samples 8000
   --block-size 50 --threads 2 --seed 13 --no-figure)    # 160 units, 40000 realizations, ~0.6 s
T=(sweep --lambda 0.1,1,5,20 --mu 0.5,2 --ta 100 --realizations 8000 --block-size 100 --records
   --threads 1 --seed 9)                                   # ~2 s

# ------------------------------------------------------------------ 1. kill -9
row_kill_sweep() {
  local N; N=$(trials 50)
  # Odd trials keep raw records (a journal of every unit), even ones do not
  # (a journal of merged prefixes, the default): both journal layouts.
  local with_records=("${A[@]}") merged=() a
  for a in "${A[@]}"; do [[ $a == --records ]] || merged+=("$a"); done
  "$BIN" "${with_records[@]}" -o ref_a 2>/dev/null || { notes="reference run failed"; lost=1; return; }
  "$BIN" "${merged[@]}" -o ref_am 2>/dev/null || { notes="reference run failed"; lost=1; return; }
  local t0 t_ref; t0=$(now_ms); "${NICE[@]}" "$BIN" "${A[@]}" -o ref_a_t 2>/dev/null; t_ref=$(( $(now_ms) - t0 ))
  local hits=0 i k rc ci ref
  for ((i = 1; i <= N; i++)); do
    if ((i % 2)); then A=("${with_records[@]}"); ref=ref_a; else A=("${merged[@]}"); ref=ref_am; fi
    trial_ok=1; rm -rf ks
    # killed twice (the run, then its first --resume) at random moments, then resumed to the end
    for k in 1 2; do
      ci=$(( RANDOM % 2 ? 0 : 5 ))  # a segment after every unit, or every 0.05 s
      local extra=(); ((k == 2)) && extra=(--resume)
      run_bg "${NICE[@]}" "$BIN" "${A[@]}" "${extra[@]}" --checkpoint-interval "0.0$ci" -o ks
      sleep "$(secs "$(rand_ms $((t_ref * 6 / 5)))")"
      kill -9 "$pid" 2>/dev/null
      wait_rc "$pid"
      if ((rc == 137)); then hits=$((hits + 1)); elif ((rc != 0)); then bad $i "run $k: exit $rc: $(head -c 200 "$W/bg.err")"; fi
    done
    "$BIN" "${A[@]}" --resume -o ks 2>"$W/final.err" || bad $i "final --resume: exit $?: $(head -c 300 "$W/final.err")"
    [[ -e ks/.journal ]] && bad $i "journal left after the final --resume"
    same_sweep $ref ks || bad $i "outputs differ from the uninterrupted run"
    n=$i; ((trial_ok)) || lost=$((lost + 1))
  done
  A=("${with_records[@]}")
  notes="$hits of $((2 * N)) kills hit a running process (uninterrupted run ${t_ref} ms; odd trials with --records, even ones with the merged-prefix journal)"
}

row_kill_sensitivity() {
  local N; N=$(trials 50)
  "$BIN" "${S[@]}" -o ref_s >/dev/null 2>&1 || { notes="reference run failed"; lost=1; return; }
  local t0 t_ref; t0=$(now_ms); "${NICE[@]}" "$BIN" "${S[@]}" -o ref_s_t >/dev/null 2>&1; t_ref=$(( $(now_ms) - t0 ))
  local hits=0 i k rc ci
  for ((i = 1; i <= N; i++)); do
    trial_ok=1; rm -rf kss
    for k in 1 2; do
      ci=$(( RANDOM % 2 ? 0 : 5 ))
      local extra=(); ((k == 2)) && extra=(--resume)
      run_bg "${NICE[@]}" "$BIN" "${S[@]}" "${extra[@]}" --checkpoint-interval "0.0$ci" -o kss
      sleep "$(secs "$(rand_ms $((t_ref * 6 / 5)))")"
      kill -9 "$pid" 2>/dev/null
      wait_rc "$pid"
      if ((rc == 137)); then hits=$((hits + 1)); elif ((rc != 0)); then bad $i "run $k: exit $rc: $(head -c 200 "$W/bg.err")"; fi
    done
    "$BIN" "${S[@]}" --resume -o kss >/dev/null 2>"$W/final.err" || bad $i "final --resume: exit $?: $(head -c 300 "$W/final.err")"
    [[ -e kss/.journal ]] && bad $i "journal left after the final --resume"
    same_study ref_s kss || bad $i "estimates differ from the uninterrupted study"
    n=$i; ((trial_ok)) || lost=$((lost + 1))
  done
  notes="$hits of $((2 * N)) kills hit a running process (uninterrupted run ${t_ref} ms)"
}

row_kill_reproduce() {
  local N; N=$(trials 50)
  "$BIN" "${R[@]}" -o ref_r 2>/dev/null || { notes="reference run failed"; lost=1; return; }
  local t0 t_ref; t0=$(now_ms); "${NICE[@]}" "$BIN" "${R[@]}" -o ref_r_t 2>/dev/null; t_ref=$(( $(now_ms) - t0 ))
  local hits=0 i rc
  for ((i = 1; i <= N; i++)); do
    trial_ok=1; rm -rf kr
    run_bg "${NICE[@]}" "$BIN" "${R[@]}" --checkpoint-interval "$((RANDOM % 2)).2" -o kr
    sleep "$(secs "$(rand_ms "$t_ref")")"
    kill -9 "$pid" 2>/dev/null
    wait_rc "$pid"
    if ((rc == 137)); then hits=$((hits + 1)); elif ((rc != 0)); then bad $i "run: exit $rc"; fi
    "$BIN" "${R[@]}" --resume -o kr 2>"$W/final.err" || bad $i "--resume: exit $?: $(tail -c 300 "$W/final.err")"
    [[ -e kr/.runs ]] && bad $i "journals (.runs) left after --resume"
    same_repro ref_r kr || bad $i "reproduction differs from the uninterrupted one"
    n=$i; ((trial_ok)) || lost=$((lost + 1))
  done
  notes="$hits of $N kills hit a running process (uninterrupted run ${t_ref} ms)"
}

# ------------------------------------------------------------------ 2. full disk
# A small tmpfs (or, where mounting is not permitted, `ulimit -f`) filled to
# leave a random amount of room; DIR holds an earlier finished run that the
# new one replaces (--overwrite). Expected: exit 3 naming the file, the
# earlier results byte for byte unchanged, and `--resume` of a copy of DIR in
# a place with room writes the uninterrupted run's outputs.
disk_ready=""
disk_setup() {
  [[ -n $disk_ready ]] && return 0
  "$BIN" "${D[@]}" --seed 7 -o ref_d 2>/dev/null || return 1
  "$BIN" "${D[@]}" --seed 8 -o earlier_d 2>/dev/null || return 1
  mkdir -p mnt
  if [[ ${FAULT_DISK:-tmpfs} == tmpfs ]] && mount -t tmpfs -o size=4M tmpfs mnt 2>/dev/null; then
    MNT=$W/mnt; disk_mode=tmpfs
    rm -rf mnt/*; cp -a earlier_d mnt/d
    "$BIN" "${D[@]}" --seed 7 --overwrite --keep-journal -o mnt/d 2>/dev/null || return 1
    disk_j=$(du -sk mnt/d/.journal | cut -f1)                 # KiB of the whole journal
    disk_o=$(du -sk --exclude=.journal mnt/d | cut -f1)       # KiB of the outputs
  else  # RLIMIT_FSIZE: the limit applies to each file
    disk_mode="ulimit -f"
    "$BIN" "${D[@]}" --seed 7 --keep-journal -o kept_d 2>/dev/null || return 1
    disk_j=$(( $(stat -c %s kept_d/.journal/seg-*.bin | sort -n | tail -1) / 1024 ))  # KiB of the largest segment
    disk_o=$(( $(stat -c %s kept_d/results.nc) / 1024 ))                           # KiB of results.nc
  fi
  disk_ready=1
}
disk_trial() {  # TRIAL KiB-OF-ROOM: one run onto the full disk; sets $phase
  local i=$1 room=$2 rc
  phase=none
  rm -rf mnt/* room_d 2>/dev/null
  cp -a earlier_d mnt/d
  (cd mnt/d && md5sum results.nc summary.json summary.csv) >"$W/earlier.md5"
  if [[ $disk_mode == tmpfs ]]; then
    local avail; avail=$(df -B1024 --output=avail mnt | tail -1)
    ((avail > room)) && fallocate -l $(( (avail - room) * 1024 )) mnt/filler
    "${NICE[@]}" "$BIN" "${D[@]}" --seed 7 --overwrite -o mnt/d >/dev/null 2>"$W/disk.err"; rc=$?
  else
    # stderr through a pipe: a file would be under the same limit (see docs/reliability.md)
    (ulimit -f "$room"; exec "${NICE[@]}" "$BIN" "${D[@]}" --seed 7 --overwrite -o mnt/d 2>&1 >/dev/null) \
      | cat >"$W/disk.err"; rc=${PIPESTATUS[0]}
  fi
  ((rc == 0)) && return 0  # there was room: no fault injected, the caller tries again
  grep -q "cannot write or read 'mnt/d/\.journal/" "$W/disk.err" && phase=journal
  grep -q "cannot write or read 'mnt/d/[a-z]" "$W/disk.err" && phase=output
  ((rc == 3)) || bad $i "exit $rc, expected 3: $(tail -c 200 "$W/disk.err")"
  [[ $phase == none ]] && bad $i "no clear message naming the file: $(tail -c 300 "$W/disk.err")"
  (cd mnt/d && md5sum --quiet -c "$W/earlier.md5" >/dev/null 2>&1) || bad $i "the earlier results in DIR changed"
  compgen -G "mnt/d/*.tmp" >/dev/null && bad $i "temporaries left in DIR"
  cp -a mnt/d room_d; rm -rf mnt/*
  "$BIN" "${D[@]}" --seed 7 --resume -o room_d 2>"$W/final.err" || bad $i "--resume with room: exit $?: $(tail -c 300 "$W/final.err")"
  same_sweep ref_d room_d || bad $i "resumed outputs differ from the uninterrupted run"
  return 0
}
row_disk() {  # PHASE: journal or output
  local want=$1 N; N=$(trials 20)
  disk_setup || { notes="setup failed"; lost=1; return; }
  local attempts=0 other=0 room lo=999999 hi=0
  while ((n < N && attempts < 4 * N)); do
    attempts=$((attempts + 1)); trial_ok=1
    if [[ $want == journal ]]; then room=$((1 + $(rand_ms $((disk_j * 9 / 10)))))
    elif [[ $disk_mode == tmpfs ]]; then room=$((disk_j + 8 + $(rand_ms $((disk_o * 8 / 10)))))
    else room=$((disk_j + 1 + $(rand_ms $((disk_o - disk_j - 2))))); fi
    disk_trial $((n + 1)) "$room"
    if [[ $phase == "$want" ]]; then ((room < lo)) && lo=$room; ((room > hi)) && hi=$room; fi
    if [[ $phase == "$want" ]] || ((trial_ok == 0)); then
      n=$((n + 1)); ((trial_ok)) || lost=$((lost + 1))
    else
      other=$((other + 1))
    fi
  done
  ((lo > hi)) && { lo="?"; hi="?"; }  # no trial failed in this phase
  if [[ $disk_mode == tmpfs ]]; then
    notes="4 MiB tmpfs filled to leave ${lo}-${hi} KiB (journal ${disk_j} KiB, outputs ${disk_o} KiB)"
  else
    notes="ulimit -f ${lo}-${hi} KiB (largest segment ${disk_j} KiB, results.nc ${disk_o} KiB)"
  fi
  notes="$notes; $other runs that filled the disk in the other phase, or had room, not counted"
}
row_disk_journal() { row_disk journal; }
row_disk_output() { row_disk output; }

# ------------------------------------------------------------------ 3. damaged journal
# A complete journal (--shard 0/1) is damaged (random bytes flipped, or cut
# at a random length), then --resume: the outputs must equal the
# uninterrupted run's (the damaged part recomputed), or the run is refused
# with a clear message and writes no outputs. Never misread.
journal_ready=""
journal_setup() {
  [[ -n $journal_ready ]] && return 0
  "$BIN" "${J[@]}" -o ref_j 2>/dev/null || return 1
  # two layouts: a shard's journal of every unit, and a whole run's journal
  # of merged prefixes (its outputs removed, so that --resume reads it)
  "$BIN" "${J[@]}" --shard 0/1 --checkpoint-interval 0 -o pristine_j 2>/dev/null || return 1
  "$BIN" "${J[@]}" --checkpoint-interval 0 --keep-journal -o pristine_jm 2>/dev/null || return 1
  rm -f pristine_jm/results.nc pristine_jm/summary.json pristine_jm/summary.csv
  journal_ready=1
}
row_damage() {  # WHICH: segment or header
  local which=$1 N; N=$(trials 50)
  journal_setup || { notes="setup failed"; lost=1; return; }
  local recomputed=0 refused=0 reported=0 i rc f how
  for ((i = 1; i <= N; i++)); do
    trial_ok=1; rm -rf dj
    if ((i % 2)); then cp -a pristine_j dj; else cp -a pristine_jm dj; fi
    if [[ $which == header ]]; then f=dj/.journal/header.bin
    else local segs=(dj/.journal/seg-*.bin); f=${segs[RANDOM % ${#segs[@]}]}; fi
    how=$("$PY" - "$f" "$RANDOM" <<'PY'
import os, random, sys
path, seed = sys.argv[1], int(sys.argv[2])
rng = random.Random(seed)
data = bytearray(open(path, "rb").read())
if rng.random() < 0.5:
    cut = rng.randrange(0, len(data))
    open(path, "wb").write(data[:cut])
    print(f"cut to {cut} of {len(data)} bytes")
else:
    offs = sorted(rng.randrange(0, len(data)) for _ in range(rng.randint(1, 4)))
    for o in offs:
        data[o] ^= rng.randint(1, 255)
    open(path, "wb").write(data)
    print(f"flipped bytes at {offs} of {len(data)}")
PY
)
    timeout 120 "$BIN" "${J[@]}" --resume -o dj >/dev/null 2>"$W/dmg.err"; rc=$?
    grep -q "journal" "$W/dmg.err" && reported=$((reported + 1))
    if ((rc == 0)); then
      recomputed=$((recomputed + 1))
      same_sweep ref_j dj || bad $i "$(basename "$f") $how: outputs differ from the uninterrupted run"
    elif ((rc == 2 || rc == 3 || rc == 5)) && grep -q "stickslip: error:.*journal" "$W/dmg.err"; then
      refused=$((refused + 1))
      [[ -e dj/results.nc || -e dj/summary.json ]] && bad $i "$(basename "$f") $how: refused but wrote outputs"
    else
      bad $i "$(basename "$f") $how: exit $rc: $(tail -c 300 "$W/dmg.err")"
    fi
    n=$i; ((trial_ok)) || lost=$((lost + 1))
  done
  notes="$recomputed resumed (exit 0, outputs compared), $refused refused with a message; the damage reported in $reported (odd trials: a journal of every unit, even: of merged prefixes)"
}
row_damage_segment() { row_damage segment; }
row_damage_header() { row_damage header; }

# ------------------------------------------------------------------ 4./5. MPI
mpi_ready=""
mpi_setup() {
  [[ -n $mpi_ready ]] && return 0
  [[ -n $MPIRUN ]] || { skip="no mpirun"; return 1; }
  "$BIN" "${M[@]}" -o ref_m 2>/dev/null || { notes="reference run failed"; lost=1; return 1; }
  mpi_ready=1
}
# mpi_trial TRIAL HOW: mpirun -np 2 sweep, hit (HOW) at a random moment after
# its first journal segment; rank 0 / mpirun must exit within 10 s with a
# message, then mpirun --resume must give the single-process outputs.
# Sets $mpi_rc (exit status) and $mpi_secs.
mpi_trial() {
  local i=$1 how=$2 target t0
  rm -rf mk mk.err
  "${NICE[@]}" "${LAUNCH[@]}" "$BIN" "${M[@]}" -o mk 2>mk.err & local mp=$!; BG+=("$mp")
  if ! wait_file "mk/.journal/seg-*"; then bad $i "no journal segment within 20 s"; kill -9 $mp; wait $mp 2>/dev/null; return; fi
  sleep "$(secs "$(rand_ms 800)")"
  case $how in
    kill-worker) target=$(rank_pid $mp 1) && kill -9 "$target" ;;
    usr1) kill -USR1 $mp ;;
    term-mpirun) kill -TERM $mp ;;
    term-ranks) target="$(rank_pid $mp 0) $(rank_pid $mp 1)"; kill -TERM $target ;;
  esac
  t0=$(now_ms)
  ( sleep 30; kill -9 $mp ) >/dev/null 2>&1 & local dog=$!
  { wait $mp; } 2>/dev/null; mpi_rc=$?
  mpi_secs=$(( ($(now_ms) - t0) ))
  kill $dog 2>/dev/null; wait $dog 2>/dev/null
  if ((mpi_rc == 0)); then other=$((other + 1)); trial_ok=2; return; fi  # finished first: not counted
  # The run finished and wrote its outputs just before the fault reached it
  # (mpirun still reports the signal): not counted either, once those
  # outputs are the single-process run's.
  if [[ ! -d mk/.journal && -e mk/results.nc ]]; then
    same_sweep ref_m mk || bad $i "$how: outputs of a run that finished first differ"
    ((trial_ok == 1)) && { other=$((other + 1)); trial_ok=2; }
    return
  fi
  ((mpi_secs <= 10000)) || bad $i "$how: exit after $mpi_secs ms (> 10 s)"
  [[ -d mk/.journal ]] || bad $i "$how: no journal left to resume"
  case $how in
    kill-worker) grep -q "rank 1 .*signal 9\|exited on signal 9" mk.err || bad $i "kill-worker: no message: $(tail -c 300 mk.err)" ;;
    usr1) ((mpi_rc == 138)) || bad $i "usr1: exit $mpi_rc, expected 138"
          grep -q "interrupted by signal 10" mk.err || bad $i "usr1: no message: $(tail -c 300 mk.err)" ;;
    term-ranks) ((mpi_rc == 143)) || bad $i "term-ranks: exit $mpi_rc, expected 143"
          grep -q "interrupted by signal 15" mk.err || bad $i "term-ranks: no message: $(tail -c 300 mk.err)" ;;
  esac
  timeout 120 "${LAUNCH[@]}" "$BIN" "${M[@]}" --resume -o mk >/dev/null 2>"$W/final.err" \
    || bad $i "$how: mpirun --resume: exit $?: $(tail -c 300 "$W/final.err")"
  same_sweep ref_m mk || bad $i "$how: resumed outputs differ from the single-process run"
}
row_mpi() {  # HOW FULL-TRIALS
  local how=$1 N; N=$(trials "$2")
  mpi_setup || return
  local attempts=0 max=0 codes=""
  other=0
  while ((n < N && attempts < 3 * N)); do
    attempts=$((attempts + 1)); trial_ok=1
    mpi_trial $((n + 1)) "$how"
    ((trial_ok == 2)) && continue
    n=$((n + 1)); ((trial_ok)) || lost=$((lost + 1))
    ((mpi_secs > max)) && max=$mpi_secs
    [[ " $codes " == *" $mpi_rc "* ]] || codes="$codes $mpi_rc"
  done
  notes="exit codes:$codes; slowest exit $(secs $max) s after the fault; $other runs finished first (not counted)"
}
row_mpi_kill_worker() { row_mpi kill-worker 10; }
row_mpi_usr1() { row_mpi usr1 10; }
row_mpi_term_ranks() { row_mpi term-ranks 10; }
row_mpi_term_mpirun() { row_mpi term-mpirun 10; }
# A worker throwing outside its compute threads, injected by the test-only
# STICKSLIP_FAULT_INJECT=mpi_worker_throw_after_units:K (backends/mpi; K
# random in [1, 40] of the 960 units): rank 1's main thread throws after
# sending K results, reports it and calls MPI_Abort. mpirun must exit
# non-zero within 10 s of that message, with a journal left, and mpirun
# --resume (without the fault) must give the single-process outputs. The
# notes give how many units the journal kept (the resume's "N units from the
# journal"): everything rank 0 finished was journaled (--checkpoint-interval 0).
row_mpi_throw() {
  local N; N=$(trials 10)
  mpi_setup || return
  local attempts=0 max=0 codes="" kept_min="" kept_max=0 k_min="" k_max=0 k mp t_msg rc kept
  other=0
  while ((n < N && attempts < 3 * N)); do
    attempts=$((attempts + 1)); trial_ok=1
    local i=$((n + 1)); k=$((1 + RANDOM % 40))
    rm -rf mt mt.err
    STICKSLIP_FAULT_INJECT=mpi_worker_throw_after_units:$k "${NICE[@]}" "${LAUNCH[@]}" \
      -x STICKSLIP_FAULT_INJECT "$BIN" "${M[@]}" -o mt 2>mt.err & mp=$!; BG+=("$mp")
    ( sleep 60; kill -9 $mp ) >/dev/null 2>&1 & local dog=$!
    t_msg=""
    while kill -0 $mp 2>/dev/null; do
      grep -q "injected fault" mt.err 2>/dev/null && { t_msg=$(now_ms); break; }
      sleep 0.02
    done
    { wait $mp; } 2>/dev/null; rc=$?
    local t_end; t_end=$(now_ms)
    kill $dog 2>/dev/null; wait $dog 2>/dev/null
    [[ -z $t_msg ]] && grep -q "injected fault" mt.err && t_msg=$t_end  # exited within one poll
    if ((rc == 0)) && [[ -z $t_msg ]]; then other=$((other + 1)); continue; fi  # finished first
    n=$i
    [[ -n $t_msg ]] || bad $i "K=$k: no message from the worker: $(tail -c 300 mt.err)"
    ((rc != 0)) || bad $i "K=$k: mpirun exit 0 after the worker failed"
    grep -q "stickslip: error: MPI rank 1: injected fault" mt.err \
      || bad $i "K=$k: the worker's message is missing: $(tail -c 300 mt.err)"
    mpi_secs=$(( t_end - ${t_msg:-$t_end} ))
    ((mpi_secs <= 10000)) || bad $i "K=$k: exit $mpi_secs ms after the message (> 10 s)"
    if [[ -d mt/.journal ]]; then
      timeout 120 "${LAUNCH[@]}" "$BIN" "${M[@]}" --resume -o mt >/dev/null 2>"$W/final.err" \
        || bad $i "K=$k: mpirun --resume: exit $?: $(tail -c 300 "$W/final.err")"
      kept=$(grep -Eo '[0-9]+ units from the journal' "$W/final.err" | grep -Eo '^[0-9]+' || echo 0)
      ((kept > kept_max)) && kept_max=$kept
      [[ -z $kept_min ]] || ((kept < kept_min)) && kept_min=$kept
      same_sweep ref_m mt || bad $i "K=$k: resumed outputs differ from the single-process run"
    elif [[ -e mt/results.nc ]]; then  # finished and wrote its outputs before the abort
      same_sweep ref_m mt || bad $i "K=$k: outputs of a run that finished first differ"
    else
      bad $i "K=$k: no journal left to resume"
    fi
    ((mpi_secs > max)) && max=$mpi_secs
    [[ " $codes " == *" $rc "* ]] || codes="$codes $rc"
    [[ -z $k_min ]] || ((k < k_min)) && k_min=$k
    ((k > k_max)) && k_max=$k
    ((trial_ok)) || lost=$((lost + 1))
  done
  notes="K = ${k_min:-?}-$k_max results sent before the throw; exit codes:$codes; slowest exit $(secs $max) s after the worker's message; the journal kept ${kept_min:-0}-$kept_max of 960 units; $other runs finished first (not counted)"
}

# ------------------------------------------------------------------ 6. two writers
# A sweep runs in DIR; at a random moment a second writer (sweep --overwrite,
# sweep --resume, merge -o DIR or reproduce -o DIR, in turn) must be refused
# with exit 2 within 5 s naming the first; the first must finish with the
# uninterrupted run's outputs.
row_two_writers() {
  local N; N=$(trials 20)
  "$BIN" "${T[@]}" -o ref_t 2>/dev/null || { notes="reference run failed"; lost=1; return; }
  "$BIN" "${A[@]}" --shard 0/1 -o shard_t 2>/dev/null || { notes="shard failed"; lost=1; return; }
  local i rc t0 late=0 kind
  local kinds=(sweep-overwrite sweep-resume merge reproduce)
  for ((i = 1; i <= N; i++)); do
    trial_ok=1; rm -rf tw
    "${NICE[@]}" "$BIN" "${T[@]}" -o tw 2>tw.err & local first=$!; BG+=("$first")
    local k; for ((k = 0; k < 200; k++)); do [[ -s tw/.stickslip.lock ]] && break; sleep 0.05; done
    sleep "$(secs "$(rand_ms 1000)")"
    kind=${kinds[i % 4]}
    t0=$(now_ms)
    case $kind in
      sweep-overwrite) "$BIN" "${A[@]}" --overwrite -o tw >/dev/null 2>tw2.err ;;
      sweep-resume) "$BIN" "${T[@]}" --resume -o tw >/dev/null 2>tw2.err ;;
      merge) "$BIN" merge shard_t -o tw >/dev/null 2>tw2.err ;;
      reproduce) "$BIN" "${R[@]}" --overwrite -o tw >/dev/null 2>tw2.err ;;
    esac
    rc=$?
    local alive=1; kill -0 $first 2>/dev/null || alive=0
    ((rc == 2)) || bad $i "$kind: second writer exit $rc, expected 2: $(tail -c 200 tw2.err)"
    grep -q "is in use by stickslip sweep (pid $first" tw2.err || bad $i "$kind: refusal does not name the first: $(tail -c 200 tw2.err)"
    (( $(now_ms) - t0 <= 5000 )) || bad $i "$kind: refused only after $(( $(now_ms) - t0 )) ms"
    ((alive)) || late=$((late + 1))
    wait_rc $first
    ((rc == 0)) || bad $i "the first sweep: exit $rc: $(tail -c 200 tw.err)"
    same_sweep ref_t tw || bad $i "$kind: the first's outputs differ from the uninterrupted run"
    n=$i; ((trial_ok)) || lost=$((lost + 1))
  done
  notes="second writers: sweep --overwrite, sweep --resume, merge, reproduce in turn; $late of $N refused after the first had exited"
}

# ------------------------------------------------------------------ the table
run_row kill_sweep "kill -9 of \`sweep\` (twice per trial), then \`--resume\`" row_kill_sweep
run_row kill_reproduce "kill -9 of \`reproduce --quick\`, then \`--resume\`" row_kill_reproduce
run_row kill_sensitivity "kill -9 of \`sensitivity\` (twice per trial), then \`--resume\`" row_kill_sensitivity
run_row disk_journal "disk full while journaling (exit 3), then \`--resume\` with room" row_disk_journal
run_row disk_output "disk full while writing outputs (exit 3), then \`--resume\` with room" row_disk_output
run_row damage_segment "journal segment: random bytes flipped or cut, then \`--resume\`" row_damage_segment
run_row damage_header "journal header: random bytes flipped or cut, then \`--resume\`" row_damage_header
run_row mpi_kill_worker "MPI: kill -9 of rank 1 (exit within 10 s), then \`--resume\`" row_mpi_kill_worker
run_row mpi_throw "MPI: a worker throws outside its compute threads" row_mpi_throw
run_row mpi_usr1 "MPI: SIGUSR1 to mpirun (exit 138), then \`--resume\`" row_mpi_usr1
run_row mpi_term_ranks "MPI: SIGTERM to every rank, as srun sends it (exit 143), then \`--resume\`" row_mpi_term_ranks
run_row mpi_term_mpirun "MPI: SIGTERM to mpirun (mpirun kills the ranks), then \`--resume\`" row_mpi_term_mpirun
run_row two_writers "two writers on one directory: the second refused (exit 2)" row_two_writers

echo
echo "| Fault | Trials | Data lost | Time | Result | Notes | Command |"
echo "|---|---:|---:|---:|---|---|---|"
for line in "${RESULTS[@]}"; do echo "$line"; done
echo
if [[ -s $FAILLOG ]]; then
  echo "Failed checks (first 30):"
  head -n 30 "$FAILLOG" | sed 's/^/- /'
  echo
fi
((skipped)) && echo "($skipped rows skipped)"
echo "$passed passed, $failed failed"
((failed == 0))
