#!/usr/bin/env bash
# Runs every test: installs what is missing, builds the host tree (which also cross-builds
# the AVR proxy and runs it in simavr), then ctest; then, for the default preset, the suites
# that read untrusted input (drawing import, protocol parser) and the simulator (sim, stream)
# again under AddressSanitizer + UBSan (host-asan preset, ctest label "asan").
# Usage: scripts/test.sh [preset]   (ENGRAVER_SKIP_ASAN=1 leaves the sanitizer step out)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-host-debug}"
scripts/bootstrap.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset" -j2
if [ "$preset" = host-debug ] && [ "${ENGRAVER_SKIP_ASAN:-0}" != 1 ]; then
  cmake --preset host-asan >/dev/null
  cmake --build --preset host-asan --target host_drawing_tests protocol_tests sim_tests stream_tests
  ctest --preset host-asan -L asan -j2
fi
