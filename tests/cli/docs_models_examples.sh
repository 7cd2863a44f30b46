#!/usr/bin/env bash
# Every `$ stickslip ...` example in docs/models.md prints what the page
# shows: each command (with its `\` continuation lines) is run in a fresh
# directory and its stderr, then its stdout, must equal the lines below it
# up to the next `$ ` line or the end of the code block.
DOC="$(cd "$(dirname "$0")/../.." && pwd)/docs/models.md"  # before lib.sh changes directory
source "$(dirname "$0")/lib.sh" "$@"

"$PY" - "$BIN" "$DOC" <<'PYEOF' || fail "docs/models.md examples differ from the binary's output"
import pathlib, shlex, subprocess, sys, tempfile
binary, doc = sys.argv[1], pathlib.Path(sys.argv[2])
examples, block, current = [], False, None
for line in doc.read_text().splitlines():
    if line.startswith("```"):
        block, current = not block, None
        continue
    if not block:
        continue
    if current is not None and current["command"].endswith("\\"):
        current["command"] = current["command"][:-1] + " " + line.strip()
    elif line.startswith("$ "):
        current = {"command": line[2:], "expected": []}
        examples.append(current)
    elif current is not None:
        current["expected"].append(line)
examples = [e for e in examples if e["command"].startswith("stickslip ")]
assert len(examples) >= 4, f"only {len(examples)} examples found in {doc}"
bad = 0
for e in examples:
    argv = shlex.split(e["command"])
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([binary, *argv[1:]], capture_output=True, text=True, cwd=tmp)
    got = (p.stderr + p.stdout).splitlines()
    if got != e["expected"]:
        bad += 1
        print(f"docs/models.md: $ {e['command']}\n  documented:", *e["expected"], "  printed:", *got,
              sep="\n    ", file=sys.stderr)
print(f"{len(examples)} examples, {bad} differ")
sys.exit(1 if bad else 0)
PYEOF
checks=$((checks + 1))
finish
