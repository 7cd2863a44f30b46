"""package.layering: two rules of the code's layout (docs/architecture.md).

1. No include cycle among the project's headers (include/, src/,
   backends/*/include/): a header reaches itself through no chain of
   `#include "..."`.
2. No tracker issue numbers in code, tests, benchmarks, scripts or their
   comments ("issue" and a number): code names the concept, and a reader of
   the source has no tracker.

Usage: python3 layering.py SOURCE_DIR. Prints every violation and exits 1
if there is one.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
ISSUE = re.compile(r"\bissues?[ _#-]{0,2}\d+\b", re.I)
HEADER = (".hpp", ".h", ".inl")
CODE = HEADER + (".cpp", ".py", ".cmake", ".sh", ".in")


def include_roots(top):
    roots = [os.path.join(top, "include")]
    backends = os.path.join(top, "backends")
    if os.path.isdir(backends):
        roots += [os.path.join(backends, b, "include") for b in sorted(os.listdir(backends))]
    return [r for r in roots if os.path.isdir(r)]


def headers(top):
    """Map of a header's path to the headers it includes (resolved)."""
    roots = include_roots(top)
    found = {}
    for base in roots + [os.path.join(top, "src")]:
        for d, _, names in os.walk(base):
            for n in names:
                if n.endswith(HEADER):
                    p = os.path.normpath(os.path.join(d, n))
                    with open(p, encoding="utf-8") as f:
                        found[p] = INCLUDE.findall(f.read())

    def resolve(frm, name):
        for base in [os.path.dirname(frm)] + roots:
            p = os.path.normpath(os.path.join(base, name))
            if p in found:
                return p
        return None

    return {p: [r for r in (resolve(p, n) for n in inc) if r] for p, inc in found.items()}


def cycles(graph):
    state, stack, out = {}, [], []

    def visit(u):
        state[u] = 1
        stack.append(u)
        for v in graph[u]:
            if state.get(v) == 1:
                out.append(stack[stack.index(v):] + [v])
            elif v not in state:
                visit(v)
        stack.pop()
        state[u] = 2

    sys.setrecursionlimit(100000)
    for u in sorted(graph):
        if u not in state:
            visit(u)
    return out


SCANNED = ("include", "src", "apps", "backends", "python/src", "python/stickslip", "cmake",
           "tests", "bench", "scripts", "examples")


def scanned_files(top):
    yield os.path.join(top, "CMakeLists.txt")
    for sub in SCANNED:
        for d, _, names in os.walk(os.path.join(top, sub)):
            for n in sorted(names):
                if n.endswith(CODE) or n == "CMakeLists.txt":
                    yield os.path.join(d, n)


def issue_numbers(top):
    hits = []
    for p in scanned_files(top):
        with open(p, encoding="utf-8") as f:
            for i, line in enumerate(f, 1):
                if ISSUE.search(line):
                    hits.append(f"{os.path.relpath(p, top)}:{i}: {line.strip()}")
    return hits


def main():
    top = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    graph = headers(top)
    bad = 0
    for c in cycles(graph):
        print("include cycle: " + " -> ".join(os.path.relpath(p, top) for p in c))
        bad += 1
    for h in issue_numbers(top):
        print("issue number in code: " + h)
        bad += 1
    print(f"package.layering: {len(graph)} headers, {bad} violations")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
