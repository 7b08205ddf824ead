#!/usr/bin/env python3
"""Fails when the firmware image passes its flash or static-RAM budget.

The image is `firmware_link_check.elf` (hal/dspic30f6014/main.cpp and every library, linked
for the AVR proxy with --gc-sections). No XC16 here, so its flash is a stand-in:
  flash bytes  = .text + .data (avr-size; .data's initial values are in flash too)
  dsPIC words  = flash bytes * 0.346 (XC16 -O2 gave 29.5 k instruction words where this
                 measure gave 85 236 B, and 23.2 k where it gave 68 590 B: 0.346 / 0.338)
  static RAM   = .bss (.data holds const tables, which XC16 keeps in flash)
The budgets and the measure are written in docs/performance.md (*Flash and RAM budget*).
"""
import argparse
import re
import subprocess
import sys

WORDS_PER_AVR_BYTE = 0.346


def sections(size_tool, elf):
    out = subprocess.run([size_tool, "-A", elf], check=True, capture_output=True,
                         text=True).stdout
    found = {}
    for line in out.splitlines():
        m = re.match(r"^(\.\S+)\s+(\d+)\s+\d+", line)
        if m:
            found[m.group(1)] = int(m.group(2))
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", default="avr-size")
    ap.add_argument("--elf", required=True)
    ap.add_argument("--max-flash-words", type=int, required=True)
    ap.add_argument("--max-bss-bytes", type=int, required=True)
    args = ap.parse_args()
    s = sections(args.size, args.elf)
    flash_bytes = s.get(".text", 0) + s.get(".data", 0)
    words = int(round(flash_bytes * WORDS_PER_AVR_BYTE))
    bss = s.get(".bss", 0)
    print("flash %d B (.text %d + .data %d) = ~%d dsPIC words, budget %d words (%.1f %%)" %
          (flash_bytes, s.get(".text", 0), s.get(".data", 0), words, args.max_flash_words,
           100.0 * words / args.max_flash_words))
    print("static RAM .bss %d B, budget %d B" % (bss, args.max_bss_bytes))
    failed = False
    if words > args.max_flash_words:
        print("FAIL flash: ~%d words over the budget of %d" % (words, args.max_flash_words))
        failed = True
    if bss > args.max_bss_bytes:
        print("FAIL static RAM: %d B over the budget of %d B" % (bss, args.max_bss_bytes))
        failed = True
    if not failed:
        print("ok: the image is within its budget")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
