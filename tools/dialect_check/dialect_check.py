#!/usr/bin/env python3
"""Checks that portable sources stay inside the C++ dialect XC16++ (GCC 4.5.1) accepts.

Every portable file (firmware/**, hal/** except hal/fake; .h .hpp .cpp .cc) is parsed by clang
as its own translation unit (a header through a one-line TU that includes it), for the AVR
target (16-bit int, 32-bit double, avr-libc's C headers) in -std=gnu++11 with no C++ library
headers, no exceptions and no RTTI. Two views report violations:

  * the compiler's view: clang's JSON AST (constexpr, nullptr, range-for, override/final,
    in-class member initialisers, alias declarations, delegating and inheriting constructors,
    ref-qualifiers, opaque enums, user-defined literals, heap, exceptions, RTTI, virtual
    destructors, namespace std) and clang's diagnostics (C++14/17 extensions, exit-time
    destructors, compile errors);
  * a token view of the file with comments and literals blanked (keywords wherever spelled,
    also inside macro bodies: constexpr, nullptr, noexcept, thread_local, alignas, alignof;
    [[attributes]]; std::; #include of anything but the allowed C headers).

Output: one line per violation, "path:line: error: [rule] message", sorted; exit status 0 when
clean, 1 on violations, 2 on a usage or tool problem.

Example:
  tools/dialect_check/dialect_check.py --repo .            # the whole portable tree
  tools/dialect_check/dialect_check.py firmware/core/isqrt.h
  tools/dialect_check/dialect_check.py --list-rules
"""

import argparse
import concurrent.futures
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Rule names and what they forbid (printed by --list-rules; quoted in every report line).
RULES = {
    "constexpr": "constexpr (GCC 4.6+)",
    "nullptr": "nullptr (GCC 4.6+): use 0",
    "range-for": "range-based for (GCC 4.6+)",
    "override-final": "override / final (GCC 4.7+)",
    "noexcept": "noexcept (GCC 4.6+)",
    "member-initializer": "in-class member initialiser (GCC 4.7+): initialise in the constructor",
    "alias-declaration": "`using X = ...` alias or alias template (GCC 4.7+): use typedef",
    "delegating-constructor": "delegating constructor (GCC 4.7+)",
    "inheriting-constructor": "inheriting constructor `using Base::Base` (GCC 4.8+)",
    "cxx11-attribute": "[[attribute]] syntax (GCC 4.8+): use __attribute__((...))",
    "thread-local": "thread_local (GCC 4.8+, and no threads on the target)",
    "alignas-alignof": "alignas / alignof (GCC 4.8+): use __attribute__((aligned)) / __alignof__",
    "user-defined-literal": "user-defined literal (GCC 4.7+)",
    "ref-qualifier": "ref-qualified member function (GCC 4.8.1+)",
    "opaque-enum": "opaque enum declaration / enum forward declaration (GCC 4.6+)",
    "std-header": "a header other than <stdint.h> <stddef.h> <limits.h> <string.h> "
                  "(XC16++ ships no C++ library)",
    "std-namespace": "anything from namespace std (there is no C++ library on the target)",
    "heap": "heap allocation (new/delete/malloc/free): use fixed storage and placement new",
    "exceptions": "exceptions (built with -fno-exceptions)",
    "rtti": "RTTI: typeid / dynamic_cast (built with -fno-rtti)",
    "virtual-destructor": "virtual destructor (needs operator delete): make it protected and "
                          "non-virtual",
    "global-destructor": "object with static storage and a non-trivial destructor (needs "
                         "__cxa_atexit)",
    "post-cxx11": "a C++14/17/20 feature (the target compiler is GCC 4.5, -std=gnu++0x)",
    "compile-error": "does not compile as gnu++11 for a 16-bit-int target",
}

ALLOWED_ANGLE_INCLUDES = {"stdint.h", "stddef.h", "limits.h", "string.h"}
SOURCE_EXTENSIONS = (".h", ".hpp", ".cpp", ".cc")
HEAP_FUNCTIONS = {"malloc", "calloc", "realloc", "free"}

# Keywords that are a violation wherever they are spelled (checked on tokens, so a macro
# body counts at its #define).
KEYWORD_RULES = {
    "constexpr": "constexpr",
    "nullptr": "nullptr",
    "noexcept": "noexcept",
    "thread_local": "thread-local",
    "alignas": "alignas-alignof",
    "alignof": "alignas-alignof",
}


class Finding:
    """One violation at a place in a file."""

    def __init__(self, path, line, rule, message):
        self.path = path
        self.line = line
        self.rule = rule
        self.message = message

    def key(self):
        return (self.path, self.line, self.rule)

    def __str__(self):
        return "%s:%d: error: [%s] %s" % (self.path, self.line, self.rule, self.message)


# ---------------------------------------------------------------------------------------------
# Token view: the file with comments, string and character literals blanked out.

def blank_comments_and_literals(text):
    """Returns text of equal length with comments and literals replaced by spaces (newlines
    kept, so offsets and line numbers stay valid). Include directives keep their "path"."""
    out = list(text)
    i, n = 0, len(text)

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank(i, j)
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not _ident_char(text[i - 1])):
            m = re.match(r'R"([^()\\ \n]{0,16})\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            end = n if end < 0 else end + len(m.group(1)) + 2
            blank(i + 1, end)
            i = end
        elif c in "\"'":
            # A digit separator (1'000) is C++14: clang reports it; do not treat as a literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and _in_number(text, i):
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            line_start = text.rfind("\n", 0, i) + 1
            is_include = re.match(r"\s*#\s*include\b", text[line_start:i]) is not None
            if not is_include:
                blank(i + 1, min(j, n))
            i = j + 1
        else:
            i += 1
    return "".join(out)


def _ident_char(c):
    return c.isalnum() or c == "_"


def _in_number(text, i):
    """True if the quote at i sits inside a numeric literal (a C++14 digit separator)."""
    j = i - 1
    while j >= 0 and (_ident_char(text[j]) or text[j] == "'"):
        j -= 1
    return text[j + 1].isdigit()


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def token_findings(path, display):
    """Violations visible in the token stream of one file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    clean = blank_comments_and_literals(text)
    found = []
    for word, rule in KEYWORD_RULES.items():
        for m in re.finditer(r"\b%s\b" % re.escape(word), clean):
            found.append(Finding(display, line_of(clean, m.start()), rule,
                                 "`%s`: %s" % (word, RULES[rule])))
    for m in re.finditer(r"\[\s*\[", clean):
        found.append(Finding(display, line_of(clean, m.start()), "cxx11-attribute",
                             RULES["cxx11-attribute"]))
    for m in re.finditer(r"(?<![\w:])std\s*::", clean):
        found.append(Finding(display, line_of(clean, m.start()), "std-namespace",
                             "`std::`: " + RULES["std-namespace"]))
    for m in re.finditer(r"^[ \t]*#[ \t]*include[ \t]*<([^>\n]*)>", clean, re.M):
        header = m.group(1).strip()
        if header not in ALLOWED_ANGLE_INCLUDES:
            found.append(Finding(display, line_of(clean, m.start()), "std-header",
                                 "<%s>: %s" % (header, RULES["std-header"])))
    return found


# ---------------------------------------------------------------------------------------------
# Compiler view: clang's JSON AST and diagnostics.

class LocationTracker:
    """Clang's JSON dump omits "file" and "line" when unchanged since the previous location
    it printed; walking the dump in print order and remembering them restores both."""

    def __init__(self):
        self.file = None
        self.line = None

    def see(self, loc):
        if "file" in loc:
            self.file = loc["file"]
        if "line" in loc:
            self.line = loc["line"]
        return (self.file, self.line)


class AstChecker:
    """Walks one TU's JSON AST in print order and records rule violations located in the
    files being checked."""

    def __init__(self, wanted, display_of):
        self.wanted = wanted          # real paths of the files whose violations we report
        self.display_of = display_of  # real path -> name printed in reports
        self.tracker = LocationTracker()
        self.found = []
        self.texts = {}

    def source(self, path):
        """The file with comments and literals blanked, one character per byte: clang's
        offsets count bytes, and Latin-1 maps every byte to one character, so a UTF-8 "µ"
        or "§" before a construct cannot shift the positions."""
        if path not in self.texts:
            with open(path, "rb") as f:
                raw = f.read()
            self.texts[path] = blank_comments_and_literals(raw.decode("latin-1"))
        return self.texts[path]

    def read_loc(self, loc, spelled=None):
        """Updates the tracker with a location object; returns (file, line, offset) of the
        place the construct is written (the expansion site for macros). If a list is given
        as spelled, appends where the tokens are spelled (inside the macro body for macros)."""
        if not isinstance(loc, dict):
            return None
        if "spellingLoc" in loc or "expansionLoc" in loc:
            result = None
            for key in ("spellingLoc", "expansionLoc"):
                if key in loc:
                    result = self.read_loc(loc[key])
                    if key == "spellingLoc" and spelled is not None:
                        spelled.append(result)
            return result
        if "offset" not in loc:
            return None
        f, line = self.tracker.see(loc)
        return (f, line, loc["offset"])

    def place(self, node):
        """Reads a node's own locations (loc, range) in print order; returns its best place."""
        here = None
        if "loc" in node:
            here = self.read_loc(node["loc"])
        begin = end = None
        spelled = []
        if "range" in node:
            begin = self.read_loc(node["range"].get("begin"), spelled)
            end = self.read_loc(node["range"].get("end"))
        node["_begin"], node["_end"] = begin, end
        node["_begin_spelled"] = spelled[0] if spelled and spelled[0] else begin
        return here or begin

    def report(self, where, rule, message=None):
        if not where or not where[0]:
            return
        real = os.path.realpath(where[0])
        if real in self.wanted:
            self.found.append(Finding(self.display_of[real], where[1], rule,
                                      message or RULES[rule]))

    def walk(self, node, records):
        """Visits a node and its "inner" children in print order; returns the first place
        found in the subtree (nodes without a location of their own take their child's)."""
        kind = node.get("kind")
        where = self.place(node)
        for key, value in node.items():
            if key not in ("loc", "range", "inner"):
                self.scan_plain(value)
        inner_records = records
        if kind == "CXXRecordDecl" and not node.get("isImplicit"):
            inner_records = records + [node.get("name", "")]
        for child in node.get("inner", []):
            if isinstance(child, dict):
                child_place = self.walk(child, inner_records)
                where = where or child_place
        if kind:
            self.check(node, kind, where, records)
        return where

    def scan_plain(self, value):
        """Keeps the tracker in step through attribute objects that are not child nodes."""
        if isinstance(value, dict):
            if "offset" in value:
                self.tracker.see(value)
                return
            for v in value.values():
                self.scan_plain(v)
        elif isinstance(value, list):
            for v in value:
                self.scan_plain(v)

    def check(self, node, kind, where, records):
        implicit = node.get("isImplicit", False)
        if kind in ("VarDecl", "FunctionDecl", "CXXMethodDecl", "CXXConstructorDecl",
                    "CXXConversionDecl", "CXXDestructorDecl"):
            if node.get("constexpr") and not implicit and not node.get("explicitlyDefaulted"):
                self.report(where, "constexpr")
        if kind == "IfStmt" and node.get("isConstexpr"):
            self.report(where, "constexpr", "if constexpr: " + RULES["constexpr"])
        elif kind == "CXXNullPtrLiteralExpr":
            self.report(where, "nullptr")
        elif kind == "CXXForRangeStmt":
            self.report(where, "range-for")
        elif kind in ("OverrideAttr", "FinalAttr"):
            self.report(where, "override-final")
        elif kind == "CXXNoexceptExpr":
            self.report(where, "noexcept", "noexcept operator: " + RULES["noexcept"])
        elif kind == "FieldDecl" and node.get("hasInClassInitializer"):
            self.report(where, "member-initializer")
        elif kind in ("TypeAliasDecl", "TypeAliasTemplateDecl") and not implicit:
            self.report(where, "alias-declaration")
        elif kind == "CXXCtorInitializer" and "delegatingInit" in node:
            self.report(where, "delegating-constructor")
        elif kind == "UsingDecl":
            name = node.get("name", "")
            parts = name.split("::")
            if len(parts) >= 2 and records and parts[-1] == records[-1]:
                self.report(where, "inheriting-constructor")
        elif kind in ("FunctionDecl", "CXXMethodDecl") and not implicit:
            name = node.get("name", "")
            if name.startswith('operator""') or name.startswith("operator \"\""):
                self.report(where, "user-defined-literal")
            qual = node.get("type", {}).get("qualType", "")
            if re.search(r"\)\s*(const\s*)?(volatile\s*)?&{1,2}\s*$", qual):
                self.report(where, "ref-qualifier")
        elif kind == "EnumDecl" and not implicit:
            # Opaque when the declaration reaches ';' before any '{' (read from the source,
            # since instantiated copies of an enum carry a collapsed range; from where the
            # tokens are spelled, so an enum written inside a macro body is read there).
            begin = node.get("_begin_spelled")
            if begin and begin[0]:
                text = self.source_or_none(begin[0])
                if text is not None:
                    brace = text.find("{", begin[2])
                    semicolon = text.find(";", begin[2])
                    if semicolon >= 0 and (brace < 0 or semicolon < brace):
                        self.report(where, "opaque-enum")
        elif kind == "CXXNewExpr" and not node.get("isPlacement"):
            self.report(where, "heap", "new without placement: " + RULES["heap"])
        elif kind == "CXXDeleteExpr":
            self.report(where, "heap", "delete: " + RULES["heap"])
        elif kind == "DeclRefExpr":
            ref = node.get("referencedDecl", {})
            if ref.get("kind") == "FunctionDecl" and ref.get("name") in HEAP_FUNCTIONS:
                self.report(where, "heap", "%s(): %s" % (ref.get("name"), RULES["heap"]))
        elif kind in ("CXXThrowExpr", "CXXTryStmt", "CXXCatchStmt"):
            self.report(where, "exceptions")
        elif kind in ("CXXTypeidExpr", "CXXDynamicCastExpr"):
            self.report(where, "rtti")
        elif kind == "NamespaceDecl" and node.get("name") == "std":
            self.report(where, "std-namespace", "namespace std: " + RULES["std-namespace"])
        if kind == "CXXDestructorDecl" and node.get("virtual") and not implicit:
            self.report(where, "virtual-destructor")

    def source_or_none(self, path):
        try:
            return self.source(path)
        except OSError:
            return None


# Clang diagnostics mapped to rules (first match wins); others are compile errors.
DIAGNOSTIC_RULES = [
    (re.compile(r"exit-time destructor"), "global-destructor"),
    (re.compile(r"exceptions disabled|-fexceptions"), "exceptions"),
    (re.compile(r"-frtti|RTTI"), "rtti"),
    (re.compile(r"thread-local"), "thread-local"),
    (re.compile(r"file not found"), "std-header"),
    (re.compile(r"C\+\+(1[4-9]|2[0-9]|2b)|c\+\+(1[4-9]|2[0-9]|2b)|deduced return types"),
     "post-cxx11"),
]

DIAG_LINE = re.compile(r"^(.*?):(\d+):\d+: (error|warning|fatal error): (.*)$")


def diagnostic_findings(stderr, wanted, display_of):
    """Errors (and the exit-time destructor warning) that clang printed for a wanted file."""
    found = []
    for raw in stderr.splitlines():
        m = DIAG_LINE.match(raw)
        if not m:
            continue
        path, line, severity, message = m.group(1), int(m.group(2)), m.group(3), m.group(4)
        real = os.path.realpath(path)
        if real not in wanted:
            continue
        rule = None
        for pattern, name in DIAGNOSTIC_RULES:
            if pattern.search(message):
                rule = name
                break
        if severity == "warning" and rule != "global-destructor":
            continue
        found.append(Finding(display_of[real], line, rule or "compile-error", message))
    return found


def clang_command(clang, repo, target, tu_path):
    flags = [clang, "-x", "c++", "-std=gnu++11", "-nostdinc++", "-fno-exceptions",
             "-fno-rtti", "-fsyntax-only", "-fno-color-diagnostics",
             "-fno-caret-diagnostics", "-fno-diagnostics-show-option",
             "-Wexit-time-destructors", "-Werror=c++14-extensions",
             "-Werror=c++17-extensions", "-Werror=c++20-extensions",
             "-Werror=c++2b-extensions", "-Wno-unknown-attributes", "-I", repo,
             "-Xclang", "-ast-dump=json"]
    if target == "avr":
        flags += ["--target=avr", "-mmcu=atmega2560"]
    return flags + [tu_path]


def check_tu(index, source, clang, repo, target, wanted, display_of, tmpdir):
    """Parses one file as its own TU; returns its findings (in any wanted file)."""
    if source.endswith((".h", ".hpp")):
        tu = os.path.join(tmpdir, "tu_%d.cpp" % index)
        with open(tu, "w") as f:
            f.write('#include "%s"\n' % source)
    else:
        tu = source
    # Decoded explicitly: clang echoes source bytes (any encoding) in its output, and the
    # locale's codec (ASCII under a bare ctest environment) must not decide whether we crash.
    proc = subprocess.run(clang_command(clang, repo, target, tu), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, encoding="utf-8", errors="replace")
    found = diagnostic_findings(proc.stderr, wanted, display_of)
    if proc.stdout.strip():
        try:
            ast = json.loads(proc.stdout)
        except ValueError as error:
            found.append(Finding(display_of[os.path.realpath(source)], 1, "compile-error",
                                 "clang AST dump unreadable: %s" % error))
            return found
        checker = AstChecker(wanted, display_of)
        checker.walk(ast, [])
        found += checker.found
    elif proc.returncode != 0 and not found:
        found.append(Finding(display_of[os.path.realpath(source)], 1, "compile-error",
                             proc.stderr.strip()[:300] or "clang failed"))
    return found


# ---------------------------------------------------------------------------------------------
# Which files, and the run.

def portable_files(repo):
    """firmware/** and hal/** except hal/fake."""
    files = []
    for top in ("firmware", "hal"):
        base = os.path.join(repo, top)
        for root, dirs, names in os.walk(base):
            rel = os.path.relpath(root, repo).replace(os.sep, "/")
            if rel == "hal/fake" or rel.startswith("hal/fake/"):
                dirs[:] = []
                continue
            dirs.sort()
            for name in sorted(names):
                if name.endswith(SOURCE_EXTENSIONS):
                    files.append(os.path.join(root, name))
    return files


def expand(paths):
    files = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, names in os.walk(p):
                dirs.sort()
                files += [os.path.join(root, n) for n in sorted(names)
                          if n.endswith(SOURCE_EXTENSIONS)]
        elif os.path.isfile(p):
            files.append(p)
        else:
            raise FileNotFoundError(p)
    return files


def find_clang(requested):
    for name in ([requested] if requested else ["clang++-14", "clang++"]):
        found = shutil.which(name)
        if found:
            return found
    return None


def main(argv):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog=__doc__[__doc__.index("Output:"):],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths", nargs="*",
                        help="files or folders to check (default: the portable tree)")
    parser.add_argument("--repo", default=".",
                        help="repository top: include root and default tree (default: .)")
    parser.add_argument("--clang", help="clang++ to use (default: clang++-14 or clang++)")
    parser.add_argument("--target", choices=["avr", "host"], default="avr",
                        help="parse for the 16-bit AVR target (default) or the host")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="clang processes in parallel")
    parser.add_argument("--list-rules", action="store_true", help="print the rules and exit")
    args = parser.parse_args(argv)

    if args.list_rules:
        for name, text in RULES.items():
            print("%-24s %s" % (name, text))
        return 0

    repo = os.path.realpath(args.repo)
    try:
        files = expand(args.paths) if args.paths else portable_files(repo)
    except FileNotFoundError as missing:
        print("dialect_check: no such file or folder: %s" % missing, file=sys.stderr)
        return 2
    clang = find_clang(args.clang)
    if not clang:
        print("dialect_check: clang++ not found (install clang-14)", file=sys.stderr)
        return 2

    display_of = {}
    for f in files:
        real = os.path.realpath(f)
        rel = os.path.relpath(real, repo)
        display_of[real] = rel if not rel.startswith("..") else f
    wanted = set(display_of)

    findings = []
    for f in files:
        findings += token_findings(f, display_of[os.path.realpath(f)])
    with tempfile.TemporaryDirectory(prefix="dialect_check_") as tmpdir:
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            jobs = [pool.submit(check_tu, i, os.path.realpath(f), clang, repo, args.target,
                                wanted, display_of, tmpdir) for i, f in enumerate(files)]
            for job in jobs:
                findings += job.result()

    unique = {}
    for finding in findings:
        unique.setdefault(finding.key(), finding)
    for key in sorted(unique):
        print(unique[key])
    print("dialect_check: %d files, %d violations" % (len(files), len(unique)),
          file=sys.stderr)
    return 1 if unique else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
