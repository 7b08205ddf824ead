#!/usr/bin/env python3
"""Fails when a per-point or per-tick cycle count of the AVR proxy passes its goal.

Runs the proxy runner in simavr (the command after --) and reads its lines
  measure <name>: min A avg B max C cycles (n = N)
Each --avg NAME=LIMIT / --max NAME=LIMIT is a goal from docs/performance.md (issue 9: a
polynomial point at most half of 1 823 cycles, a tick's worst at most half of 13 741;
issue 22: the adaptive point 11 223 on average, 81 293 at worst). Cycle counts in simavr
are exact, so a flash cut that slows the hot path shows here, not in a reviewer's memory.
The max of a few-hundred-cycle measure may include one Timer1 overflow interrupt (~40
cycles) of the measuring clock, so short measures are held by their average.
"""
import argparse
import re
import subprocess
import sys


def budgets(pairs, kind):
    out = []
    for p in pairs:
        name, _, limit = p.rpartition("=")
        if not name or not limit.isdigit():
            sys.exit(f"cycle_budget_check: --{kind} wants NAME=LIMIT, not '{p}'")
        out.append((kind, name, int(limit)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--avg", action="append", default=[], metavar="NAME=LIMIT")
    ap.add_argument("--max", action="append", default=[], metavar="NAME=LIMIT")
    ap.add_argument("command", nargs=argparse.REMAINDER, help="-- simavr_run ... runner.elf")
    args = ap.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        sys.exit("cycle_budget_check: no command to run")
    run = subprocess.run(command, capture_output=True, text=True)
    measured = {}
    for m in re.finditer(r"^measure (.+?): min (\d+) avg (\d+) max (\d+) cycles", run.stdout,
                         re.M):
        measured[m.group(1)] = {"avg": int(m.group(3)), "max": int(m.group(4))}
    failed = 0
    for kind, name, limit in budgets(args.avg, "avg") + budgets(args.max, "max"):
        if name not in measured:
            print(f"FAIL {name}: not measured (the runner printed no such line)")
            failed += 1
            continue
        value = measured[name][kind]
        verdict = "ok" if value <= limit else "FAIL"
        failed += verdict == "FAIL"
        print(f"{verdict} {name}: {kind} {value} cycles, goal <= {limit}")
    if run.returncode != 0:
        print(f"FAIL the runner exited {run.returncode}")
        failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
