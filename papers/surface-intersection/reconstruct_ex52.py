#!/usr/bin/env python3
"""Alsaïdi's Example 5.2: one biquadratic pair consistent with the paper's tables.

The PDF garbled the control points of the two Bezier surfaces of Example 5.2
(vectors of five numbers for points in 3-D), and its tables do not pin the
pair down: the tabulated points sit in a few clusters, and 11 pairs of
coordinate nets (the constant among them) vanish on them to about their
rounding, where 4 would fix the pair up to a common affine map of space
(`free_directions`). This script builds ONE pair whose intersection
passes near the tabulated points, with every choice written out:

  A1  both patches have bidegree (2, 2) ("two quadratic Bezier surfaces").
  A2  S1(u, v) = (u, v, c1(u, v)): a graph over the unit square.
  A3  S2(s, t) = (X(s, t), Y(s, t), -c2(s, t)): X, Y biquadratic, fitted so
      that (X, Y)(s_k, t_k) = (u_k, v_k) at the tabulated points (least
      squares, Tikhonov 1e-6 toward the identity grid X = s, Y = t).
  A4  c1 (c2) is the conic (total degree 2) fitted algebraically to the
      tabulated (u, v) ((s, t)) points, scaled to unit gradient on average
      there and signed so that c1(X, Y) and c2 agree; the curve is then
      c1(u, v) + c2(s, t) = 0 with (u, v) = (X, Y)(s, t): the zero levels of
      a bowl and a dome, as in Example 5.1.
  A5  fitted to Table 2 and the four Example-5.2 rows the PDF put in Table 1;
      Table 4 (RK4, same start) is left out of the fit: its (s, t) run
      backwards against its (u, v) (see the README), so it is not a curve.
  A6  control points rounded to 4 decimals; the JSON files are the pair.

Writes examples/data/ssi/seed002_ex52_{a,b}.json. Needs numpy. Run from the
repository root: python3 papers/surface-intersection/reconstruct_ex52.py
"""
import json
from math import comb

import numpy as np

# (u, v, s, t): Table 2 and Table 1's rows 42, 89, 45, 49 (which belong to 5.2).
FIT = [
    (0.7274, 0.2327, 0.7849, 0.2990), (0.6506, 0.4785, 0.7954, 0.5829),
    (0.5868, 0.5138, 0.7475, 0.6408), (0.5839, 0.5149, 0.7450, 0.6428),
    (0.7031, 0.1782, 0.7436, 0.2362), (0.3939, 0.1505, 0.3981, 0.1613),
    (0.3862, 0.1536, 0.3904, 0.1637), (0.3827, 0.1550, 0.3870, 0.1649),
    (0.3825, 0.1551, 0.3868, 0.1650), (0.3825, 0.1551, 0.3867, 0.1650),
    (0.4842, 0.1249, 0.4910, 0.1454), (0.3823, 0.1552, 0.3865, 0.1651),
    (0.4499, 0.1324, 0.4552, 0.1487), (0.4205, 0.1410, 0.4250, 0.1542),
]


def bern(n, i, x):
    return comb(n, i) * x**i * (1 - x) ** (n - i)


def basis22(u, v):
    return np.array([bern(2, i, u) * bern(2, j, v) for i in range(3) for j in range(3)])


def conic_terms(x, y):
    return np.array([1, x, y, x * x, x * y, y * y])


def fit_conic(pts):
    """Smallest right singular vector, scaled to unit mean gradient at the points."""
    c = np.linalg.svd(np.array([conic_terms(x, y) for x, y in pts]))[2][-1]
    grad = [np.hypot(c[1] + 2 * c[3] * x + c[4] * y, c[2] + c[4] * x + 2 * c[5] * y) for x, y in pts]
    return c / np.mean(grad)


def conic_net(c):
    """Bernstein coefficients (bidegree (2, 2) on [0, 1]^2) of a conic: 1 -> (1, 1, 1),
    x -> (0, 1/2, 1), x^2 -> (0, 0, 1), tensor products."""
    p = [np.ones(3), np.array([0, 0.5, 1]), np.array([0, 0, 1.0])]
    terms = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)]
    return sum(ck * np.outer(p[a], p[b]) for ck, (a, b) in zip(c, terms))


def ridge(a, b, prior, lam):
    m = np.vstack([a, np.sqrt(lam) * np.eye(a.shape[1])])
    return np.linalg.lstsq(m, np.concatenate([b, np.sqrt(lam) * prior]), rcond=None)[0]


def free_directions(pts, rel=1e-4):
    """How many pairs of coordinate nets (9 + 9 values, one coordinate) vanish on the
    tabulated points to about their rounding: right singular vectors of the
    collocation matrix with singular value below `rel`, the constant included."""
    rows = [np.concatenate([basis22(p[0], p[1]), -basis22(p[2], p[3])]) for p in pts]
    sv = np.linalg.svd(np.array(rows), compute_uv=False)
    return 18 - len(sv) + int(np.sum(sv < rel * 1.5))


def main():
    print(f"free directions at the tables' rounding (constant included): {free_directions(FIT)}")
    grid = np.array([[i / 2, j / 2] for i in range(3) for j in range(3)])
    a = np.array([basis22(p[2], p[3]) for p in FIT])
    x_net = ridge(a, np.array([p[0] for p in FIT]), grid[:, 0], 1e-6).reshape(3, 3)
    y_net = ridge(a, np.array([p[1] for p in FIT]), grid[:, 1], 1e-6).reshape(3, 3)
    c1 = fit_conic([(p[0], p[1]) for p in FIT])
    c2 = fit_conic([(p[2], p[3]) for p in FIT])
    # Sign: c2 must agree with c1 composed with (X, Y) off the curve.
    probe = [(s, t) for s in np.linspace(0, 1, 11) for t in np.linspace(0, 1, 11)]
    dot = 0.0
    for s, t in probe:
        b = basis22(s, t)
        dot += (conic_terms(b @ x_net.ravel(), b @ y_net.ravel()) @ c1) * (conic_terms(s, t) @ c2)
    if dot < 0:
        c2 = -c2
    z1, z2 = conic_net(c1), -conic_net(c2)
    net1 = [[float(round(grid[3 * i + j][0], 4)), float(round(grid[3 * i + j][1], 4)), float(round(z1[i, j], 4))] for i in range(3) for j in range(3)]
    net2 = [[float(round(x_net[i, j], 4)), float(round(y_net[i, j], 4)), float(round(z2[i, j], 4))] for i in range(3) for j in range(3)]
    for name, net in [("a", net1), ("b", net2)]:
        with open(f"examples/data/ssi/seed002_ex52_{name}.json", "w") as f:
            json.dump({"type": "tensor", "degree": [2, 2], "points": net}, f)
            f.write("\n")
    print("S1", json.dumps(net1), "\nS2", json.dumps(net2))


if __name__ == "__main__":
    main()
