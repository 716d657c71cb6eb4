#!/usr/bin/env bash
# The README's second command (and CI's): installs what is missing, builds
# everything in Release (library, tools, tests, benchmarks) and runs the whole
# test suite with CTest.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-"$here/build"}
"$here/scripts/setup.sh"
BUILD_DIR="$build_dir" "$here/scripts/build.sh"
ctest --test-dir "$build_dir" --output-on-failure --parallel "$(nproc)" --timeout 600
