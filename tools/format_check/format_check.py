#!/usr/bin/env python3
"""Formatting gate: every C/C++ source and header must be unchanged by clang-format.

Runs `clang-format --dry-run --Werror` with the repository's .clang-format over the files git
knows about (tracked, plus untracked ones that are not ignored) and lists each file that
would change. Exit 0: all formatted; 1: some files need `clang-format -i`; 2: usage or tool
error; 77: clang-format not found (ctest reports the test as skipped).

Left out on purpose (their bytes are test data): tools/dialect_check/testdata/**,
tools/format_check/testdata/**, host_tests/**/data/**, any golden/ folder.
"""
import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys

SKIP_RC = 77
SOURCE_SUFFIXES = ('.h', '.hpp', '.c', '.cpp')
# Paths (from the repository top, '/'-separated) whose bytes must stay as they are.
EXCLUDED = [
    re.compile(r'^tools/dialect_check/testdata/'),
    re.compile(r'^tools/format_check/testdata/'),
    re.compile(r'^host_tests/(.*/)?data/'),
    re.compile(r'(^|/)golden/'),
]
# clang-format's dry-run diagnostic: "path:line:col: error: code should be clang-formatted"
DIAGNOSTIC = re.compile(r'^(.*?):\d+:\d+: (?:error|warning): code should be clang-formatted')
BUILD_DIRS = ('build', 'out', '.git', '.cache')


def is_excluded(rel_path):
    return any(pattern.search(rel_path) for pattern in EXCLUDED)


def git_files(repo):
    """Source files git knows about, or None if this is not a git checkout."""
    try:
        out = subprocess.run(
            ['git', '-C', repo, 'ls-files', '--cached', '--others', '--exclude-standard', '-z'],
            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    names = [n for n in out.decode('utf-8', 'replace').split('\0') if n]
    return sorted(set(names))


def walked_files(repo):
    """Fallback for a source tree without .git: every file below the top except build dirs."""
    names = []
    for root, dirs, files in os.walk(repo):
        rel_root = os.path.relpath(root, repo)
        if rel_root == '.':
            dirs[:] = [d for d in dirs if d not in BUILD_DIRS]
        for name in files:
            names.append(os.path.normpath(os.path.join(rel_root, name)).replace(os.sep, '/'))
    return sorted(names)


def repo_sources(repo):
    names = git_files(repo)
    if names is None:
        names = walked_files(repo)
    return [n for n in names
            if n.endswith(SOURCE_SUFFIXES) and not is_excluded(n)
            and os.path.isfile(os.path.join(repo, n))]


def check_chunk(clang_format, style_file, cwd, files):
    """Returns (offending files, tool error text or '')."""
    proc = subprocess.run(
        [clang_format, '--style=file:' + style_file, '--dry-run', '--Werror'] + files,
        cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    text = proc.stderr.decode('utf-8', 'replace')
    bad = set()
    for line in text.splitlines():
        match = DIAGNOSTIC.match(line)
        if match:
            bad.add(match.group(1))
    if proc.returncode != 0 and not bad:
        return bad, text.strip() or 'clang-format exited with %d' % proc.returncode
    return bad, ''


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--repo', default=os.path.join(os.path.dirname(__file__), '..', '..'),
                        help='repository top (holds .clang-format)')
    parser.add_argument('--clang-format', default='',
                        help='clang-format binary (default: clang-format-14, clang-format)')
    parser.add_argument('--jobs', type=int, default=2)
    parser.add_argument('files', nargs='*',
                        help='check these files instead of the whole repository')
    args = parser.parse_args()

    repo = os.path.abspath(args.repo)
    tool = args.clang_format or shutil.which('clang-format-14') or shutil.which('clang-format')
    if not tool or not (os.path.isfile(tool) or shutil.which(tool)):
        print('SKIP: clang-format not found')
        return SKIP_RC
    style_file = os.path.join(repo, '.clang-format')
    if not os.path.isfile(style_file):
        print('error: no .clang-format at %s' % repo, file=sys.stderr)
        return 2

    if args.files:
        cwd, files = os.getcwd(), args.files
    else:
        cwd, files = repo, repo_sources(repo)
    if not files:
        print('error: no files to check', file=sys.stderr)
        return 2

    jobs = max(1, args.jobs)
    chunks = [files[i::jobs] for i in range(jobs) if files[i::jobs]]
    bad, errors = set(), []
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(chunks)) as pool:
        for chunk_bad, error in pool.map(
                lambda chunk: check_chunk(tool, style_file, cwd, chunk), chunks):
            bad |= chunk_bad
            if error:
                errors.append(error)
    if errors:
        print('error: clang-format failed:\n' + '\n'.join(errors), file=sys.stderr)
        return 2
    if bad:
        print('%d of %d files are not clang-formatted (fix: clang-format -i FILE):'
              % (len(bad), len(files)))
        for name in sorted(bad):
            print('  ' + name)
        return 1
    print('%d files clang-formatted' % len(files))
    return 0


if __name__ == '__main__':
    sys.exit(main())
