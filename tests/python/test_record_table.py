"""One table of per-realization record fields (include/stickslip/record_schema.hpp):
records.csv's record columns are its identity and outcome rows, and the
"statistics" of `simulate --format json` and Python's Realization.record are
its outcome rows, in the table's order and with the same values. A field
written by hand in one output and missing from another, or a writer's own
list of keys, fails here."""
import csv
import json
import math

import stickslip
from stickslip import _stickslip

FIELDS = _stickslip.record_fields()
IDENTITY = [f["name"] for f in FIELDS if f["role"] == "identity"]
OUTCOME = [f["name"] for f in FIELDS if f["role"] == "outcome"]
MODEL = dict(lam=1.3, mu=4.0, k=40.0, ta=12.0, c=0.3)
CLI_MODEL = ["--lambda", 1.3, "--mu", 4.0, "--k", 40.0, "--ta", 12.0, "--c", 0.3]
SEED = 11


def test_the_table_has_the_expected_roles():
    assert [f["role"] for f in FIELDS if f["role"] != "internal"] == (
        ["identity"] * len(IDENTITY) + ["outcome"] * len(OUTCOME))
    names = [f["name"] for f in FIELDS]
    assert len(set(names)) == len(names)
    symbols = [f["symbol"] for f in FIELDS if f["symbol"]]
    assert len(set(symbols)) == len(symbols) and not set(symbols) & set(names)
    # The powers, which the issue found missing from simulate and Python.
    assert {"friction_power", "damping_power"} <= set(OUTCOME)


def records_csv(cli, tmp_path):
    out = tmp_path / "sweep"
    cli("sweep", *CLI_MODEL, "--realizations", 6, "--block-size", 3, "--seed", SEED, "--records",
        "--statistics", "family", "-o", out)
    with open(out / "records.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def simulate_json(cli, tmp_path, realization):
    path = tmp_path / f"r{realization}.json"
    cli("simulate", *CLI_MODEL, "--seed", SEED, "--realization", realization, "--format", "json",
        "-o", path)
    return json.loads(path.read_text())


def same(a, b):
    return a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))


def test_records_csv_simulate_json_and_python_record_carry_the_table(cli, tmp_path):
    header, rows = records_csv(cli, tmp_path)
    assert header[0] == "point"
    first = header.index(IDENTITY[0])
    assert header[first:] == IDENTITY + OUTCOME
    for row in rows[:3]:
        r = int(row[first])
        theirs = dict(zip(header[first:], row[first:]))
        doc = simulate_json(cli, tmp_path, r)
        stats = doc["statistics"]
        assert list(stats) == OUTCOME
        ours = stickslip.simulate(seed=SEED, realization=r, **MODEL).record
        assert list(ours) == OUTCOME
        # The same values in all three (records.csv's -1 / 0/1 markers, the
        # JSON's null where the realization has no first stick).
        for name in OUTCOME:
            value = ours[name]
            text = theirs[name]
            if isinstance(value, bool):
                assert text == str(int(value)) and stats[name] is value, name
            elif isinstance(value, int):
                assert int(text) == value and stats[name] == value, name
            else:
                assert same(float(text), value), (name, text, value)
                assert stats[name] is None if value == -1 else same(stats[name], value), name
        init = doc["initial_conditions"]
        assert [float(theirs[n]) for n in ("x0", "xdot0")] == [init["x0"], init["xdot0"]]
        assert int(theirs["belt_start"]) == init["belt_start"]


def test_a_field_reads_by_its_symbol():
    r = stickslip.simulate(seed=SEED, realization=2, **MODEL).record
    for f in FIELDS:
        if f["symbol"] and f["role"] == "outcome":
            assert same(r[f["symbol"]], r[f["name"]]), f
    assert r["S_T"] == r["sticks"] and r["R"] == r["stick_fraction"]
    assert r.get("S_L") == r["slips"] and r.get("no such field", 7) == 7
