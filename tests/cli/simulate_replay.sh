# Replay mode of `simulate`: given switch times and initial conditions give
# one exact, deterministic realization.
source "$(dirname "$0")/lib.sh"

given=(--x0 0.3 --xdot0 -0.2 --belt-start -1 --switch-times 1.5,2.25,7,7.5,12 --ta 15)
run_ok simulate "${given[@]}" && cp stdout first.csv
run_ok simulate "${given[@]}" && cp stdout second.csv
cmp -s first.csv second.csv || fail "replay is not deterministic"
# the seed, the realization and lambda do not matter once everything is given
run_ok simulate "${given[@]}" --seed 99 --realization 5 --lambda 30
cmp -s stdout first.csv || fail "replay depends on seed/realization/lambda"
# a switch-time file is the same as the list
printf '# measured belt signal\n1.5\n2.25\n\n7   # comment\n7.5\n12\n' >belt.txt
run_ok simulate --x0 0.3 --xdot0 -0.2 --belt-start -1 --switch-times-file belt.txt --ta 15
cmp -s stdout first.csv || fail "--switch-times-file differs from --switch-times"

# The given scenario is what was simulated: belt switches at exactly the
# given times, the given start, and no others.
run_ok simulate "${given[@]}" --format json --events && cp stdout replay.json
"$PY" - replay.json <<'PYEOF' || fail "replay JSON"
import json, sys
d = json.load(open(sys.argv[1]))
ic = d["initial_conditions"]
assert (ic["x0"], ic["xdot0"], ic["belt_start"]) == (0.3, -0.2, -1), ic
assert ic["given"] == {"x0": True, "xdot0": True, "belt_start": True}
assert d["switch_times"] == "given"
sw = [e["time"] for e in d["events"] if e["kind"] == "belt_switch"]
assert sw == [1.5, 2.25, 7, 7.5, 12], sw
assert d["episodes"][0]["x_start"] == 0.3 and d["episodes"][0]["belt_velocity"] == -1
PYEOF

# No switch in the window (exact case): the mass sticks once it catches the
# belt and the stick lasts (a - x_start)/V, then pure grazing slip.
# Here a = mu m g / k = 1 * 1 * 8 / 4 = 2 exactly, and V = 0.5: the stick lasts 4.
run_ok simulate --x0 0 --xdot0 0.5 --V 0.5 --belt-start +1 --mu 1 --g 8 --k 4 \
  --switch-times '' --ta 10
expect_eq "no switch: stick, then grazing slip" "$(tail -n +2 stdout | tr '\n' ' ')" \
  "stick,0,4,0,0.5,0 slip,4,10,2,0.5,1 "

# Partly given: the other inputs come from the stream, as in the sweep.
run_ok simulate --seed 3 --realization 4 --format json && cp stdout drawn.json
run_ok simulate --seed 3 --realization 4 --format json --x0 0.5 && cp stdout partial.json
"$PY" - drawn.json partial.json <<'PYEOF' || fail "partly given initial conditions"
import json, sys
a, b = (json.load(open(p))["initial_conditions"] for p in sys.argv[1:])
assert b["x0"] == 0.5 and b["given"]["x0"] and not b["given"]["xdot0"]
assert (a["xdot0"], a["belt_start"]) == (b["xdot0"], b["belt_start"])
PYEOF
finish
