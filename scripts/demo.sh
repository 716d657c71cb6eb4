#!/usr/bin/env bash
# The README's first command: installs what is missing, builds hsmap,
# simulates the small `tiny` survey (with ground truth) and inspects it
# (loads, validates, summarises).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-"$here/build"}
"$here/scripts/setup.sh"
BUILD_DIR="$build_dir" "$here/scripts/build.sh" --target hsmap
hsmap="$build_dir/tools/hsmap"
"$hsmap" simulate --preset tiny --out "$build_dir/tiny-survey" --force
"$hsmap" inspect "$build_dir/tiny-survey"
