#!/usr/bin/env bash
# Installs the Debian packages hsmap builds against. Non-interactive and
# idempotent: when every package is already installed it changes nothing and
# does not touch the network.
#
#   scripts/setup.sh           what building and testing need
#   scripts/setup.sh --docs    also python3-numpy and python3-matplotlib, for the
#                              scripts that draw the figures in docs/
#   scripts/setup.sh --fuzz    also clang, its libFuzzer/sanitizer runtimes and
#                              llvm-symbolizer, for scripts/fuzz.sh (docs/FUZZING.md)
# The two flags can be combined.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config time python3
  libeigen3-dev libceres-dev libsuitesparse-dev
  libopencv-dev libembree-dev libgeographiclib-dev libcgal-dev libgdal-dev
  libtbb-dev libcli11-dev libyaml-cpp-dev zlib1g-dev
  gdal-bin  # GDAL's command-line tools: gdalinfo (tests), gdal_translate (benchmarks)
  libgtest-dev libgmock-dev libbenchmark-dev
  snakemake  # the campaign workflow (scripts/campaign/) and its test
  chromium  # the run report's browser test (CTest report.browser, docs/REPORT.md)
)
# npm installs the report's plotting libraries at build time (pipelines/report/web).
# Debian's nodejs and npm, unless a node with its own npm is already installed
# (NodeSource's nodejs bundles npm, and Debian's npm would conflict with it).
if ! command -v npm > /dev/null; then PACKAGES+=(nodejs npm); fi
for flag in "$@"; do
  case "$flag" in
    --docs) PACKAGES+=(python3-numpy python3-matplotlib) ;;
    --fuzz) PACKAGES+=(clang libclang-rt-dev llvm) ;;
    *)
      echo "usage: scripts/setup.sh [--docs] [--fuzz]" >&2
      exit 2
      ;;
  esac
done

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
