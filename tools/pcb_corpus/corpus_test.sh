#!/bin/sh
# The corpus report on the shared sample boards (../shared/samples/pcb from the source tree):
# every file reads and matches gerbv, every board plans and its tool cuts no copper. Skips
# (exit 77) without ../shared or gerbv.
# Usage: corpus_test.sh PCB_CORPUS_EXE SOURCE_DIR
exe=$1
samples=$2/../shared/samples/pcb
[ -d "$samples" ] || { echo "no $samples: skipped"; exit 77; }
command -v gerbv > /dev/null || { echo "no gerbv: skipped"; exit 77; }
out=$("$exe" "$samples") || exit 1
echo "$out"
# | all | files | read | M of C | boards | planned | P of K |
echo "$out" | awk -F'|' '
  $2 == " all " {
    seen = 1
    split($5, m, " of "); split($8, p, " of ")
    if ($3 + 0 < 1 || $3 != $4) { print "files read: " $4 " of " $3; bad = 1 }
    if (m[1] + 0 != m[2] + 0 || m[2] + 0 < 1) { print "gerbv agreement: " $5; bad = 1 }
    if ($6 + 0 < 1 || $6 != $7) { print "boards planned: " $7 " of " $6; bad = 1 }
    if (p[1] + 0 != p[2] + 0 || p[2] + 0 != $7 + 0) { print "isolation check: " $8; bad = 1 }
  }
  END { if (!seen) print "no summary row"; exit (bad || !seen) }'
