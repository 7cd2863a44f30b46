#!/usr/bin/env bash
# Outputs sized to their content: summary.json leaves out the joint (D, X)
# histograms unless --json-histograms asks for them (and says where they
# are); with it they equal results.nc's; results.nc stores its large
# variables deflated, its small ones contiguous, with the same values.
source "$(dirname "$0")/lib.sh" "$@"
G=(--lambda 0.5,3.8,10 --mu 0.5,5 --ta 10 --realizations 200 --seed 4 --threads 1
   --statistics paper,family)
run_ok sweep "${G[@]}" -o plain
run_ok sweep "${G[@]}" --json-histograms -o full
"$PY" - plain full <<'PY' >"$WORK/check.out" 2>&1
import json, sys
import netCDF4, numpy as np
plain, full = (json.load(open(d + "/summary.json")) for d in sys.argv[1:3])
assert plain["parameters"]["joint_histograms"] == "in results.nc only", plain["parameters"]["joint_histograms"]
assert full["parameters"]["joint_histograms"] == "here and in results.nc"
assert all("stick_duration_onset_counts" not in p for p in plain["points"])
nc = netCDF4.Dataset(sys.argv[2] + "/results.nc")
counts = np.asarray(nc["stick_duration_onset_counts"][:])
shape = counts.shape
flat = counts.reshape(-1, shape[-2], shape[-1])
for i, p in enumerate(full["points"]):
    assert np.array_equal(np.asarray(p["stick_duration_onset_counts"]), flat[i]), i
# the other members are the same in both files
for a, b in zip(plain["points"], full["points"]):
    b = {k: v for k, v in b.items() if not k.startswith("stick_duration_onset")}
    assert a == b
# deflated when large, contiguous when small; the values read back either way
big = nc["stick_duration_onset_counts"]
assert big.filters()["zlib"] and big.filters()["shuffle"], big.filters()
small = nc["stick_fraction_mean"] if "stick_fraction_mean" in nc.variables else None
if small is not None and small.size < 4096:
    assert not small.filters()["zlib"], small.filters()
print("ok")
PY
rc=$?
expect_eq "summary.json and results.nc checks ($(tail -n 3 "$WORK/check.out"))" "$rc" "0"
finish
