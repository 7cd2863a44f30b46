# The model family from the command line: flags, TOML, replay
# files with levels, every bad input of the family refused before any work
# (exit 2, the parameter, the value and the allowed range, nothing written),
# and the paper's model written as a family member giving the paper's bits.
source "$(dirname "$0")/lib.sh"

exit_code() { "$BIN" "$@" >"$WORK/stdout" 2>"$WORK/stderr"; echo $?; }

# ---- bad input: exit 2, names, nothing written ----
bad() {  # bad "phrases" ARGS... (sweep and simulate)
  local phrases=$1
  shift
  expect_fail "$phrases" sweep --realizations 10 "$@"
  expect_eq "exit code of sweep $*" "$(exit_code sweep --realizations 10 -o "$WORK/never" "$@")" 2
  [[ -e $WORK/never ]] && fail "sweep $* created its output directory"
  expect_fail "$phrases" simulate "$@"
  expect_eq "exit code of simulate $*" "$(exit_code simulate "$@")" 2
}
bad "mu_k (kinetic friction)|4|<= mu_s = 3" --mu-s 3 --mu-k 4
bad "mu_k (kinetic friction)|6|<= mu_s = 5" --mu-k 6
bad "c (damping)|-0.5|>= 0" --c -0.5
bad "c (damping)|-1|>= 0" --damping -1
bad "belt-levels (count)|1|at least 2 levels" --belt-levels 1
bad "belt level v2|1|distinct" --belt-levels 1,1
bad "belt level v3|-1|distinct" --belt-levels -1,0,-1
bad "--belt-levels entry #2|'inf'|finite" --belt-levels 1,inf
bad "belt-rates r2|0|rate > 0" --belt-rates 1,0
bad "belt-rates r1|-2|rate > 0" --belt-rates -2,1
bad "--belt-rates entry #1|'nan'|finite" --belt-rates nan,1
bad "belt-rates (count)|3|exactly 2" --belt-rates 1,2,3
bad "belt generator|(missing)|3 x 3" --belt-levels 1,0,-1
bad "--belt-start|'3'|+1 (first level), -1 (second level) or stationary" --belt-start 3
expect_fail "grid axis|mu|mu sets mu_s and mu_k" sweep --mu 1,2 --mu-s 3
expect_fail "grid axis|V|belt levels are given" sweep --V 1,2 --belt-levels 1,-2

# a generator row that does not sum to 0, and a non-square one (TOML)
cat >gen.toml <<'TOML'
[model]
belt_levels = [1, 0, -1]
belt_generator = [[-1, 0.5, 0.5], [1, -2, 1], [0.5, 0.5, -2]]
TOML
expect_fail "belt generator row 3 sum|-1|0 (q3,3 = -sum" sweep --config gen.toml
cat >square.toml <<'TOML'
[model]
belt_levels = [1, 0, -1]
belt_generator = [[-1, 1], [1, -1]]
TOML
expect_fail "belt generator (entries)|4|n x n = 9 rates for 3 levels" sweep --config square.toml
expect_fail "--belt-generator|a square matrix" simulate --belt-levels 1,0,-1 --belt-generator '-1,1;1,-1,0'
bad "belt rate q1,2|-1|rate >= 0" --belt-levels 1,-1 --belt-generator '1,-1;1,-1'
bad "belt generator row 1 sum|0.5|0 (q1,1" --belt-levels 1,0,-1 --belt-generator '-1,1,0.5;1,-2,1;1,1,-2'
bad "belt rate of leaving belt level v2|0|rate > 0" --belt-levels 1,0,-1 --belt-generator '-1,1,0;0,0,0;1,1,-2' 

# a replay file naming a level the belt does not have
printf '0.5 2\n1.5 4\n' >levels.txt
expect_fail "belt level at levels.txt:2|'4'|1 to 2" simulate --switch-times-file levels.txt
expect_eq "exit code of a bad level line" "$(exit_code simulate --switch-times-file levels.txt)" 2

# ---- the paper's model written as a family member: the same bits ----
run_ok sweep --lambda 0.5,3 --mu 2 --realizations 300 --records -o paper
run_ok sweep --lambda 0.5,3 --mu-s 2 --mu-k 2 --c 0 --belt-levels 1,-1 --realizations 300 --records -o spelled
cut -d, -f3- paper/summary.csv >a.csv
cut -d, -f3- spelled/summary.csv >b.csv
cmp -s a.csv b.csv || fail "mu_s = mu_k = mu, c = 0, levels (V, -V) differ from the paper's sweep"
cmp -s paper/records.csv spelled/records.csv || fail "records differ for the paper's model spelled as a family"

# ---- a family sweep: flags and TOML agree, threads do not matter ----
family=(--c 0.3,1 --mu-s 6 --mu-k 4 --belt-levels 1.5,-0.5 --belt-rates 2,1
        --belt-start stationary --realizations 200 --records)
run_ok sweep "${family[@]}" --threads 1 -o fam1
run_ok sweep "${family[@]}" --threads 2 -o fam2
cmp -s fam1/summary.csv fam2/summary.csv || fail "family sweep differs between 1 and 2 threads"
cmp -s fam1/records.csv fam2/records.csv || fail "family records differ between 1 and 2 threads"
cat >fam.toml <<'TOML'
[model]
mu_s = 6
mu_k = 4
belt_levels = [1.5, -0.5]
belt_rates = [2, 1]
[grid]
c = [0.3, 1]
[initial]
belt_start = "stationary"
[sweep]
realizations = 200
keep_records = true
TOML
run_ok sweep --config fam.toml -o famtoml
cmp -s fam1/summary.csv famtoml/summary.csv || fail "TOML and flags give different family sweeps"
# c may be swept from 0; a negative c in a grid is refused
run_ok sweep --c 0,0.5 --mu-s 6 --realizations 20 -o czero
expect_fail "--c|'-1,0.5'|values >= 0" sweep --c -1,0.5
# lambda has no effect when belt rates are given: refused as an axis
expect_fail "grid axis|lambda|belt rates are given" sweep --lambda 0.5,2 --belt-rates 2,1

# every realization of the sweep is replayed alone by simulate
"$PY" - fam1 "$BIN" <<'PYEOF' || fail "family records are not replayed by simulate"
import csv, json, subprocess, sys
out, binary = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(f"{out}/records.csv")))
base = ["--mu-s", "6", "--mu-k", "4", "--belt-levels", "1.5,-0.5",
        "--belt-rates", "2,1", "--seed", "1", "--format", "json"]
for row in rows[::37]:
    doc = json.loads(subprocess.run([binary, "simulate", "--c", row["c"], "--realization",
                                     row["realization"], *base], check=True,
                                    capture_output=True, text=True).stdout)
    ic, st = doc["initial_conditions"], doc["statistics"]
    assert ic["x0"] == float(row["x0"]) and ic["xdot0"] == float(row["xdot0"]), row
    assert ic["belt_start"] == int(row["belt_start"]), (ic, row)
    assert st["sticks"] == int(row["sticks"]) and st["stick_fraction"] == float(row["stick_fraction"]), (st, row)
    assert doc["parameters"]["mu_s"] == 6 and doc["parameters"]["c"] == float(row["c"])
    assert doc["parameters"]["belt_levels"] == [1.5, -0.5]
    assert doc["parameters"]["belt_rates"] == [2, 1]
PYEOF
checks=$((checks + 1))

# summary.json and results.nc record the family
"$PY" - fam1 <<'PYEOF' || fail "summary.json lacks the family parameters"
import json, sys
doc = json.load(open(f"{sys.argv[1]}/summary.json"))
base = doc["parameters"]["base"]
assert base["mu_s"] == 6 and base["mu_k"] == 4 and base["c"] is None, base
assert base["belt_levels"] == [1.5, -0.5] and base["belt_rates"] == [2, 1], base
assert base["belt_generator"] == [[-2, 2], [1, -1]], base
assert doc["parameters"]["swept"] == ["c"]
assert doc["parameters"]["initial_conditions"]["belt_start"] == "stationary"
PYEOF
checks=$((checks + 1))

# ---- replay of a three-level belt with 't level' lines ----
printf '# t level\n1 3\n2.5 1\n4 2\n' >three.txt
run_ok simulate --belt-levels 1,0,-1 --belt-generator '-1,0.5,0.5;1,-2,1;0.5,0.5,-1' --belt-start 2 --switch-times-file three.txt --ta 6 \
  --x0 0.1 --xdot0 0 --events --format json
"$PY" - "$WORK/stdout" <<'PYEOF' || fail "three-level replay"
import json, sys
doc = json.load(open(sys.argv[1]))
sw = [(e["time"], e["v"]) for e in doc["events"] if e["kind"] == "belt_switch"]
assert sw == [(1, -1), (2.5, 1), (4, 0)], sw
assert doc["initial_conditions"]["belt_start"] == 2
# at level 0 from x' = 0 the mass starts in a stick that lasts until t = 1
first = doc["episodes"][0]
assert first["mode"] == "stick" and first["start"] == 0 and first["end"] == 1, first
PYEOF
checks=$((checks + 1))
finish
