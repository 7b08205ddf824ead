#!/usr/bin/env python3
"""clang-tidy gate for the portable code: no finding in firmware/** and hal/** (not hal/fake).

Runs clang-tidy with the repository's .clang-tidy and --warnings-as-errors='*' on every
portable .cpp listed in the build's compile_commands.json (headers are checked through
them, per HeaderFilterRegex) and lists the files with findings. Exit 0: clean; 1: findings;
2: usage or tool error; 77: clang-tidy or compile_commands.json missing (ctest: skipped).
"""
import argparse
import concurrent.futures
import json
import os
import re
import shutil
import subprocess
import sys

SKIP_RC = 77
PORTABLE = re.compile(r'^(firmware|hal)/')
NOT_PORTABLE = re.compile(r'^hal/fake/')
PER_FILE_TIMEOUT_S = 300


def portable_sources(repo, build_dir):
    """Repository-relative portable .cpp files the build compiles, in a stable order."""
    with open(os.path.join(build_dir, 'compile_commands.json')) as f:
        entries = json.load(f)
    names = set()
    for entry in entries:
        path = os.path.normpath(os.path.join(entry.get('directory', ''), entry['file']))
        rel = os.path.relpath(path, repo).replace(os.sep, '/')
        if rel.endswith('.cpp') and PORTABLE.match(rel) and not NOT_PORTABLE.match(rel):
            names.add(rel)
    return sorted(names)


def tidy_one(tool, build_dir, repo, rel):
    """Returns (file, findings text or '', passed)."""
    cmd = [tool, '-p', build_dir, '--quiet', "--warnings-as-errors=*",
           os.path.join(repo, rel)]
    try:
        proc = subprocess.run(cmd, cwd=repo, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=PER_FILE_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return rel, 'clang-tidy timed out after %d s' % PER_FILE_TIMEOUT_S, False
    text = proc.stdout.decode('utf-8', 'replace')
    # Keep the diagnostics, drop clang-tidy's "N warnings generated." chatter.
    lines = [l for l in text.splitlines() if not re.match(r'^\d+ warnings? generated\.$', l)
             and not l.startswith('Suppressed ') and not l.startswith('Use -header-filter')]
    return rel, '\n'.join(lines).strip(), proc.returncode == 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--repo', default=os.path.join(os.path.dirname(__file__), '..', '..'))
    parser.add_argument('--build-dir', required=True, help='holds compile_commands.json')
    parser.add_argument('--clang-tidy', default='',
                        help='clang-tidy binary (default: clang-tidy-14, clang-tidy)')
    parser.add_argument('--jobs', type=int, default=2)
    args = parser.parse_args()

    repo = os.path.abspath(args.repo)
    build_dir = os.path.abspath(args.build_dir)
    tool = args.clang_tidy or shutil.which('clang-tidy-14') or shutil.which('clang-tidy')
    if not tool or not (os.path.isfile(tool) or shutil.which(tool)):
        print('SKIP: clang-tidy not found')
        return SKIP_RC
    if not os.path.isfile(os.path.join(build_dir, 'compile_commands.json')):
        print('SKIP: no compile_commands.json in %s (CMAKE_EXPORT_COMPILE_COMMANDS)' % build_dir)
        return SKIP_RC
    files = portable_sources(repo, build_dir)
    if not files:
        print('error: no portable sources in compile_commands.json', file=sys.stderr)
        return 2

    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for rel, text, passed in pool.map(lambda r: tidy_one(tool, build_dir, repo, r), files):
            if not passed:
                failed.append(rel)
                print('--- %s\n%s' % (rel, text))
    if failed:
        print('%d of %d portable files have clang-tidy findings:' % (len(failed), len(files)))
        for rel in failed:
            print('  ' + rel)
        return 1
    print('%d portable files clean under clang-tidy' % len(files))
    return 0


if __name__ == '__main__':
    sys.exit(main())
