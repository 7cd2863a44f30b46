# `sweep --config FILE`: the file holds the same settings as the flags, flags
# override it, the axis order is documented (docs/cli.md), and the resolved
# configuration stored with the results reruns to identical points.
source "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)
example="$here/../../examples/paper_study.toml"

axes() { "$PY" -c 'import json,sys; d=json.load(open(sys.argv[1]))["parameters"]; print(" ".join(a["name"] + "=" + str(len(a["values"])) for a in d["axes"]))' "$1"; }
base() { "$PY" -c 'import json,sys; d=json.load(open(sys.argv[1]))["parameters"]; print(d["base"][sys.argv[2]], d["realizations"], d["seed"])' "$1" "$2"; }

# The example file, shrunk by flags: a list replaces the file's lambda grid,
# a single number fixes mu (no mu axis), --realizations overrides 2000.
run_ok sweep --config "$example" --lambda 0.5,3.8 --mu 3 --ta 10 --realizations 30 --seed 4 -o ex
expect_eq "axes from file + flags" "$(axes ex/summary.json)" "lambda=2"
expect_eq "fixed mu, realizations, seed" "$(base ex/summary.json mu)" "3 30 4"
expect_eq "ta from the flag" "$(base ex/summary.json ta)" "10 30 4"

# Without flags the file's grid is used (40 x 8 for the paper; check the
# parsing only, with a dry small override of the run size).
run_ok sweep --config "$example" --realizations 1 --ta 0.5 -o full
expect_eq "paper grid" "$(axes full/summary.json)" "lambda=40 mu=8"

# Axis order: flags alone give lambda, mu, then the others as given.
run_ok sweep --k 2,4 --V 1,2 --mu 1,2 --lambda 1,2 --ta 5 --realizations 5 -o order1
expect_eq "flag axis order" "$(axes order1/summary.json)" "lambda=2 mu=2 k=2 V=2"
# A file keeps its own order; axes only given as flags come after it.
printf '[grid]\norder = ["k", "lambda"]\nlambda = [1, 2]\nk = "lin:2:4:3"\n' >order.toml
run_ok sweep --config order.toml --mu 1,2 --lambda 0.5,1,2 --ta 5 --realizations 5 -o order2
expect_eq "file order, flags appended" "$(axes order2/summary.json)" "k=3 lambda=3 mu=2"

# The resolved configuration stored in the output reruns to the same points.
"$PY" -c 'import json,sys; open("resolved.toml","w").write(json.load(open(sys.argv[1]))["parameters"]["config"])' \
  order2/summary.json || fail "no resolved config in summary.json"
run_ok sweep --config resolved.toml -o rerun
points() { "$PY" -c 'import json,sys; print(json.dumps(json.load(open(sys.argv[1]))["points"]))' "$1"; }
expect_eq "rerun from the resolved config" "$(points rerun/summary.json | md5sum)" \
  "$(points order2/summary.json | md5sum)"
finish
