# package.downstream: what a C++ user of stickslip does, step by step, and
# fail at the first step that fails:
#   1. cmake --install the build into a fresh temporary prefix;
#   2. configure the consumer project (tests/package/downstream) with only
#      CMAKE_PREFIX_PATH pointing there; this also checks that the installed
#      headers are the public API (none under detail/, none includes Highway
#      or a header that is not installed), compiles each of them in its own
#      translation unit, and checks that stickslip::core has no I/O libraries;
#   3. build it and run its three programs (own_observer: a user's observer
#      on the header templates, compiled with -march=haswell and fused
#      multiply-adds allowed, gives the library's bits);
#   4. compare what they computed with the installed `stickslip` binary
#      running the same sweep: summary.csv byte for byte, and the R means.
# Usage: bash install_and_consume.sh BUILD_DIR CONSUMER_SOURCE_DIR
# Environment (set by tests/package/CMakeLists.txt): CMAKE_COMMAND,
# CONSUMER_GENERATOR, CONSUMER_CXX, CONSUMER_CXX_FLAGS, CONSUMER_BUILD_TYPE,
# CONSUMER_LAUNCHER, STICKSLIP_PYTHON.
set -euo pipefail
build_dir=${1:?usage: $0 BUILD_DIR CONSUMER_SOURCE_DIR}
consumer_src=${2:?usage: $0 BUILD_DIR CONSUMER_SOURCE_DIR}
cmake_cmd=${CMAKE_COMMAND:-cmake}
py=${STICKSLIP_PYTHON:-/usr/bin/python3}
work=$(mktemp -d "${TMPDIR:-/tmp}/stickslip-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

step() { echo "== $*"; }
die() { echo "FAIL: $*" >&2; exit 1; }

step "install into $prefix"
"$cmake_cmd" --install "$build_dir" --prefix "$prefix" >"$work/install.log" ||
  { cat "$work/install.log"; die "cmake --install"; }
for f in bin/stickslip include/stickslip/version.hpp include/stickslip/sweep.hpp \
         include/stickslip/io/writers.hpp lib/cmake/stickslip/stickslip-config.cmake \
         lib/cmake/stickslip/stickslip-config-version.cmake; do
  [[ -e $prefix/$f ]] || die "the install lacks $f"
done

step "configure the consumer"
args=(-S "$consumer_src" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix")
[[ -n ${CONSUMER_GENERATOR:-} ]] && args+=(-G "$CONSUMER_GENERATOR")
[[ -n ${CONSUMER_CXX:-} ]] && args+=(-DCMAKE_CXX_COMPILER="$CONSUMER_CXX")
[[ -n ${CONSUMER_CXX_FLAGS:-} ]] && args+=(-DCMAKE_CXX_FLAGS="$CONSUMER_CXX_FLAGS")
[[ -n ${CONSUMER_BUILD_TYPE:-} ]] && args+=(-DCMAKE_BUILD_TYPE="$CONSUMER_BUILD_TYPE")
[[ -n ${CONSUMER_LAUNCHER:-} ]] && args+=(-DCMAKE_CXX_COMPILER_LAUNCHER="$CONSUMER_LAUNCHER")
# own_observer with -march=haswell where the CPU runs it (fused multiply-adds)
if grep -qw fma /proc/cpuinfo && grep -qw avx2 /proc/cpuinfo; then
  args+=(-DSTICKSLIP_CONSUMER_FMA=ON)
else
  echo "note: this CPU has no FMA/AVX2: own_observer is built without -march=haswell"
fi
"$cmake_cmd" "${args[@]}" || die "configuring the consumer against $prefix"

step "build the consumer"
"$cmake_cmd" --build "$work/build" -j 2 || die "building the consumer"

step "run the consumer"
"$work/build/core_only" >"$work/core_only.txt" || die "core_only"
"$work/build/sweep_to_csv" "$work/library" || die "sweep_to_csv"
"$work/build/own_observer" || die "own_observer: the header templates in a user's build differ from the library"

step "compare with the installed stickslip binary"
"$prefix/bin/stickslip" sweep --lambda 1,3.8 --realizations 100 --seed 7 --threads 1 \
  -o "$work/binary" || die "installed stickslip sweep"
cmp "$work/library/summary.csv" "$work/binary/summary.csv" ||
  die "summary.csv from the library differs from the binary's"
"$py" - "$work/core_only.txt" "$work/binary/summary.csv" <<'PYEOF' || die "core_only R means"
import csv, sys
lines = [l.split() for l in open(sys.argv[1]) if not l.startswith("#")]
rows = list(csv.DictReader(open(sys.argv[2])))
assert len(lines) == len(rows) == 2, (lines, rows)
for (lam, r_mean), row in zip(lines, rows):
    assert float(lam) == float(row["lambda"]), (lam, row["lambda"])
    assert float(r_mean) == float(row["R_mean"]), (r_mean, row["R_mean"])
print("core_only R means equal the binary's:", [row["R_mean"] for row in rows])
PYEOF
site=$(find "$prefix" -path '*/stickslip/__init__.py' -printf '%h\n' 2>/dev/null | head -n 1)
if [[ -n $site ]]; then
  step "import the installed Python package"
  PYTHONPATH=$(dirname "$site") "$py" - "$work/binary/summary.json" <<'PYEOF' || die "installed Python package"
import json, sys
import stickslip
assert stickslip.__file__.startswith(sys.path[1]) or "prefix" in stickslip.__file__, stickslip.__file__
ds = stickslip.sweep(lam=[1.0, 3.8], realizations=100, seed=7, threads=1)
points = json.load(open(sys.argv[1]))["points"]
assert [float(v) for v in ds["stick_fraction_mean"].values] == [p["R"]["mean"] for p in points]
print("installed Python package equals the binary:", stickslip.__file__)
PYEOF
fi
echo "package.downstream: passed"
