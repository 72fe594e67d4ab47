#!/usr/bin/env python3
"""Writes the experiment's two NURBS surfaces to assets/nurbs/ (see assets/nurbs/README.md).

The paper ([nurbs] in docs/design.md) gives only the counts: a butterfly of 81 control points and a corn
leaf of 175. Both nets are built here from closed-form shape functions, so they can be
rebuilt and changed in one place. Pure Python, deterministic: running it again writes the
same bytes.

    python3 scripts/make_nurbs_assets.py
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "assets", "nurbs")


def clamped(interior, degree):
    return [0.0] * (degree + 1) + list(interior) + [1.0] * (degree + 1)


def greville(knots, degree, count):
    """The parameter each control point stands for (the mean of the degree knots after its
    index); the shapes are sampled there, so that the net follows the parameterization."""
    return [sum(knots[i + 1:i + degree + 1]) / degree for i in range(count)]


def lerp_table(table, t):
    """Piecewise-linear interpolation of equally spaced values over [0, 1]."""
    x = t * (len(table) - 1)
    k = min(int(x), len(table) - 2)
    f = x - k
    return table[k] * (1 - f) + table[k + 1] * f


def write(name, about, degree, count, knots, rows):
    path = os.path.join(OUT, name + ".nurbs")
    with open(path, "w") as f:
        f.write("# %s\n" % about)
        f.write("# Written by scripts/make_nurbs_assets.py; format in assets/nurbs/README.md.\n")
        f.write("nurbs 1\n")
        f.write("name %s\n" % name)
        f.write("degree %d %d\n" % degree)
        f.write("count %d %d\n" % count)
        f.write("knots u %s\n" % " ".join("%.6f" % k for k in knots[0]))
        f.write("knots v %s\n" % " ".join("%.6f" % k for k in knots[1]))
        for (x, y, z, w) in rows:
            f.write("point %.6f %.6f %.6f %.4f\n" % (x, y, z, w))
    print("wrote", os.path.relpath(path), "(%d control points)" % len(rows))


def butterfly():
    """9 x 9 bicubic: u runs from the left wing tip to the right one across the body, v
    from the head to the tail. Body along -z, wings spread along x and raised in a V
    (dihedral); the half-span along v traces the forewing, the notch between the wings and
    the smaller hindwing; wing tips carry weight 1.5 (rational)."""
    nu, nv = 9, 9
    half_span = [0.030, 0.042, 0.046, 0.040, 0.026, 0.030, 0.032, 0.026, 0.014]
    knots = (clamped([0.1, 0.3, 0.5, 0.7, 0.9], 3), clamped([0.15, 0.3, 0.5, 0.65, 0.85], 3))
    gu, gv = greville(knots[0], 3, nu), greville(knots[1], 3, nv)
    rows = []
    for i in range(nu):
        s = 2 * gu[i] - 1  # -1 .. 1 across the span
        a = abs(s)
        for j in range(nv):
            t = gv[j]  # 0 head .. 1 tail
            h = lerp_table(half_span, t)
            x = h * math.copysign(a ** 0.9, s)
            z = 0.022 - 0.050 * t + 0.010 * a * a * (1 - t) - 0.008 * a * a * t
            y = 0.010 * a ** 1.5 - 0.002 * (1 - a) ** 2
            w = 1.0 + 0.5 * a * a
            rows.append((x, y, z, w))
    write("butterfly", "Butterfly: 9 x 9 = 81 control points, bicubic, rational (wing tips weight 1.5).",
          (3, 3), (nu, nv), knots, rows)


def leaf():
    """7 x 25 bicubic: u across the blade, v from the base to the tip. The midrib rises from
    the base and arches over (z forward, y up); the half-width swells from the sheath to its
    widest about 40% along and narrows to the tip; the blade folds into a V along the midrib
    and its margins ripple; the midrib column carries weight 1.25 (rational)."""
    nu, nv = 7, 25
    interior = [(k / 22) ** 1.1 for k in range(1, 22)]
    knots = (clamped([0.3, 0.5, 0.7], 3), clamped(interior, 3))
    gu, gv = greville(knots[0], 3, nu), greville(knots[1], 3, nv)
    rows = []
    for i in range(nu):
        s = 2 * gu[i] - 1
        a = abs(s)
        for j in range(nv):
            t = gv[j]
            cy, cz = 0.30 * t - 0.32 * t * t, 0.50 * t
            ty, tz = 0.30 - 0.64 * t, 0.50
            n = math.hypot(ty, tz)
            ny, nz = tz / n, -ty / n  # normal of the midrib, upwards
            width = max(0.045 * math.sin(math.pi * t ** 0.75) ** 0.7 + 0.010 * (1 - t) ** 3, 0.0008)
            lift = 0.010 * a * (1 - 0.7 * t) + 0.004 * math.sin(2 * math.pi * 7 * t) * a ** 3
            x = width * s
            y = cy + ny * lift
            z = cz + nz * lift
            w = 1.0 + 0.25 * (1 - a)
            rows.append((x, y, z, w))
    write("corn-leaf", "Corn leaf: 7 x 25 = 175 control points, bicubic, rational (midrib weight 1.25).",
          (3, 3), (nu, nv), knots, rows)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    butterfly()
    leaf()
