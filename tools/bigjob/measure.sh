#!/bin/sh
# Big-job figures for docs/performance.md: for each size, makes a drawing with make_job.py,
# runs `engraver run` under /usr/bin/time -v and prints one table row (wall time, peak
# memory, plot size, machine time, speed). Nothing big is kept: files go to a temp dir.
# "CPU s" (user + system) is given beside the wall time: on a loaded shared machine the
# wall time says more about the other jobs than about this one.
# Usage: tools/bigjob/measure.sh ENGRAVER KIND N [N...]   (KIND: contour, lines, circle)
# The PNG plot is asked for (--png: `run` writes only the SVG by default) so the figures
# stay those of the tables measured before.
# BIGJOB_TIMEOUT_S=600 stops a run after that many seconds (its peak memory is still shown).
set -eu
engraver=$1
kind=$2
shift 2
here=$(dirname "$0")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "| $kind segments | wall s | CPU s | peak RSS MB | SVG KB | PNG KB | machine s | sim processor s | x real time per processor s | outcome |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for n in "$@"; do
  rm -rf "$dir/out"
  python3 "$here/make_job.py" "$kind" "$n" -o "$dir/job.dxf"
  if /usr/bin/time -v timeout "${BIGJOB_TIMEOUT_S:-0}" "$engraver" run "$dir/job.dxf" --png -o "$dir/out" >"$dir/stdout" 2>"$dir/time"; then :; fi
  wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$dir/time")
  rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$dir/time")
  user=$(sed -n 's/.*User time (seconds): //p' "$dir/time")
  sys=$(sed -n 's/.*System time (seconds): //p' "$dir/time")
  svg=$(($(stat -c %s "$dir/out/job.svg" 2>/dev/null || echo 0) / 1024))
  png=$(($(stat -c %s "$dir/out/job.png" 2>/dev/null || echo 0) / 1024))
  python3 - "$dir/out/job.json" "$n" "$wall" "$rss" "$svg" "$png" "$user" "$sys" <<'PY'
import json, sys
path, n, wall, rss, svg, png, user, system = sys.argv[1:]
try:
    j = json.load(open(path))
except OSError:
    j = {}
m, s = wall.split(":")[-2:]
print("| %s | %.1f | %.1f | %d | %s | %s | %.0f | %.2f | %.0f | %s |" % (
    n, int(m) * 60 + float(s), float(user) + float(system), int(rss) // 1024, svg, png,
    j.get("simulated_machine_ms", 0) / 1000.0, j.get("simulator_cpu_s", 0),
    j.get("speedup_per_cpu_second", 0), j.get("outcome", "no report")))
PY
done
