#!/usr/bin/env bash
# --preset paper-printed / paper-figures name the paper's printed
# parameters and the k = 40 N/m its figures used; flags given after still win.
source "$(dirname "$0")/lib.sh" "$@"

params() { "$PY" -c 'import json,sys; p=json.load(open(sys.argv[1]))["parameters"]; print(" ".join(f"{k}={p[k]:g}" for k in ("m","k","g","mu","V","lambda","ta")))' "$1"; }

run_ok simulate --preset paper-figures --format json && cp stdout figures.json
expect_eq "paper-figures" "$(params figures.json)" "m=1 k=40 g=9.81 mu=5 V=1 lambda=1 ta=50"
run_ok simulate --preset paper-printed --format json && cp stdout printed.json
expect_eq "paper-printed" "$(params printed.json)" "m=1 k=4 g=9.81 mu=5 V=1 lambda=1 ta=50"
run_ok simulate --preset paper-figures --k 20 --mu 2 --format json && cp stdout mixed.json
expect_eq "flags over the preset" "$(params mixed.json)" "m=1 k=20 g=9.81 mu=2 V=1 lambda=1 ta=50"
expect_fail "--preset|'paper'|paper-printed or paper-figures" simulate --preset paper

# A sweep with the preset is the sweep with k = 40, bit for bit.
A=(--lambda 0.5,3 --mu 5 --ta 10 --realizations 20 --block-size 10 --threads 1)
run_ok sweep "${A[@]}" --preset paper-figures -o with_preset
run_ok sweep "${A[@]}" --k 40 -o with_k
cmp -s with_preset/summary.csv with_k/summary.csv || fail "--preset paper-figures differs from --k 40"
run_ok sweep "${A[@]}" -o printed_default
cmp -s with_preset/summary.csv printed_default/summary.csv && fail "the preset changed nothing"
finish
