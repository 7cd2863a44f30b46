# A sweep realization can be replayed alone: `simulate --seed S
# --realization r` with a point's parameters gives the same initial
# conditions, statistics and event counts as that realization's raw record.
source "$(dirname "$0")/lib.sh"

# log:... puts a computed (not typed) value on the grid: its shortest text in
# records.csv must read back to the same double.
run_ok sweep --lambda log:0.3:3.8:3 --mu 1,5 --ta 30 --realizations 20 --block-size 7 \
  --seed 11 --records -o out
[[ -s out/records.csv ]] || fail "records.csv missing"
"$PY" - "$BIN" out/records.csv <<'PYEOF' || fail "simulate does not replay the sweep's records"
import csv, json, subprocess, sys
binary, path = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(path)))
assert len(rows) == 6 * 20, len(rows)
checked = 0
for row in rows[::3]:
    out = subprocess.run(
        [binary, "simulate", "--lambda", row["lambda"], "--mu", row["mu"], "--ta", "30",
         "--seed", "11", "--realization", row["realization"], "--format", "json"],
        check=True, capture_output=True, text=True).stdout
    d = json.loads(out)
    ic, st, ev = d["initial_conditions"], d["statistics"], d["event_counts"]
    pairs = [
        ("x0", ic["x0"], float(row["x0"])),
        ("xdot0", ic["xdot0"], float(row["xdot0"])),
        ("belt_start", ic["belt_start"], int(row["belt_start"])),
        ("sticks", st["sticks"], int(row["sticks"])),
        ("slips", st["slips"], int(row["slips"])),
        ("stick_fraction", st["stick_fraction"], float(row["stick_fraction"])),
        ("belt_switches", ev["belt_switch"], int(row["belt_switches"])),
        ("stick_onsets", ev["stick_onset"], int(row["stick_onsets"])),
        ("stick_breaks", ev["stick_break"], int(row["stick_breaks"])),
        ("slip_reversals", ev["slip_reversal"], int(row["slip_reversals"])),
    ]
    if int(row["sticks"]) > 0:
        pairs += [("first_stick_start", st["first_stick_start"], float(row["first_stick_start"])),
                  ("first_stick_duration", st["first_stick_duration"],
                   float(row["first_stick_duration"]))]
    for name, got, want in pairs:
        assert got == want, (row["point"], row["realization"], name, got, want)
    checked += 1
print(f"{checked} realizations replayed exactly")
PYEOF
finish
