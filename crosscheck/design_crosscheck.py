#!/usr/bin/env python3
"""Checks design files independently of zhf: the largest |sum_i y_l^m(x_i)| / M over 1 <= l <= t
and every m, with the real orthonormal SH from the normalised associated-Legendre recurrence,
in NumPy's long double. A t-design gives rounding (~1e-16); a point moved by 1e-6 gives ~1e-8.

Usage: python3 crosscheck/design_crosscheck.py t_100.json [more design files]
"""
import json
import sys

import numpy as np

L = np.longdouble
PI = L("3.14159265358979323846264338327950288")


def worst_sum(points, t):
    x = np.array([[L(repr(c)) for c in p] for p in points], dtype=L)
    x /= np.sqrt((x * x).sum(axis=1))[:, None]
    z = x[:, 2]
    s = np.sqrt(np.maximum(L(0), 1 - z * z))
    phi = np.arctan2(x[:, 1], x[:, 0])
    count = len(x)
    worst = L(0)
    diagonal = np.full(count, 1 / np.sqrt(4 * PI), dtype=L)  # P_m^m, normalised
    for m in range(t + 1):
        if m > 0:
            diagonal = diagonal * np.sqrt(L(2 * m + 1) / L(2 * m)) * s
        trig = [np.ones(count, dtype=L)] if m == 0 else [np.sqrt(L(2)) * np.cos(m * phi), np.sqrt(L(2)) * np.sin(m * phi)]
        before, p = None, diagonal
        for l in range(m, t + 1):
            if l == m + 1:
                before, p = p, np.sqrt(L(2 * m + 3)) * z * p
            elif l > m + 1:
                a = np.sqrt(L(4 * l * l - 1) / L(l * l - m * m))
                b = np.sqrt(L((l - 1) ** 2 - m * m) / L(4 * (l - 1) ** 2 - 1))
                before, p = p, a * (z * p - b * before)
            if l >= 1:
                for factor in trig:
                    worst = max(worst, abs((p * factor).sum()) / count)
    return worst


for path in sys.argv[1:]:
    with open(path) as f:
        design = json.load(f)
    print("%s: t %d, %d points, max |sum y| / M = %.2e" % (path, design["t"], len(design["points"]), float(worst_sum(design["points"], design["t"]))))
