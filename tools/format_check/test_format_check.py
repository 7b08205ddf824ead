#!/usr/bin/env python3
"""Test of format_check.py: a mis-formatted file fails and is listed, a formatted one passes.

Works on temporary copies of testdata/ so nothing can reformat the planted file in place.
Exit 77 (skipped) when clang-format is missing.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CHECKER = os.path.join(HERE, 'format_check.py')


def run_checker(repo, clang_format, path):
    cmd = [sys.executable, CHECKER, '--repo', repo, path]
    if clang_format:
        cmd[2:2] = ['--clang-format', clang_format]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    return proc.returncode, proc.stdout.decode('utf-8', 'replace')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--repo', default=os.path.join(HERE, '..', '..'))
    parser.add_argument('--clang-format', default='')
    args = parser.parse_args()
    repo = os.path.abspath(args.repo)

    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        cases = [('misformatted.cpp', 1), ('formatted.cpp', 0)]
        for name, want_rc in cases:
            copy = os.path.join(tmp, name)
            shutil.copyfile(os.path.join(HERE, 'testdata', name), copy)
            rc, out = run_checker(repo, args.clang_format, copy)
            if rc == 77:
                print('SKIP: clang-format not found')
                return 77
            if rc != want_rc:
                failures.append('%s: exit %d, want %d\n%s' % (name, rc, want_rc, out))
            elif want_rc == 1 and copy not in out:
                failures.append('%s: rejected but not listed\n%s' % (name, out))
    if failures:
        print('FAIL\n' + '\n'.join(failures))
        return 1
    print('OK: mis-formatted file rejected and listed, formatted file accepted')
    return 0


if __name__ == '__main__':
    sys.exit(main())
