#!/bin/sh
# Simulator speed of two (or more) engraver builds on one job, run in turn (A B A B ...) so
# the shared machine's load falls on both alike: prints, per build, each run's machine time
# per second of the simulator's processor time (`speedup_per_cpu_second` of the report),
# sorted; quote the median. Nothing is kept: outputs go to a temp dir.
# Usage: tools/bigjob/sim_speed_ab.sh JOB.dxf RUNS ENGRAVER [ENGRAVER...]
set -eu
job=$1
runs=$2
shift 2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
name=$(basename "$job" .dxf)
i=0
while [ "$i" -lt "$runs" ]; do
  n=0
  for engraver in "$@"; do
    n=$((n + 1))
    rm -rf "$dir/out"
    "$engraver" run "$job" -o "$dir/out" >/dev/null 2>&1 || true
    python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))
print(sys.argv[2], round(j["speedup_per_cpu_second"]))' "$dir/out/$name.json" "$n" >>"$dir/runs"
  done
  i=$((i + 1))
done
n=0
for engraver in "$@"; do
  n=$((n + 1))
  printf '%s:' "$engraver"
  awk -v n="$n" '$1 == n { print $2 }' "$dir/runs" | sort -n | tr '\n' ' '
  echo
done
