#!/bin/sh
# send --resume end to end over TCP: the simulator in real time, a send killed with SIGKILL
# mid-job, then `send --resume`; the cut path (pen-down trace) against an uninterrupted run.
# Usage: scripts/resume_demo.sh [ENGRAVER] [DRAWING] [KILL_AFTER_S]   (about 4 minutes)
set -e
E=${1:-build/host-debug/host/cli/engraver}
S=${2:-samples/engraver-word.dxf}
K=${3:-45}
D=$(mktemp -d)
here=$(dirname "$0")
$E sim --listen 127.0.0.1:18731 --realtime --trace "$D/ref.csv" >"$D/sim1.log" 2>&1 &
SIM=$!; sleep 0.5
$E send "$S" --to tcp://127.0.0.1:18731 --poll-ms 100 >"$D/ref.log" 2>&1
kill $SIM
$E sim --listen 127.0.0.1:18732 --realtime --trace "$D/int.csv" >"$D/sim2.log" 2>&1 &
SIM=$!; sleep 0.5
$E send "$S" --to tcp://127.0.0.1:18732 --poll-ms 100 >"$D/send1.log" 2>&1 &
SEND=$!; sleep "$K"; kill -9 $SEND; sleep 4
$E send "$S" --to tcp://127.0.0.1:18732 --poll-ms 100 --resume >"$D/send2.log" 2>&1
kill $SIM
grep "resuming at" "$D/send2.log"
python3 "$here/compare_cut_paths.py" "$D/ref.csv" "$D/int.csv"
echo "logs and traces in $D"
