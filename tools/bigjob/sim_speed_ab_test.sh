#!/bin/sh
# sim_speed_ab.sh with stand-in engravers: one that writes a report (its figure is printed)
# and one that fails (the script stops naming the step and showing the engraver's words).
# Usage: sim_speed_ab_test.sh PATH/TO/sim_speed_ab.sh
set -u
script=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cat >"$dir/good" <<'SH'
#!/bin/sh
# engraver run JOB -o OUT: a report only.
mkdir -p "$4" && echo '{"speedup_per_cpu_second": 41.6}' >"$4/$(basename "$2" .dxf).json"
SH
cat >"$dir/bad" <<'SH'
#!/bin/sh
echo "engraver: cannot read $2" >&2
exit 2
SH
chmod +x "$dir/good" "$dir/bad"

out=$(sh "$script" "$dir/job.dxf" 2 "$dir/good" 2>"$dir/err") || fail "good runs: exit $?: $(cat "$dir/err")"
[ "$out" = "$dir/good:42 42 " ] || fail "good runs printed '$out'"

sh "$script" "$dir/job.dxf" 2 "$dir/good" "$dir/bad" >/dev/null 2>"$dir/err"
status=$?
[ "$status" -eq 1 ] || fail "a failed run: exit $status, not 1"
grep -qF "failed (exit 1) at: reading job.json, the report of run 1 of $dir/bad" "$dir/err" ||
  fail "the failing step is not named: $(cat "$dir/err")"
grep -qF "engraver: cannot read $dir/job.dxf" "$dir/err" ||
  fail "the engraver's words are not shown: $(cat "$dir/err")"

sh "$script" "$dir/job.dxf" 2>"$dir/err" && fail "no engraver given: exit 0"
grep -q "^usage: " "$dir/err" || fail "no engraver given: $(cat "$dir/err")"
echo "ok"
