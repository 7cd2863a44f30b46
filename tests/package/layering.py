"""package.layering: rules of the code's layout (docs/architecture.md).

1. No include cycle among the project's headers (include/, src/,
   backends/*/include/): a header reaches itself through no chain of
   `#include "..."`.
2. No new cycle among components. A component is a header and the .cpp
   that implements it (same name, the header included first): the .cpp's
   includes are the component's too. parameters.hpp and
   model/oscillator_model.hpp had no header cycle, yet parameters.cpp used
   the model while the model's header included parameters.hpp: the two
   could be neither understood nor tested apart. A cycle is broken by
   moving what both sides need into a header of its own (motion_mode.hpp,
   phase_reduction.hpp, sweep_spec.hpp, point_accumulators.hpp). A cycle
   that must stay is listed in KNOWN_COMPONENT_CYCLES with the reason (none
   is); the test fails on any other, and on a listed one once it is gone
   (delete its entry then).
3. Each library includes only the libraries below it (docs/architecture.md):
   core <- precision <- io <- run, study (run and study side by side). The
   core is include/stickslip/ outside io/, run/, study/ and precision/, and
   src/core.
4. No tracker issue numbers in code, tests, benchmarks, scripts or their
   comments, nor in README.md and docs/ ("issue" and a number): code and
   docs name the concept (or a commit, for a dated comparison), and a
   reader of the source or the manual has no tracker.

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
    # The public include directories, and src/core: the core's private
    # headers (engines/fast_math_simd.hpp, serialize/codecs.hpp) are included
    # by a path relative to it.
    roots = [os.path.join(top, "include"), os.path.join(top, "src", "core")]
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

    return {p: [r for r in (resolve(p, n) for n in inc) if r] for p, inc in found.items()}, resolve


# Each entry: the headers of one strongly connected set of components
# (relative paths, sorted), and why it is still there. Add none: break a
# new cycle instead.
KNOWN_COMPONENT_CYCLES = {}


def forwarder(path):
    """Whether a header only forwards to another (one #include, nothing else)."""
    with open(path, encoding="utf-8") as f:
        lines = [l.strip() for l in f if l.strip() and not l.strip().startswith("//")]
    lines = [l for l in lines if l != "#pragma once"]
    return len(lines) == 1 and INCLUDE.match(lines[0]) is not None


def component_graph(top, graph, resolve):
    """The header graph plus, for each header, the includes of its .cpp."""
    comp = {h: list(v) for h, v in graph.items()}
    for sub in ("src", "backends", "apps", "python/src"):
        for d, _, names in os.walk(os.path.join(top, sub)):
            for n in sorted(names):
                if not n.endswith(".cpp"):
                    continue
                p = os.path.join(d, n)
                with open(p, encoding="utf-8") as f:
                    inc = INCLUDE.findall(f.read())
                own = resolve(p, inc[0]) if inc else None
                if own is None or os.path.splitext(os.path.basename(own))[0] != n[:-4]:
                    continue
                for r in (resolve(p, i) for i in inc[1:]):
                    if r and r != own and r not in comp[own]:
                        comp[own].append(r)
    return comp


def strongly_connected(graph):
    """Tarjan's strongly connected sets of more than one node."""
    index, low, on, stack, out = {}, {}, set(), [], []

    def visit(u):
        index[u] = low[u] = len(index)
        stack.append(u)
        on.add(u)
        for v in graph[u]:
            if v not in index:
                visit(v)
                low[u] = min(low[u], low[v])
            elif v in on:
                low[u] = min(low[u], index[v])
        if low[u] == index[u]:
            scc = []
            while True:
                w = stack.pop()
                on.discard(w)
                scc.append(w)
                if w == u:
                    break
            if len(scc) > 1:
                out.append(scc)

    sys.setrecursionlimit(100000)
    for u in sorted(graph):
        if u not in index:
            visit(u)
    return out


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
    yield os.path.join(top, "README.md")
    for d, _, names in os.walk(os.path.join(top, "docs")):
        yield from (os.path.join(d, n) for n in sorted(names) if n.endswith(".md"))
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


# What each library may include: itself and the libraries below it.
ALLOWED = {
    "core": {"core"},
    "precision": {"core", "precision"},
    "io": {"core", "precision", "io"},
    "run": {"core", "precision", "io", "run"},
    "study": {"core", "precision", "io", "study"},
}


def library_of(top, path):
    """The library a header or source belongs to, or None (tests, apps, ...)."""
    rel = os.path.relpath(path, top).split(os.sep)
    if rel[0] == "src" and len(rel) > 2 and rel[1] in ALLOWED:
        return rel[1]
    if rel[:2] == ["include", "stickslip"]:
        return rel[2] if len(rel) > 3 and rel[2] in ALLOWED else "core"
    return None


def upward_includes(top, resolve):
    """Includes of a library's files that reach a library above it."""
    hits = []
    for sub in ("include", "src"):
        for d, _, names in os.walk(os.path.join(top, sub)):
            for n in sorted(names):
                if not n.endswith(HEADER + (".cpp",)):
                    continue
                p = os.path.normpath(os.path.join(d, n))
                lib = library_of(top, p)
                if lib is None:
                    continue
                with open(p, encoding="utf-8") as f:
                    for name in INCLUDE.findall(f.read()):
                        r = resolve(p, name)
                        target = library_of(top, r) if r else None
                        if target and target not in ALLOWED[lib]:
                            hits.append(f"{os.path.relpath(p, top)} ({lib}) includes "
                                        f"{os.path.relpath(r, top)} ({target})")
    return hits


def main():
    top = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    graph, resolve = headers(top)
    bad = 0
    for c in cycles(graph):
        print("include cycle: " + " -> ".join(os.path.relpath(p, top) for p in c))
        bad += 1
    seen = set()
    for scc in strongly_connected(component_graph(top, graph, resolve)):
        # A forwarding header is not a component: it lies on a cycle only
        # because the old path it keeps is still included.
        key = tuple(sorted(os.path.relpath(p, top) for p in scc if not forwarder(p)))
        seen.add(key)
        if key not in KNOWN_COMPONENT_CYCLES:
            print("component cycle (a header with its .cpp): " + ", ".join(key))
            bad += 1
    for key in KNOWN_COMPONENT_CYCLES:
        if key not in seen:
            print("known component cycle gone, delete its entry: " + ", ".join(key))
            bad += 1
    for h in upward_includes(top, resolve):
        print("include of a library above: " + h)
        bad += 1
    for h in issue_numbers(top):
        print("issue number in code or docs: " + h)
        bad += 1
    print(f"package.layering: {len(graph)} headers, {bad} violations")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
