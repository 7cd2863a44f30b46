# Shapes of `simulate` output: the CSV episode table, JSON, events, the
# sampled trajectory and the one-line summary on stderr.
source "$(dirname "$0")/lib.sh"

run_ok simulate --seed 7 --realization 3 --ta 20 && cp stdout episodes.csv
expect_eq "CSV header" "$(head -1 episodes.csv)" "mode,start,end,x_start,belt_velocity,censored"
grep -qE '^seed 7 realization 3: S_T = [0-9]+, S_L = [0-9]+, R = ' stderr ||
  fail "summary line on stderr: $(cat stderr)"

# Episodes alternate, tile [0, t_a] exactly (text equality of the shared
# boundaries), only the last is censored, and numbers keep full precision.
"$PY" - episodes.csv <<'PYEOF' || fail "episode table invariants"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) >= 2, rows
assert all(len(r) == 6 for r in rows)
assert rows[0]["start"] == "0" and rows[-1]["end"] == "20", (rows[0], rows[-1])
for a, b in zip(rows, rows[1:]):
    assert a["end"] == b["start"], (a, b)
    assert a["mode"] != b["mode"], (a, b)
    assert a["censored"] == "0"
assert rows[-1]["censored"] == "1"
assert {r["mode"] for r in rows} <= {"stick", "slip"}
assert {r["belt_velocity"] for r in rows} <= {"1", "-1"}
# shortest round-trip text: 17 significant digits appear somewhere
assert any(len(r["start"].replace(".", "").lstrip("0")) >= 15 for r in rows[1:])
PYEOF

# -o FILE holds exactly what stdout would
mkdir -p out
run_ok simulate --seed 7 --realization 3 --ta 20 -o out/episodes.csv
cmp -s out/episodes.csv episodes.csv || fail "-o FILE differs from stdout"
expect_eq "-o leaves no temporary file" "$(ls out)" "episodes.csv"

# aliases give the same realization; another seed gives another one
run_ok simulate --seed 7 --realization 3 --window 20 --switch-rate 1 --friction-coefficient 5
cmp -s stdout episodes.csv || fail "long aliases differ from the symbols"
run_ok simulate --seed 8 --realization 3 --ta 20
cmp -s stdout episodes.csv && fail "another seed gave the same realization"

# JSON: the documented keys, and the same episodes as the CSV
run_ok simulate --seed 7 --realization 3 --ta 20 --format json && cp stdout episodes.json
run_ok simulate --seed 7 --realization 3 --ta 20 --format json --events && cp stdout events.json
"$PY" - episodes.json events.json episodes.csv <<'PYEOF' || fail "JSON shape"
import csv, json, sys
doc = json.load(open(sys.argv[1]))
for key in ("parameters", "seed", "realization", "initial_conditions", "episodes", "statistics"):
    assert key in doc, key
assert "events" not in doc
assert doc["seed"] == 7 and doc["realization"] == 3
assert doc["parameters"] == {"m": 1, "k": 4, "g": 9.81, "mu": 5, "V": 1, "lambda": 1, "ta": 20,
                             "c": 0, "mu_s": 5, "mu_k": 5, "belt_levels": [1, -1],
                             "belt_generator": [[-1, 1], [1, -1]], "belt_rates": [1, 1]}
ic = doc["initial_conditions"]
assert -1 <= ic["x0"] <= 1 and -1 <= ic["xdot0"] <= 1 and ic["belt_start"] in (1, -1)
rows = list(csv.DictReader(open(sys.argv[3])))
assert len(rows) == len(doc["episodes"])
for r, e in zip(rows, doc["episodes"]):
    assert e["mode"] == r["mode"] and e["mode"] in ("stick", "slip")
    for k in ("start", "end", "x_start", "belt_velocity"):
        assert e[k] == float(r[k]), (k, e, r)
    assert e["censored"] == (r["censored"] == "1")
sticks = sum(1 for e in doc["episodes"] if e["mode"] == "stick" and e["end"] > e["start"])
assert doc["statistics"]["sticks"] == sticks
ev = json.load(open(sys.argv[2]))
assert ev["episodes"] == doc["episodes"]
assert len(ev["events"]) > 0
for e in ev["events"]:
    assert set(e) == {"kind", "time", "x", "xdot", "v"}, e
    assert e["kind"] in ("belt_switch", "stick_onset", "stick_break", "slip_reversal")
times = [e["time"] for e in ev["events"]]
assert times == sorted(times)
counts = ev["event_counts"]
assert sum(counts.values()) == len(ev["events"])
PYEOF

# --events in CSV goes to events.csv next to -o; --trajectory to trajectory.csv
mkdir -p run
run_ok simulate --seed 7 --realization 3 --ta 20 --events --trajectory 0.01 -o run/episodes.csv
expect_eq "files next to -o" "$(ls run | tr '\n' ' ')" "episodes.csv events.csv trajectory.csv "
expect_eq "events header" "$(head -1 run/events.csv)" "kind,time,x,xdot,v"
expect_eq "trajectory header" "$(head -1 run/trajectory.csv)" "t,x,xdot,v,mode"
"$PY" - run/trajectory.csv run/events.csv run/episodes.csv <<'PYEOF' || fail "trajectory shape"
import csv, sys
traj = list(csv.DictReader(open(sys.argv[1])))
events = list(csv.DictReader(open(sys.argv[2])))
t = [float(r["t"]) for r in traj]
assert t[0] == 0.0 and t[-1] == 20.0
assert all(b >= a for a, b in zip(t, t[1:])), "time goes backwards"
assert len(traj) >= 2000
grid = {round(k * 0.01, 9) for k in range(2001)}
assert grid <= {round(x, 9) for x in t}, "grid points missing"
ts = set(t)
assert all(float(e["time"]) in ts for e in events), "an event instant is missing"
# the belt velocity takes both values around every belt switch
for e in events:
    if e["kind"] == "belt_switch":
        at = {r["v"] for r in traj if float(r["t"]) == float(e["time"])}
        assert at == {"1", "-1"}, (e, at)
# while sticking, x' equals v
for r in traj:
    if r["mode"] == "stick":
        assert abs(float(r["xdot"]) - float(r["v"])) < 1e-12, r
PYEOF

# --trajectory-file and --events-file choose the paths; stdout keeps the table
run_ok simulate --seed 7 --realization 3 --ta 20 --events --events-file ev.csv \
  --trajectory 0.5 --trajectory-file tr.csv
cmp -s stdout episodes.csv || fail "table on stdout changed by --events/--trajectory"
[[ -s ev.csv && -s tr.csv ]] || fail "--events-file / --trajectory-file not written"

# A given switch at t = 0 (docs/outputs.md, "Episodes"): the first row keeps
# the belt before it (+1, the --belt-start), the events table gives the
# switch at t = 0 with the new belt (-1), and the first slip runs on -1:
# the mass, at rest, slips until its velocity is -1 and sticks there, so the
# stick's x_start is below x0 and its belt is -1.
run_ok simulate --switch-times 0,1,60 --x0 0.1 --xdot0 0 --belt-start +1 --ta 5 --events \
  --events-file ev0.csv && cp stdout ep0.csv
"$PY" - ep0.csv ev0.csv <<'PYEOF' || fail "a switch at t = 0"
import csv, sys
ep = list(csv.DictReader(open(sys.argv[1])))
ev = list(csv.DictReader(open(sys.argv[2])))
assert ep[0]["mode"] == "slip" and ep[0]["start"] == "0" and ep[0]["belt_velocity"] == "1", ep[0]
assert ev[0]["kind"] == "belt_switch" and ev[0]["time"] == "0" and ev[0]["v"] == "-1", ev[0]
assert ep[1]["mode"] == "stick" and ep[1]["belt_velocity"] == "-1", ep[1]
assert float(ep[1]["x_start"]) < 0.1, ep[1]
PYEOF
finish
