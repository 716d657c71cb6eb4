# Sourced by the benchmark scripts that take `SURVEY... [-- BUILD_DIR]`:
# sets `surveys` (the survey folders), `build` (default build), `hsmap` (the
# binary, which must exist) and `work` (${WORK_DIR:-/tmp}, where run folders
# go). Exits with a usage line (status 2) when no survey is given.
surveys=()
build="build"
while [[ $# -gt 0 ]]; do
  if [[ $1 == "--" ]]; then build="$2"; break; fi
  surveys+=("$1"); shift
done
((${#surveys[@]} > 0)) || { echo "usage: $0 SURVEY... [-- BUILD_DIR]" >&2; exit 2; }
hsmap="$build/tools/hsmap"
[[ -x "$hsmap" ]] || { echo "error: $hsmap not found; build it with scripts/build.sh --target hsmap" >&2; exit 1; }
work="${WORK_DIR:-/tmp}"
