#!/usr/bin/env python3
"""Writes large test drawings for the big-job measurements (docs/performance.md) and the
soak test: nothing big is committed, the files are made when needed.

Kinds (N = number of segments):
  contour N   one closed chained contour of N LINE entities: a circle of radius R about
              the work area's middle with a gentle radial wave, so consecutive segments
              chain into one curve (as a PCB outline or a traced bitmap does)
  lines N     N separate random LINE entities (short, scattered): N pen lifts
  circle N    the exact ring of ../shared/samples/large (radius 70 about (120, 90))
  gcode N     the contour as G-code G1 moves (mm, absolute)

Output: DXF R12 ENTITIES section only (what dxflib needs), millimetres, streamed (a million
segments never sit in memory). Deterministic for a given --seed.

Usage: tools/bigjob/make_job.py contour 10000 > /tmp/c10k.dxf
       tools/bigjob/make_job.py lines 100000 --seed 3 -o /tmp/l100k.dxf
"""
import argparse
import math
import random
import sys


def ring(n, cx, cy, r, wave_mm, waves, phase):
    for i in range(n):
        a = 2 * math.pi * i / n
        rr = r + wave_mm * math.sin(waves * a + phase)
        yield cx + rr * math.cos(a), cy + rr * math.sin(a)


def write_dxf_lines(out, segments):
    out.write("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n")
    out.write("0\nSECTION\n2\nENTITIES\n")
    for (x0, y0), (x1, y1) in segments:
        out.write("0\nLINE\n8\n0\n10\n%.4f\n20\n%.4f\n30\n0.0\n11\n%.4f\n21\n%.4f\n31\n0.0\n"
                  % (x0, y0, x1, y1))
    out.write("0\nENDSEC\n0\nEOF\n")


def closed(points):
    first = prev = None
    for p in points:
        if prev is None:
            first = p
        else:
            yield prev, p
        prev = p
    if prev is not None and first is not prev:
        yield prev, first


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("kind", choices=["contour", "lines", "circle", "gcode"])
    ap.add_argument("n", type=int, help="number of segments")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("-o", "--output", help="file to write (default stdout)")
    a = ap.parse_args()
    if a.n < 3:
        ap.error("n must be at least 3")
    rnd = random.Random(a.seed)
    out = open(a.output, "w") if a.output else sys.stdout
    if a.kind == "circle":
        write_dxf_lines(out, closed(ring(a.n, 120.0, 90.0, 70.0, 0.0, 0, 0.0)))
    elif a.kind in ("contour", "gcode"):
        r = rnd.uniform(40.0, 90.0)
        pts = ring(a.n, 148.0, 105.0, r, rnd.uniform(0.5, 3.0), rnd.randint(3, 40),
                   rnd.uniform(0, math.pi))
        if a.kind == "contour":
            write_dxf_lines(out, closed(pts))
        else:
            out.write("G21\nG90\nG0 Z2\n")
            first = None
            for x, y in pts:
                if first is None:
                    first = (x, y)
                    out.write("G0 X%.4f Y%.4f\nG1 Z-0.1 F600\n" % (x, y))
                else:
                    out.write("G1 X%.4f Y%.4f\n" % (x, y))
            out.write("G1 X%.4f Y%.4f\nG0 Z2\nM2\n" % first)
    else:
        def scatter():
            for _ in range(a.n):
                x, y = rnd.uniform(5, 290), rnd.uniform(5, 200)
                ang = rnd.uniform(0, 2 * math.pi)
                ln = rnd.uniform(0.5, 5.0)
                yield (x, y), (x + ln * math.cos(ang), y + ln * math.sin(ang))
        write_dxf_lines(out, scatter())
    if a.output:
        out.close()


if __name__ == "__main__":
    main()
