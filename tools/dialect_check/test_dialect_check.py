#!/usr/bin/env python3
"""Proves dialect_check.py catches every planted violation in testdata/ and nothing else.

Each testdata file marks its violating lines with a trailing "// expect: <rule>[, <rule>]".
The check must report exactly those (file, line, rule) triples, exit 1 on the planted files,
and exit 0 with no report on the clean ones (clean.h, clean.cpp, clean_non_ascii.h).

Usage: test_dialect_check.py [--clang CLANG]
"""

import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "dialect_check.py")
DATA = os.path.join(HERE, "testdata")
CLEAN = ("clean.h", "clean.cpp", "clean_non_ascii.h")


def expected_findings():
    """(file, line, rule) for every "// expect:" marker in testdata/."""
    expected = set()
    for name in sorted(os.listdir(DATA)):
        with open(os.path.join(DATA, name), encoding="utf-8") as f:
            for number, text in enumerate(f, 1):
                m = re.search(r"//\s*expect:\s*(.+)$", text)
                if m:
                    for rule in m.group(1).split(","):
                        expected.add((name, number, rule.strip()))
    return expected


def run_check(clang, paths):
    command = [sys.executable, CHECK, "--repo", DATA] + paths
    if clang:
        command += ["--clang", clang]
    proc = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    reported = set()
    for line in proc.stdout.splitlines():
        m = re.match(r"^(.+?):(\d+): error: \[([a-z0-9-]+)\] ", line)
        if not m:
            print("unparseable report line: %r" % line)
            reported.add(("?", 0, line))
            continue
        reported.add((os.path.basename(m.group(1)), int(m.group(2)), m.group(3)))
    return proc.returncode, reported, proc.stderr


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--clang", help="clang++ for dialect_check.py")
    args = parser.parse_args()
    failures = 0

    planted = sorted(n for n in os.listdir(DATA) if n not in CLEAN)
    code, reported, stderr = run_check(args.clang, [os.path.join(DATA, n) for n in planted])
    expected = expected_findings()
    for miss in sorted(expected - reported):
        print("MISSED   %s:%d [%s]" % miss)
        failures += 1
    for extra in sorted(reported - expected):
        print("SPURIOUS %s:%d [%s]" % extra)
        failures += 1
    if code != 1:
        print("planted files: exit status %d, want 1\n%s" % (code, stderr))
        failures += 1
    files_with_rules = {name for name, _, _ in expected}
    for name in planted:
        if name not in files_with_rules:
            print("testdata/%s plants nothing (no // expect: marker)" % name)
            failures += 1

    code, reported, stderr = run_check(args.clang, [os.path.join(DATA, n) for n in CLEAN])
    if code != 0 or reported:
        print("clean files: exit status %d, want 0; reported %s\n%s"
              % (code, sorted(reported), stderr))
        failures += 1

    rules = sorted({rule for _, _, rule in expected})
    print("%d planted violations over %d rules in %d files checked; clean files pass: %s"
          % (len(expected), len(rules), len(planted), "no" if failures else "yes"))
    print("%d passed, %d failed" % (len(expected) + 1 - failures, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
