#!/usr/bin/env bash
# Runs every test: installs what is missing, builds the host tree (which also cross-builds
# the AVR proxy and runs it in simavr), then ctest. Usage: scripts/test.sh [preset]
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-host-debug}"
scripts/bootstrap.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset" -j2
