#!/usr/bin/env python3
"""Generates samples/engraver-word.dxf: the word ENGRAVER as single-stroke letters, each
letter one or two cubic B-splines (smooth pieces joined at corners by knots of
multiplicity 3), framed by a rounded rectangle (LWPOLYLINE with bulge arcs) with a CIRCLE
as the dot of an exclamation mark. Units: millimetres ($INSUNITS 4).

Usage: samples/make_engraver_word.py > samples/engraver-word.dxf
"""
import math

CELL_W, CELL_H, PITCH = 7.0, 10.0, 9.0   # letter box and advance, mm
ORIGIN = (8.0, 6.0)                      # lower-left of the first letter


def line(a, b):
    """A straight piece as a clamped cubic (4 collinear control points)."""
    return [a, ((2 * a[0] + b[0]) / 3, (2 * a[1] + b[1]) / 3),
            ((a[0] + 2 * b[0]) / 3, (a[1] + 2 * b[1]) / 3), b]


def join(*pieces):
    """Clamped cubic pieces (each starting where the last ended) as one B-spline: control
    points and knots, with a knot of multiplicity 3 at each joint (a corner)."""
    ctrl = list(pieces[0])
    knots = [0.0] * 4 + [float(i) for i in range(1, len(pieces[0]) - 3)]
    t = float(len(pieces[0]) - 3)
    for p in pieces[1:]:
        assert p[0] == ctrl[-1]
        knots += [t] * 3 + [t + i for i in range(1, len(p) - 3)]
        ctrl += p[1:]
        t += len(p) - 3
    knots += [t] * 4
    assert len(knots) == len(ctrl) + 4
    return ctrl, knots


# Letters in a 7 x 10 box; each entry is a list of splines.
def letter_E():
    return [join(line((7, 10), (0, 10)), line((0, 10), (0, 0)), line((0, 0), (7, 0))),
            join(line((0, 5), (5, 5)))]


def letter_N():
    return [join(line((0, 0), (0, 10)), line((0, 10), (7, 0)), line((7, 0), (7, 10)))]


def letter_G():
    arc = [(6.8, 8.6), (5.6, 10.3), (1.4, 10.3), (0, 8.0), (0, 2.0), (1.4, -0.3), (5.6, -0.3),
           (7, 1.5), (7, 4.5)]
    return [join(arc, line((7, 4.5), (3.8, 4.5)))]


def letter_R():
    bowl = [(0, 10), (4.6, 10), (7, 10), (7, 7.5), (7, 5.3), (4.6, 5.0), (0, 5.0)]
    return [join(line((0, 0), (0, 10)), bowl), join(line((3.5, 5.0), (7, 0)))]


def letter_A():
    return [join(line((0, 0), (3.5, 10)), line((3.5, 10), (7, 0))),
            join(line((1.4, 4.0), (5.6, 4.0)))]


def letter_V():
    return [join(line((0, 10), (3.5, 0)), line((3.5, 0), (7, 10)))]


WORD = [letter_E, letter_N, letter_G, letter_R, letter_A, letter_V, letter_E, letter_R]


class Dxf:
    def __init__(self):
        self.out = []
        self.handle = 0x100

    def g(self, code, value):
        self.out.append("%d\n%s\n" % (code, value))

    def entity(self, kind):
        self.g(0, kind)
        self.g(5, "%X" % self.handle)
        self.handle += 1
        self.g(100, "AcDbEntity")
        self.g(8, "ENGRAVE")

    def spline(self, ctrl, knots):
        self.entity("SPLINE")
        self.g(100, "AcDbSpline")
        self.g(210, "0.0"); self.g(220, "0.0"); self.g(230, "1.0")
        self.g(70, 8)  # planar
        self.g(71, 3)
        self.g(72, len(knots))
        self.g(73, len(ctrl))
        self.g(74, 0)
        for k in knots:
            self.g(40, "%.1f" % k)
        for x, y in ctrl:
            self.g(10, "%.4f" % x); self.g(20, "%.4f" % y); self.g(30, "0.0")

    def circle(self, c, r):
        self.entity("CIRCLE")
        self.g(100, "AcDbCircle")
        self.g(10, "%.4f" % c[0]); self.g(20, "%.4f" % c[1]); self.g(30, "0.0")
        self.g(40, "%.4f" % r)

    def lwpolyline(self, vertices, closed):
        self.entity("LWPOLYLINE")
        self.g(100, "AcDbPolyline")
        self.g(90, len(vertices))
        self.g(70, 1 if closed else 0)
        for x, y, bulge in vertices:
            self.g(10, "%.4f" % x); self.g(20, "%.4f" % y)
            if bulge:
                self.g(42, "%.10f" % bulge)


def main():
    d = Dxf()
    d.g(999, "engraver-word.dxf: sample drawing of the engraver project (samples/README.md)")
    d.g(0, "SECTION"); d.g(2, "HEADER")
    d.g(9, "$ACADVER"); d.g(1, "AC1015")
    d.g(9, "$INSUNITS"); d.g(70, 4)
    d.g(0, "ENDSEC")
    d.g(0, "SECTION"); d.g(2, "ENTITIES")
    ox, oy = ORIGIN
    for i, make in enumerate(WORD):
        for ctrl, knots in make():
            moved = [(ox + i * PITCH + x, oy + y) for x, y in ctrl]
            d.spline(moved, knots)
    # Exclamation mark: a stroke and a dot (exact circle).
    x_bang = ox + len(WORD) * PITCH + 1.0
    d.spline(*join(line((x_bang, oy + 10), (x_bang, oy + 3))))
    d.circle((x_bang, oy + 0.6), 0.6)
    # Frame: rounded rectangle, corner radius 3 mm (bulge tan(90deg / 4)).
    w, h, r = x_bang + 6.0, oy + CELL_H + 6.0, 3.0
    b = math.tan(math.pi / 8)
    d.lwpolyline([(r, 0, 0), (w - r, 0, b), (w, r, 0), (w, h - r, b), (w - r, h, 0),
                  (r, h, b), (0, h - r, 0), (0, r, b)], True)
    d.g(0, "ENDSEC")
    d.g(0, "EOF")
    print("".join(d.out), end="")


if __name__ == "__main__":
    main()
