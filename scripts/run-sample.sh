#!/usr/bin/env bash
# The main job: the bundled sample drawing through the simulated machine (firmware on the
# host, TMC428 model, real loopback TCP), with a summary and a plot in out/.
# Usage: scripts/run-sample.sh [drawing] [outdir]
set -euo pipefail
cd "$(dirname "$0")/.."
drawing="${1:-samples/engraver-word.dxf}"
outdir="${2:-out}"
scripts/bootstrap.sh
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target engraver
build/host-release/host/cli/engraver run "$drawing" -o "$outdir"
