#!/usr/bin/env python3
"""Generates samples/engraver-word.dxf: the word "engraver" as outlined lettering on a name
plate.

Each letter is a monoline skeleton of a geometric lowercase (straight strokes, slightly
waisted, and circular arcs). The script traces the outline a round pen of the stroke width
leaves along it (round ends, round outer corners, inner corners rounded to FILLET), one
closed outline per face of the skeleton (the outside and each counter), and fits a closed
cubic B-spline to every outline: least squares with parameter correction, spans split
until the fit is within FIT_TOL of the traced outline, then every knot the fit can do
without removed. Each spline is written clamped (end knots of multiplicity 4, simple
interior knots, first control point = last), C2-smooth all round, the seam too. The plate
is a rounded rectangle (LWPOLYLINE with bulge arcs) with a mounting hole (CIRCLE) in each
corner. Units: millimetres ($INSUNITS 4).

Python 3 standard library only; deterministic: the output is the same byte for byte on
every run.

Usage: samples/make_engraver_word.py > samples/engraver-word.dxf
"""
import math

SCALE = 1.2            # design units (x-height 10) -> mm
STROKE = 1.6           # stroke width, design units
GAP = 1.9              # space between letters, design units
FILLET = 0.5           # radius that rounds the inner corners, design units
SMOOTH = 0.02          # sine of the largest turn between strokes taken as smooth
WAIST = 0.15           # straight strokes are this much narrower in the middle
FIT_TOL = 0.04         # largest distance of a fitted outline from the traced one, mm
SAMPLE_MM = 0.1        # spacing of the traced outline points the fit uses, mm
SPAN0_MM = 6.0         # first knots: a span per this length...
SPAN0_DEG = 60.0       # ... and per this much turning
MAX_CONTROL = 64       # control points per SPLINE entity
BASELINE = 11.0        # of the word on the plate (centred across it), mm
PLATE_W, PLATE_H = 124.0, 30.0  # plate size, mm

# ---------------------------------------------------------------- letter skeletons
# A skeleton is a list of strokes; a stroke is a polyline of (x, y, pen radius) points in
# design units whose end points are the graph's vertices; strokes meet only at their ends.
# Each letter function returns its strokes and its advance width.


def stem(a, b, *cuts):
    """A straight stroke from a to b, waisted (narrower in the middle by WAIST), as pieces
    split at the given points on it (where other strokes join). Points carry the local
    pen radius: (x, y, r)."""
    length = math.hypot(b[0] - a[0], b[1] - a[1])
    marks = [0.0] + sorted(math.hypot(c[0] - a[0], c[1] - a[1]) / length for c in cuts) + [1.0]
    pieces = []
    for t0, t1 in zip(marks, marks[1:]):
        n = max(2, int(math.ceil((t1 - t0) * length / 0.25)))
        piece = []
        for i in range(n + 1):
            t = t0 + (t1 - t0) * i / n
            r = STROKE / 2 * (1 - WAIST * math.sin(math.pi * t))
            piece.append((a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, r))
        pieces.append(piece)
    return pieces


def arc(c, r, deg0, deg1, step=2.0):
    """Circular arc from deg0 to deg1 (either direction), sampled every ~step degrees."""
    n = max(2, int(math.ceil(abs(deg1 - deg0) / step)))
    return [[(c[0] + r * math.cos(math.radians(deg0 + (deg1 - deg0) * i / n)),
              c[1] + r * math.sin(math.radians(deg0 + (deg1 - deg0) * i / n)), STROKE / 2)
             for i in range(n + 1)]]


H = 10.0 - STROKE / 2  # skeleton top (x-height 10 at the outline)
B = STROKE / 2         # skeleton baseline
BOWL_R = (10.0 - STROKE) / 2
BOWL_C = 5.0


def on_circle(c, r, deg):
    return (c[0] + r * math.cos(math.radians(deg)), c[1] + r * math.sin(math.radians(deg)))


def letter_e():
    c = (BOWL_C, BOWL_C)
    a, b = on_circle(c, BOWL_R, 0), on_circle(c, BOWL_R, 180)
    return stem(b, a) + arc(c, BOWL_R, 0, 180) + arc(c, BOWL_R, 180, 325), 10.0


ARCH_C, ARCH_R = (3.8, H - 4.0), 4.0  # the arch of n and r
ARCH_J = 180 - math.degrees(math.acos((ARCH_C[0] - B) / ARCH_R))  # where it meets the stem


def letter_n():
    j = on_circle(ARCH_C, ARCH_R, ARCH_J)
    leg = (ARCH_C[0] + ARCH_R, ARCH_C[1])
    return (stem((B, B), (B, H), j) + arc(ARCH_C, ARCH_R, ARCH_J, 0) +
            stem(leg, (leg[0], B)), leg[0] + B)


def letter_r():
    j = on_circle(ARCH_C, ARCH_R, ARCH_J)
    end = on_circle(ARCH_C, ARCH_R, 62)
    return stem((B, B), (B, H), j) + arc(ARCH_C, ARCH_R, ARCH_J, 62), end[0] + B


BOWL_J = 38.0                                            # where the bowl meets the stem
STEM_X = BOWL_C + BOWL_R * math.cos(math.radians(BOWL_J))


def bowl(bottom):
    """The bowl of a and g: a circle cut by the stem, which runs from the x-height down to
    y = bottom."""
    c = (BOWL_C, BOWL_C)
    j1, j2 = on_circle(c, BOWL_R, BOWL_J), on_circle(c, BOWL_R, -BOWL_J)
    return stem((STEM_X, H), (STEM_X, bottom), j1, j2) + arc(c, BOWL_R, BOWL_J, 360 - BOWL_J)


def letter_a():
    return bowl(B), STEM_X + B


def letter_g():
    hook_r, hook_y = 3.4, 0.0
    hook_c = (STEM_X - hook_r, hook_y)
    return bowl(hook_y) + arc(hook_c, hook_r, 0, -150), STEM_X + B


def letter_v():
    return stem((B, H), (4.6, B)) + stem((4.6, B), (9.2 - B, H)), 9.2


WORD = [letter_e, letter_n, letter_g, letter_r, letter_a, letter_v, letter_e, letter_r]

# ---------------------------------------------------------------- stroke outlines


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def mul(a, s):
    return (a[0] * s, a[1] * s)


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def unit(a):
    n = math.sqrt(a[0] * a[0] + a[1] * a[1])
    return (a[0] / n, a[1] / n)


def right_normal(d):
    return (d[1], -d[0])


def key(p):
    return (round(p[0], 6), round(p[1], 6))


def offset_right(pts):
    """The polyline of (x, y, r) points offset by r to its right (mitred at inner points;
    at the ends the normal is extrapolated, exact for sampled arcs)."""
    normals = [right_normal(unit(sub(b, a))) for a, b in zip(pts, pts[1:])]
    out = []
    for i, p in enumerate(pts):
        if i == 0 or i == len(pts) - 1:
            n0, n1 = (normals[0], normals[1]) if i == 0 else (normals[-1], normals[-2])
            if len(normals) > 1:
                n0 = unit(sub(mul(n0, 1.5), mul(n1, 0.5)))
            out.append(add(p, mul(n0, p[2])))
        else:
            n1, n2 = normals[i - 1], normals[i]
            m = unit(add(n1, n2))
            out.append(add(p, mul(m, p[2] / (m[0] * n1[0] + m[1] * n1[1]))))
    return out


def seg_intersection(p, p2, q, q2):
    """Parameter s along p-p2 where segments p-p2 and q-q2 cross, or None."""
    d, e = sub(p2, p), sub(q2, q)
    den = cross(d, e)
    if abs(den) < 1e-15:
        return None
    w = sub(q, p)
    s, t = cross(w, e) / den, cross(w, d) / den
    if 0 <= s <= 1 and 0 <= t <= 1:
        return s
    return None


def round_join(v, a, b):
    """Arc around v, counter-clockwise, from point a to point b."""
    t0 = math.atan2(a[1] - v[1], a[0] - v[0])
    t1 = math.atan2(b[1] - v[1], b[0] - v[0])
    r0, r1 = math.hypot(a[0] - v[0], a[1] - v[1]), math.hypot(b[0] - v[0], b[1] - v[1])
    while t1 <= t0:
        t1 += 2 * math.pi
    n = max(1, int(math.ceil((t1 - t0) / math.radians(3))))
    out = []
    for i in range(1, n):
        f = i / n
        r = r0 + (r1 - r0) * f
        out.append((v[0] + r * math.cos(t0 + (t1 - t0) * f), v[1] + r * math.sin(t0 + (t1 - t0) * f)))
    return out


def walk(c, i, dist, step):
    """From point i of polyline c, the index and point dist further along (step +-1)."""
    p = c[i]
    while True:
        q = c[i + step]
        d = math.hypot(q[0] - p[0], q[1] - p[1])
        if d >= dist:
            return i, (p[0] + (q[0] - p[0]) * dist / d, p[1] + (q[1] - p[1]) * dist / d)
        dist -= d
        i += step
        p = q


def cut_concave(c, m, window=80):
    """c has a concave join after point m: cuts the small loop the two sides make there and
    rounds the corner with a fillet of radius FILLET (a quadratic Bezier, tangent to both)."""
    window = min(window, len(c) // 2 - 2)
    for i in range(m, m - window, -1):
        for j in range(max(m, i + 1), m + window):
            s = seg_intersection(c[i - 1], c[i], c[j], c[j + 1])
            if s is None:
                continue
            x = add(c[i - 1], mul(sub(c[i], c[i - 1]), s))
            d_in, d_out = unit(sub(c[i], c[i - 1])), unit(sub(c[j + 1], c[j]))
            turn = math.acos(max(-1.0, min(1.0, d_in[0] * d_out[0] + d_in[1] * d_out[1])))
            c = c[:i] + [x] + c[j + 1:]
            L = min(FILLET * math.tan(turn / 2), 1.2)
            ia, pa = walk(c, i, L, -1)
            ib, pb = walk(c, i, L, +1)
            n = 12
            bez = [add(add(mul(pa, (1 - u) ** 2), mul(x, 2 * u * (1 - u))), mul(pb, u * u))
                   for u in (k / n for k in range(n + 1))]
            return c[:ia] + bez + c[ib + 1:]
    raise ValueError("concave join without a crossing")


def outlines(strokes):
    """The closed outlines of the strokes drawn with a round pen (radius: each point's r):
    one per face of
    the skeleton graph (the outer one counter-clockwise, the counters clockwise)."""
    halves = []  # each stroke both ways: half-edge h and its reverse h ^ 1
    for s in strokes:
        halves.append(s)
        halves.append(list(reversed(s)))
    leaving = {}
    for h, pts in enumerate(halves):
        leaving.setdefault(key(pts[0]), []).append(h)

    def angle(h):
        d = sub(halves[h][1], halves[h][0])
        return math.atan2(d[1], d[0])

    def next_half(h):
        """The half-edge that follows h around its face: the first one counter-clockwise
        from the way back."""
        back = h ^ 1
        a0 = angle(back)
        best, best_delta = back, 2 * math.pi
        for g in leaving[key(halves[h][-1])]:
            if g == back:
                continue
            delta = (angle(g) - a0) % (2 * math.pi)
            if 0 < delta < best_delta:
                best, best_delta = g, delta
        return best

    used, result = set(), []
    for h0 in range(len(halves)):
        if h0 in used:
            continue
        cycle, h = [], h0
        while h not in used:
            used.add(h)
            cycle.append(h)
            h = next_half(h)
        pieces = [offset_right(halves[h]) for h in cycle]
        contour, concave = [], []
        for i, h in enumerate(cycle):
            nxt = cycle[(i + 1) % len(cycle)]
            contour += pieces[i]
            d_in = unit(sub(halves[h][-1], halves[h][-2]))
            d_out = unit(sub(halves[nxt][1], halves[nxt][0]))
            turn = cross(d_in, d_out)
            if nxt == h ^ 1 or turn > SMOOTH:
                contour += round_join(halves[h][-1], pieces[i][-1], pieces[(i + 1) % len(cycle)][0])
            elif turn < -SMOOTH:
                concave.append(len(contour) - 1)
            else:  # a smooth joint: one point midway between the two offset ends
                nxt_piece = pieces[(i + 1) % len(cycle)]
                mid = mul(add(contour.pop(), nxt_piece[0]), 0.5)
                contour.append(mid)
                pieces[(i + 1) % len(cycle)] = [mid] + nxt_piece[1:]
                if i == len(cycle) - 1:
                    contour[0] = mid
        # Cut the concave joins one at a time, each with the contour turned to put it in the
        # middle (so the search windows never wrap).
        marks = [False] * len(contour)
        for m in concave:
            marks[m] = True
        tagged = list(zip(contour, marks))
        while any(t for _, t in tagged):
            m = next(k for k, (_, t) in enumerate(tagged) if t)
            shift = m - len(tagged) // 2
            tagged = tagged[shift:] + tagged[:shift]
            m = len(tagged) // 2
            tagged[m] = (tagged[m][0], False)
            pts = [p for p, _ in tagged]
            cut = cut_concave(pts, m)
            keep = {id(p): t for p, t in tagged}
            tagged = [(p, keep.get(id(p), False)) for p in cut]
        clean = []
        for p, _ in tagged:
            if not clean or math.hypot(p[0] - clean[-1][0], p[1] - clean[-1][1]) > 1e-9:
                clean.append(p)
        if math.hypot(clean[0][0] - clean[-1][0], clean[0][1] - clean[-1][1]) < 1e-9:
            clean.pop()
        result.append(clean)
    return result


def resample(poly, step):
    """Closed polyline -> points every ~step along it, starting at its first point."""
    seg = [math.hypot(poly[(i + 1) % len(poly)][0] - poly[i][0],
                      poly[(i + 1) % len(poly)][1] - poly[i][1]) for i in range(len(poly))]
    total = sum(seg)
    n = int(math.ceil(total / step))
    out, i, run = [], 0, 0.0
    for k in range(n):
        s = total * k / n
        while run + seg[i] < s:
            run += seg[i]
            i += 1
        a, b = poly[i], poly[(i + 1) % len(poly)]
        f = (s - run) / seg[i] if seg[i] > 0 else 0.0
        out.append((a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f))
    return out, total

# ---------------------------------------------------------------- B-spline fitting


def basis(t, span, u):
    """The 4 cubic basis functions nonzero on knot span [t[span], t[span+1])."""
    n = [1.0, 0.0, 0.0, 0.0]
    left, right = [0.0] * 4, [0.0] * 4
    for j in range(1, 4):
        left[j] = u - t[span + 1 - j]
        right[j] = t[span + j] - u
        saved = 0.0
        for r in range(j):
            tmp = n[r] / (right[r + 1] + left[j - r])
            n[r] = saved + right[r + 1] * tmp
            saved = left[j - r] * tmp
        n[j] = saved
    return n


def periodic_knots(breaks, period):
    """Knot vector of the unwrapped periodic cubic: t[3] = 0, t[n + 3] = period."""
    n = len(breaks)
    return [breaks[(i - 3) % n] + period * ((i - 3) // n) for i in range(n + 7)]


def solve(a, b):
    """Gaussian elimination with partial pivoting; b is a list of right-hand sides."""
    n = len(a)
    a = [row[:] + [rhs[i] for rhs in b] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            if f:
                for k in range(c, len(a[r])):
                    a[r][k] -= f * a[c][k]
    x = [[0.0] * n for _ in b]
    for c in range(n - 1, -1, -1):
        for m in range(len(b)):
            s = a[c][n + m] - sum(a[c][k] * x[m][k] for k in range(c + 1, n))
            x[m][c] = s / a[c][c]
    return x


def fit_periodic(pts, params, total, breaks):
    """Least-squares periodic cubic B-spline with span boundaries `breaks` through pts at
    the given parameters. Returns its control points."""
    n = len(breaks)
    t = periodic_knots(breaks, total)
    ata = [[0.0] * n for _ in range(n)]
    atx, aty = [0.0] * n, [0.0] * n
    for p, u in zip(pts, params):
        span, nb = periodic_basis(t, n, u)
        idx = [(span - 3 + i) % n for i in range(4)]
        for i in range(4):
            atx[idx[i]] += nb[i] * p[0]
            aty[idx[i]] += nb[i] * p[1]
            for j in range(4):
                ata[idx[i]][idx[j]] += nb[i] * nb[j]
    cx, cy = solve(ata, [atx, aty])
    return list(zip(cx, cy))


def periodic_basis(t, n, u):
    """Span index and basis functions of the unwrapped periodic knots t at u in [0, period)."""
    lo, hi = 3, n + 2
    while lo < hi:  # last span whose start is <= u
        mid = (lo + hi + 1) // 2
        if t[mid] <= u:
            lo = mid
        else:
            hi = mid - 1
    return lo, basis(t, lo, u)


def periodic_point(ctrl, t, total, u):
    n = len(ctrl)
    span, nb = periodic_basis(t, n, u % total)
    return (sum(nb[i] * ctrl[(span - 3 + i) % n][0] for i in range(4)),
            sum(nb[i] * ctrl[(span - 3 + i) % n][1] for i in range(4)))


def project(ctrl, t, total, p, u):
    """Parameter of the curve point nearest p, by Newton steps from u; and the distance."""
    h = 1e-4
    for _ in range(4):
        c = periodic_point(ctrl, t, total, u)
        c1 = periodic_point(ctrl, t, total, u + h)
        c0 = periodic_point(ctrl, t, total, u - h)
        d1 = ((c1[0] - c0[0]) / (2 * h), (c1[1] - c0[1]) / (2 * h))
        d2 = ((c1[0] - 2 * c[0] + c0[0]) / (h * h), (c1[1] - 2 * c[1] + c0[1]) / (h * h))
        e = sub(c, p)
        f = e[0] * d1[0] + e[1] * d1[1]
        df = d1[0] * d1[0] + d1[1] * d1[1] + e[0] * d2[0] + e[1] * d2[1]
        if df <= 0:
            break
        step = max(-0.2, min(0.2, f / df))
        u -= step
        if abs(step) < 1e-6:
            break
    c = periodic_point(ctrl, t, total, u)
    return u, math.hypot(c[0] - p[0], c[1] - p[1])


def first_breaks(pts, total):
    """First knots: one span per SPAN0_MM of length plus one per SPAN0_DEG of turning."""
    n = len(pts)
    step = total / n
    weight = []
    for k in range(n):
        a, b, c = pts[k - 1], pts[k], pts[(k + 1) % n]
        d1, d2 = sub(b, a), sub(c, b)
        turn = abs(math.atan2(cross(d1, d2), d1[0] * d2[0] + d1[1] * d2[1]))
        weight.append(step / SPAN0_MM + math.degrees(turn) / SPAN0_DEG)
    spans = max(8, int(math.ceil(sum(weight))))
    per = sum(weight) / spans
    breaks, run = [0.0], 0.0
    for k, w in enumerate(weight):
        run += w
        if run >= per * len(breaks) and len(breaks) < spans:
            breaks.append(step * (k + 0.5))
    return breaks


def fit_with(pts, total, breaks):
    """Fit with parameter correction; returns control points and the error per span."""
    params = [total * k / len(pts) for k in range(len(pts))]
    for _ in range(3):
        ctrl = fit_periodic(pts, params, total, breaks)
        t = periodic_knots(breaks, total)
        err = [0.0] * len(breaks)
        for k, p in enumerate(pts):
            u, d = project(ctrl, t, total, p, params[k])
            params[k] = u % total
            span, _ = periodic_basis(t, len(breaks), params[k])
            err[span - 3] = max(err[span - 3], d)
    return ctrl, err


def fit_outline(poly):
    """Closed outline -> periodic cubic B-spline (control points, span boundaries, period):
    least squares with parameter correction; spans that miss the outline by more than
    FIT_TOL are split, then knots the fit can do without are removed."""
    pts, total = resample(poly, SAMPLE_MM)
    breaks = first_breaks(pts, total)
    for _ in range(60):
        ctrl, err = fit_with(pts, total, breaks)
        if max(err) <= FIT_TOL:
            break
        bad = [i for i, e in enumerate(err) if e > max(FIT_TOL, max(err) / 2)]
        ends = breaks + [total]
        for i in reversed(bad):
            breaks.insert(i + 1, (ends[i] + ends[i + 1]) / 2)
    else:
        raise ValueError("outline fit did not converge")
    i = 1  # the knot at 0 stays: the seam of the clamped curve
    while i < len(breaks) and len(breaks) > 8:
        trial = breaks[:i] + breaks[i + 1:]
        c, e = fit_with(pts, total, trial)
        if max(e) <= FIT_TOL:
            breaks, ctrl = trial, c
        else:
            i += 1
    return ctrl, breaks, total


def insert_knot(ctrl, t, u):
    """Boehm insertion of knot u into a cubic (control points, knots)."""
    k = max(i for i in range(3, len(ctrl)) if t[i] <= u)
    new = []
    for i in range(len(ctrl) + 1):
        if i <= k - 3:
            new.append(ctrl[i])
        elif i > k:
            new.append(ctrl[i - 1])
        else:
            a = (u - t[i]) / (t[i + 3] - t[i])
            new.append(add(mul(ctrl[i - 1], 1 - a), mul(ctrl[i], a)))
    return new, t[:k + 1] + [u] + t[k + 1:]


def clamp(ctrl, breaks, total):
    """Periodic cubic -> the same closed curve as a clamped cubic, seam at parameter 0."""
    n = len(ctrl)
    p = ctrl + ctrl[:3]
    t = periodic_knots(breaks, total)
    for u in (0.0, 0.0, total, total):
        p, t = insert_knot(p, t, u)
    a = t.index(0.0)  # first of the three zeros; the curve starts at p[a - 1]
    knots = [0.0] * 4 + [k for k in t if 0.0 < k < total] + [total] * 4
    out = p[a - 1:a - 1 + len(knots) - 4]
    assert len(out) == n + 3
    assert math.hypot(out[0][0] - out[-1][0], out[0][1] - out[-1][1]) < 1e-9
    return out, knots


def split(ctrl, knots):
    """A clamped cubic with more than MAX_CONTROL control points -> pieces that fit."""
    if len(ctrl) <= MAX_CONTROL:
        return [(ctrl, knots)]
    inner = sorted(set(k for k in knots[4:-4]))
    u = inner[len(inner) // 2]
    for _ in range(2):
        ctrl, knots = insert_knot(ctrl, knots, u)
    a = knots.index(u)
    left = (ctrl[:a], knots[:a + 3] + [u])
    right = (ctrl[a - 1:], [u] + knots[a:])
    return split(*left) + split(*right)


# ---------------------------------------------------------------- DXF writer


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
            self.g(40, "%.4f" % k)
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


def word_splines(x):
    """Every letter outline of the word, starting at x (mm), as clamped cubics (control
    points mm, knots mm)."""
    out = []
    for make in WORD:
        strokes, width = make()
        for poly in outlines(strokes):
            mm = [(x + SCALE * px, BASELINE + SCALE * py) for px, py in poly]
            ctrl, breaks, total = fit_outline(mm)
            ctrl, knots = clamp(ctrl, breaks, total)
            ctrl = [(round(px, 4), round(py, 4)) for px, py in ctrl]
            knots = [round(k, 4) for k in knots]
            out += split(ctrl, knots)
        x += SCALE * (width + GAP)
    return out


def main():
    word_w = SCALE * (sum(make()[1] for make in WORD) + GAP * (len(WORD) - 1))
    splines = word_splines((PLATE_W - word_w) / 2)
    d = Dxf()
    d.g(999, "engraver-word.dxf: sample drawing of the engraver project (samples/README.md)")
    d.g(0, "SECTION"); d.g(2, "HEADER")
    d.g(9, "$ACADVER"); d.g(1, "AC1015")
    d.g(9, "$INSUNITS"); d.g(70, 4)
    d.g(0, "ENDSEC")
    d.g(0, "SECTION"); d.g(2, "ENTITIES")
    for ctrl, knots in splines:
        d.spline(ctrl, knots)
    # Plate: rounded rectangle, corner radius 4 mm (bulge tan(90deg / 4)), with a mounting
    # hole in each corner.
    w, h, r = PLATE_W, PLATE_H, 4.0
    for cx, cy in ((4.5, 4.5), (w - 4.5, 4.5), (w - 4.5, h - 4.5), (4.5, h - 4.5)):
        d.circle((cx, cy), 1.5)
    b = math.tan(math.pi / 8)
    d.lwpolyline([(r, 0, 0), (w - r, 0, b), (w, r, 0), (w, h - r, b), (w - r, h, 0),
                  (r, h, b), (0, h - r, 0), (0, r, b)], True)
    d.g(0, "ENDSEC")
    d.g(0, "EOF")
    print("".join(d.out), end="")


if __name__ == "__main__":
    main()
