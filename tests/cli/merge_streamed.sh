# `merge` of a grid of more than 1,024 points writes its outputs window by
# window (docs/outputs.md), as `sweep` does: the same files as the unsharded
# sweep; and a write that fails (`ulimit -f`) at any point, during a window
# or at the commit, exits 3 and leaves no temporary and no OUT it created.
source "$(dirname "$0")/lib.sh"

grid=(--lambda lin:0.5:5:40 --mu lin:0.5:5:30 --realizations 2 --ta 1 --seed 4)
run_ok sweep "${grid[@]}" -o one
run_ok sweep "${grid[@]}" --shard 0/2 -o s0
run_ok sweep "${grid[@]}" --shard 1/2 -o s1
run_ok merge s0 s1 -o m
cmp -s one/summary.csv m/summary.csv || fail "the merged summary.csv is not the sweep's"
grep -q '"command_line": ".* merge s0 s1 -o m"' m/summary.json || fail "summary.json: not the merge's command line"
"$PY" - one/results.nc m/results.nc <<'PYEOF' || fail "the merged results.nc is not the sweep's"
import sys, netCDF4, numpy as np
a, b = (netCDF4.Dataset(p) for p in sys.argv[1:])
assert sorted(a.variables) == sorted(b.variables)
for n in a.variables:
    x, y = np.asarray(a[n][:]), np.asarray(b[n][:])
    assert x.tobytes() == y.tobytes(), n
# streamed: the chunks end at the windows' rows (32 of 40 rows of 30 points)
assert any(v.chunking() != "contiguous" and v.chunking()[0] == 32 for v in b.variables.values())
# the merge made the file: its own command line, not shard 0's
assert " merge s0 s1 -o m" in b.command_line and "--shard" not in b.command_line, b.command_line
assert b.command_line in b.history, b.history
PYEOF
pass
# A grid of one window (written at once): the merge's command line too.
small=(--lambda 1,2 --mu 5 --realizations 4 --ta 1)
run_ok sweep "${small[@]}" --shard 0/2 -o q0
run_ok sweep "${small[@]}" --shard 1/2 -o q1
run_ok merge q0 q1 -o qm
grep -q '"command_line": ".* merge q0 q1 -o qm"' qm/summary.json ||
  fail "summary.json of a one-window merge: not the merge's command line"
pass
nc_failures=0
for limit in 100 600 1200 1288; do
  rm -rf "m$limit"
  (ulimit -f "$limit"; "$BIN" merge s0 s1 -o "m$limit") >out.txt 2>err.txt
  rc=$?
  checks=$((checks + 1))
  if ((rc == 0)); then
    [[ -z $(ls m$limit/*.tmp 2>/dev/null) ]] || fail "ulimit -f $limit: a temporary beside the outputs"
    continue
  fi
  ((rc == 3)) || fail "ulimit -f $limit: exit $rc, expected 3 (I/O): $(cat err.txt)"
  # One message, once: netCDF-C++'s destructor printed its own failed close
  # ahead of it, and its text carried "NetCDF: " twice and a source line.
  [[ $(wc -l <err.txt) == 1 && $(cat err.txt) == "stickslip: error: "* ]] ||
    fail "ulimit -f $limit: stderr is not one error line: $(cat err.txt)"
  grep -q "NetCDF: NetCDF\|file: nc" err.txt && fail "ulimit -f $limit: netCDF-C++'s raw text: $(cat err.txt)"
  if grep -q "results.nc': NetCDF: " err.txt; then
    nc_failures=$((nc_failures + 1))
    grep -q "netCDF does not say why; the file-size limit (ulimit -f) is $((limit * 1024)) bytes" err.txt ||
      fail "ulimit -f $limit: the NetCDF error does not name the limit: $(cat err.txt)"
  fi
  [[ ! -e m$limit ]] || fail "ulimit -f $limit: the failed merge left m$limit: $(ls -a m$limit)"
done
checks=$((checks + 1))
((nc_failures > 0)) || fail "no limit failed inside results.nc's own writes"
finish
