#!/usr/bin/env python3
"""Writes a large synthetic copper layer (about 0.7 MB, KiCad-like 4.6 mm format) for
measuring the Gerber reader: a 160 x 120 mm board with a grid of 2 000 SMD pads and 1 000
through-hole pads, 12 000 track segments at 45/90 degrees between them, 40 filled zones
(regions with arc corners) and clearances cut into one zone with clear polarity.
Usage: make_large_gerber.py OUT.gbr  (deterministic: the same file every time)"""
import random
import sys

rnd = random.Random(11)
out = []
w = out.append
w("%TF.FileFunction,Copper,L1,Top*%")
w("%FSLAX46Y46*%")
w("%MOMM*%")
w("%LPD*%")
w("%ADD10C,0.250000*%")
w("%ADD11C,0.400000*%")
w("%ADD12R,1.200000X0.600000*%")
w("%ADD13C,1.700000*%")
w("%ADD14O,1.700000X2.400000*%")
w("%ADD15C,0.800000*%")
w("G75*")


def nm(mm):
    return int(round(mm * 1e6))


def xy(x, y):
    return "X%dY%d" % (nm(x), nm(y))


# Zones first (regions with rounded corners), then clearances in the first one.
for k in range(40):
    x0 = 5 + (k % 8) * 19.5
    y0 = 5 + (k // 8) * 23
    x1, y1, r = x0 + 15, y0 + 18, 1.0
    w("G36*")
    w(xy(x0 + r, y0) + "D02*")
    w("G01*")
    w(xy(x1 - r, y0) + "D01*")
    w("G03*")
    w(xy(x1, y0 + r) + "I0J%dD01*" % nm(r))
    w("G01*")
    w(xy(x1, y1 - r) + "D01*")
    w("G03*")
    w(xy(x1 - r, y1) + "I%dJ0D01*" % nm(-r))
    w("G01*")
    w(xy(x0 + r, y1) + "D01*")
    w("G03*")
    w(xy(x0, y1 - r) + "I0J%dD01*" % nm(-r))
    w("G01*")
    w(xy(x0, y0 + r) + "D01*")
    w("G03*")
    w(xy(x0 + r, y0) + "I%dJ0D01*" % nm(r))
    w("G01*")
    w("G37*")
w("%LPC*%")
w("D13*")
for k in range(30):
    w(xy(8 + (k % 6) * 2.2, 8 + (k // 6) * 2.8) + "D03*")
w("%LPD*%")
# Pads.
w("D12*")
for k in range(2000):
    w(xy(3 + (k % 80) * 1.95, 3 + (k // 80) * 4.6) + "D03*")
w("D14*")
for k in range(1000):
    w(xy(4 + (k % 50) * 3.1, 4.5 + (k // 50) * 5.7) + "D03*")
# Tracks: random walks of 45/90 degree segments.
x, y = 80.0, 60.0
segments = 0
while segments < 12000:
    w("D%d*" % (10 if rnd.random() < 0.8 else 11))
    x, y = 3 + rnd.random() * 154, 3 + rnd.random() * 114
    w(xy(x, y) + "D02*")
    for _ in range(rnd.randint(3, 12)):
        d = rnd.choice([(1, 0), (0, 1), (-1, 0), (0, -1), (0.7071, 0.7071), (-0.7071, 0.7071),
                        (0.7071, -0.7071), (-0.7071, -0.7071)])
        step = rnd.uniform(0.5, 6)
        x = min(157, max(3, x + d[0] * step))
        y = min(117, max(3, y + d[1] * step))
        w(xy(x, y) + "D01*")
        segments += 1
w("D15*")
for k in range(800):
    w(xy(3 + rnd.random() * 154, 3 + rnd.random() * 114) + "D03*")
w("M02*")
open(sys.argv[1], "w").write("\n".join(out) + "\n")
