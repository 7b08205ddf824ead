#!/usr/bin/env python3
"""Fails when a hot path of the firmware reaches a wide-arithmetic library helper.

Reads `avr-objdump -d -C` of an AVR ELF, builds the static call graph (call, rcall and
the tail jumps jmp/rjmp that leave a function) from each root function, and reports every
path to a forbidden helper. Indirect calls (icall/eicall/ijmp/eijmp) cannot be followed:
one reachable from a root is a failure too, so a virtual call cannot hide a helper.

avr-gcc 5.4 / libgcc names and what XC16 (the dsPIC's GCC 4.5 port) calls the same thing
(XC16 prefixes C symbols with one more underscore):
  64-bit  multiply   __muldi3 (+ __muldi3_6, __mulsidi3, __umulsidi3)  ->  ___muldi3
          divide     __divdi3, __udivdi3 (+ __udivmod64, __divdi3_moddi3)  ->  ___divdi3, ___udivdi3
          remainder  __moddi3, __umoddi3 (+ __udivdi3_umoddi3)        ->  ___moddi3, ___umoddi3
          shifts     __ashldi3, __ashrdi3, __lshrdi3                  ->  ___ashldi3, ___ashrdi3, ___lshrdi3
          other      __negdi2, __adddi3(_s8), __subdi3, __cmpdi2(_s8) ->  inline on the dsPIC (ADD/ADDC,
                     CP/CPB chains), ___cmpdi2 / ___ucmpdi2 where not inlined
  32-bit  divide     __udivmodsi4, __divmodsi4                         ->  ___udivsi3, ___divsi3,
                                                                           ___umodsi3, ___modsi3
avr-gcc inlines 64-bit additions and comparisons in registers on most paths, so the absence
of helpers proves no 64-bit multiply, divide or shift; the sources' static_asserts and
comments bound the rest.
"""
import argparse
import bisect
import re
import subprocess
import sys

HELPERS_64 = {
    "__muldi3", "__muldi3_6", "__mulsidi3", "__umulsidi3", "__umulsidi3_helper",
    "__divdi3", "__udivdi3", "__moddi3", "__umoddi3", "__udivmod64", "__divdi3_moddi3",
    "__udivdi3_umoddi3", "__negdi2", "__ashldi3", "__ashrdi3", "__lshrdi3", "__adddi3",
    "__adddi3_s8", "__subdi3", "__cmpdi2", "__cmpdi2_s8",
    # The same helpers as XC16 names them (for a dsPIC listing fed through the same check).
    "___muldi3", "___divdi3", "___udivdi3", "___moddi3", "___umoddi3", "___ashldi3",
    "___ashrdi3", "___lshrdi3", "___negdi2", "___cmpdi2", "___ucmpdi2",
}
HELPERS_DIV32 = {
    "__udivmodsi4", "__divmodsi4", "__udivmodsi4_loop", "__udivmodsi4_ep",
    "___udivsi3", "___divsi3", "___umodsi3", "___modsi3",
}

FUNC_RE = re.compile(r"^([0-9a-f]+) <(.+)>:$")
# "  aeb6:\t0e 94 06 3b \tcall\t0x760c\t; 0x760c <name>"
INSN_RE = re.compile(r"^\s*([0-9a-f]+):\t[^\t]*\t(\S+)(?:\t(.*))?$")
TARGET_RE = re.compile(r";\s*0x([0-9a-f]+)")
CALLS = {"call", "rcall", "jmp", "rjmp"}
INDIRECT = {"icall", "eicall", "ijmp", "eijmp"}


def read_listing(objdump, elf):
    """Returns (starts, names, edges, indirect): function start addresses (sorted), their
    demangled names, callee start addresses per function, functions with an indirect call."""
    text = subprocess.run([objdump, "-d", "-C", elf], check=True, capture_output=True,
                          text=True).stdout
    funcs = []  # (start, name, [(target address)...], has_indirect)
    for line in text.splitlines():
        m = FUNC_RE.match(line)
        if m:
            funcs.append([int(m.group(1), 16), m.group(2), [], False])
            continue
        m = INSN_RE.match(line)
        if not m or not funcs:
            continue
        op = m.group(2)
        if op in INDIRECT:
            funcs[-1][3] = True
        elif op in CALLS and m.group(3):
            t = TARGET_RE.search(m.group(3))
            if t:
                funcs[-1][2].append(int(t.group(1), 16))
    funcs.sort(key=lambda f: f[0])
    starts = [f[0] for f in funcs]
    names = [f[1] for f in funcs]
    edges = []
    indirect = []
    for i, f in enumerate(funcs):
        callees = set()
        for addr in f[2]:
            j = bisect.bisect_right(starts, addr) - 1
            if j >= 0 and j != i:  # a jump inside the function is a branch, not an edge
                callees.add(j)
        edges.append(sorted(callees))
        indirect.append(f[3])
    return starts, names, edges, indirect


def bare(name):
    """Helper names without demangling noise: "__muldi3" stays, "f(int) const" -> "f"."""
    return name.split("(")[0].strip()


def check_root(root, names, edges, indirect, forbidden):
    """Returns the list of problems reachable from functions whose name starts with root."""
    roots = [i for i, n in enumerate(names) if n.startswith(root)]
    if not roots:
        return ["root not found in the listing: " + root]
    problems = []
    parent = {r: None for r in roots}
    queue = list(roots)
    while queue:
        i = queue.pop(0)
        path = []
        k = i
        while k is not None:
            path.append(names[k])
            k = parent[k]
        chain = " <- ".join(path)
        if bare(names[i]) in forbidden:
            problems.append("reaches " + bare(names[i]) + ": " + chain)
            continue
        if indirect[i]:
            problems.append("indirect call (not followed) in: " + chain)
        for j in edges[i]:
            if j not in parent:
                parent[j] = i
                queue.append(j)
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--objdump", default="avr-objdump")
    ap.add_argument("--elf", required=True)
    ap.add_argument("--root", action="append", required=True,
                    help="demangled name prefix of a hot function, e.g. "
                         "'core::SpanEvaluator::evaluate_q6('")
    ap.add_argument("--no-div32", action="store_true",
                    help="also forbid the 32/32-bit division helpers")
    args = ap.parse_args()
    forbidden = set(HELPERS_64)
    if args.no_div32:
        forbidden |= HELPERS_DIV32
    _, names, edges, indirect = read_listing(args.objdump, args.elf)
    failed = False
    for root in args.root:
        problems = check_root(root, names, edges, indirect, forbidden)
        for p in problems:
            print("FAIL %s: %s" % (root, p))
        if problems:
            failed = True
        else:
            print("ok %s: no %s helper reachable" %
                  (root, "64-bit or 32-bit division" if args.no_div32 else "64-bit"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
