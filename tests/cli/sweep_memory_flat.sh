# Memory does not grow with the number of realizations: peak RSS of
# a one-point sweep with N = 10^3 and N = 10^5 differ by less than 4 MiB.
# (The journal buffers about --checkpoint-interval seconds of finished units,
# which is bounded by time, not N; a short interval keeps it small here.)
source "$(dirname "$0")/lib.sh"

peak_kib() {  # peak RSS in KiB of one sweep run as a child of python
  "$PY" - "$BIN" "$@" <<'PYEOF'
import resource, subprocess, sys
r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
if r.returncode != 0:
    sys.stderr.write(r.stderr.decode()); sys.exit(1)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
PYEOF
}

small=$(peak_kib sweep --lambda 3.8 --mu 5 --realizations 1000 --checkpoint-interval 0.05 -o n3) ||
  fail "N=1e3 sweep failed"
large=$(peak_kib sweep --lambda 3.8 --mu 5 --realizations 100000 --checkpoint-interval 0.05 -o n5) ||
  fail "N=1e5 sweep failed"
echo "peak RSS: N=1e3 ${small} KiB, N=1e5 ${large} KiB"
checks=$((checks + 1))
(( large - small < 4096 )) || fail "peak RSS grew from ${small} KiB to ${large} KiB with N"
finish
