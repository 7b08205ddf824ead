#!/bin/sh
# Simulator speed of two (or more) engraver builds on one job, run in turn (A B A B ...) so
# the shared machine's load falls on both alike: prints, per build, each run's machine time
# per second of the simulator's processor time (`speedup_per_cpu_second` of the report),
# sorted; quote the median. Nothing is kept: outputs go to a temp dir.
# A step that fails stops the script (exit 1) with a line on stderr naming the step, and the
# end of the engraver's output when its run left no report.
# Usage: tools/bigjob/sim_speed_ab.sh JOB.dxf RUNS ENGRAVER [ENGRAVER...]
set -eu
if [ "$#" -lt 3 ]; then
  echo "usage: $0 JOB.dxf RUNS ENGRAVER [ENGRAVER...]" >&2
  exit 2
fi
job=$1
runs=$2
shift 2
step="making a temp dir"
dir=""
# set -e stops at the first failing command without a word: say which step it was.
on_exit() {
  status=$?
  if [ "$status" -ne 0 ]; then
    echo "$0: failed (exit $status) at: $step" >&2
    if [ -n "$dir" ] && [ -s "$dir/log" ]; then
      echo "the engraver's last lines:" >&2
      tail -n 5 "$dir/log" >&2
    fi
  fi
  [ -z "$dir" ] || rm -rf "$dir"
}
trap on_exit EXIT
dir=$(mktemp -d)
name=$(basename "$job" .dxf)
i=0
while [ "$i" -lt "$runs" ]; do
  n=0
  for engraver in "$@"; do
    n=$((n + 1))
    rm -rf "$dir/out" "$dir/log"
    step="run $((i + 1)) of $engraver on $job"
    # A refused or failed job still ends below: its report is what is read.
    "$engraver" run "$job" -o "$dir/out" >"$dir/log" 2>&1 || true
    step="reading $name.json, the report of run $((i + 1)) of $engraver"
    python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))
print(sys.argv[2], round(j["speedup_per_cpu_second"]))' "$dir/out/$name.json" "$n" >>"$dir/runs"
  done
  i=$((i + 1))
done
step="printing the runs"
n=0
for engraver in "$@"; do
  n=$((n + 1))
  printf '%s:' "$engraver"
  awk -v n="$n" '$1 == n { print $2 }' "$dir/runs" | sort -n | tr '\n' ' '
  echo
done
