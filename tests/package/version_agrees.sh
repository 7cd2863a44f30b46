# package.version_agrees: the version has one source, project(VERSION) in
# the top CMakeLists.txt, passed here by CMake as EXPECTED. Everything that
# states a version must say the same:
#   `stickslip --version`, summary.json (parameters.version), results.nc
#   (global attribute version), the package version file (and it accepts
#   find_package(stickslip MAJOR.MINOR), not the next major release, and in
#   0.x not the next minor one),
#   CITATION.cff (version:) and CHANGELOG.md (a "## [EXPECTED]" section).
# Usage: bash version_agrees.sh path/to/stickslip EXPECTED SOURCE_DIR
# Environment: STICKSLIP_VERSION_FILE, the generated stickslip-config-version.cmake
# (empty when the build has no install rules: that check is skipped).
source "$(dirname "$0")/../cli/lib.sh"
expected=${2:?usage: $0 stickslip VERSION SOURCE_DIR}
source_dir=${3:?usage: $0 stickslip VERSION SOURCE_DIR}
cmake_cmd=${CMAKE_COMMAND:-cmake}
[[ $expected =~ ^[0-9]+\.[0-9]+\.[0-9]+$ ]] || fail "project version '$expected' is not MAJOR.MINOR.PATCH"

# --version: "stickslip VERSION (git revision)"
run_ok --version
expect_eq "--version" "$(head -1 stdout | cut -d' ' -f1-2)" "stickslip $expected"

# the outputs of a sweep
run_ok sweep --lambda 1 --realizations 10 --threads 1 -o out
expect_eq "summary.json version" \
  "$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["parameters"]["version"])' out/summary.json)" \
  "$expected"
if command -v ncdump >/dev/null; then
  expect_eq "results.nc version" \
    "$(ncdump -h out/results.nc | sed -n 's/^[[:space:]]*:version = "\(.*\)" ;$/\1/p')" "$expected"
else
  echo "ncdump not found: results.nc not checked"
fi

# the package version file, as find_package evaluates it
version_file=${STICKSLIP_VERSION_FILE:-}
ask() {  # ask REQUESTED: "PACKAGE_VERSION compatible?" for find_package(stickslip REQUESTED)
  local requested=$1 major minor
  IFS=. read -r major minor _ <<<"$requested"
  cat >ask.cmake <<CMAKE
set(PACKAGE_FIND_VERSION "$requested")
set(PACKAGE_FIND_VERSION_MAJOR "$major")
set(PACKAGE_FIND_VERSION_MINOR "${minor:-0}")
set(PACKAGE_FIND_VERSION_COUNT 2)
set(CMAKE_SIZEOF_VOID_P 8)
include("$version_file")
message("\${PACKAGE_VERSION} \${PACKAGE_VERSION_COMPATIBLE}")
CMAKE
  "$cmake_cmd" -P ask.cmake 2>&1
}
if [[ -z $version_file ]]; then
  echo "no install rules (STICKSLIP_INSTALL=OFF): package version file not checked"
elif [[ -f $version_file ]]; then
  IFS=. read -r major minor _ <<<"$expected"
  expect_eq "package version file, find_package(stickslip $major.$minor)" \
    "$(ask "$major.$minor")" "$expected TRUE"
  expect_eq "package version file, find_package(stickslip $((major + 1)).0)" \
    "$(ask "$((major + 1)).0")" "$expected FALSE"
  if [[ $major == 0 ]]; then  # 0.x: a minor release may break the API
    expect_eq "package version file, find_package(stickslip 0.$((minor + 1)))" \
      "$(ask "0.$((minor + 1))")" "$expected FALSE"
  fi
else
  fail "no package version file $version_file"
fi

# the citation and the changelog
expect_eq "CITATION.cff version" \
  "$(sed -n 's/^version: *"\{0,1\}\([^"]*\)"\{0,1\} *$/\1/p' "$source_dir/CITATION.cff")" "$expected"
checks=$((checks + 1))
grep -q "^## \[$expected\]" "$source_dir/CHANGELOG.md" ||
  fail "CHANGELOG.md has no '## [$expected]' section"

finish
