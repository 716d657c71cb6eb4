#!/usr/bin/env bash
# The README's first command: installs what is missing, builds hsmap, writes
# the built-in sample survey and inspects it (loads, validates, summarises).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-"$here/build"}
"$here/scripts/setup.sh"
BUILD_DIR="$build_dir" "$here/scripts/build.sh" --target hsmap
hsmap="$build_dir/tools/hsmap"
"$hsmap" sample --out "$build_dir/sample-survey" --force
"$hsmap" inspect "$build_dir/sample-survey"
