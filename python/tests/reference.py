"""Independent references for the Python tests: real SH by the textbook associated-Legendre
recurrence with factorial normalisation (not zhf's normalised recurrence), and rotations built
from axis and angle by Rodrigues' formula."""

from math import factorial, pi, sqrt

import numpy as np


def real_sh(order, directions):
    """(points, 3) unit directions -> (points, order*order): zhf's convention (no Condon-Shortley
    phase, index l(l+1)+m, m < 0 with sin(|m| phi))."""
    d = np.asarray(directions, dtype=np.float64)
    x, y, z = d[:, 0], d[:, 1], d[:, 2]
    s = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    phi = np.arctan2(y, x)
    out = np.zeros((len(d), order * order))
    for m in range(order):
        # P_m^m = (2m-1)!! s^m, P_{m+1}^m = (2m+1) z P_m^m, then the three-term recurrence in l.
        p = {m: np.prod(np.arange(1, 2 * m, 2, dtype=np.float64)) * s ** m}
        if m + 1 < order:
            p[m + 1] = (2 * m + 1) * z * p[m]
        for l in range(m + 2, order):
            p[l] = ((2 * l - 1) * z * p[l - 1] - (l + m - 1) * p[l - 2]) / (l - m)
        for l in range(m, order):
            k = sqrt((2 * l + 1) / (4 * pi) * factorial(l - m) / factorial(l + m))
            if m == 0:
                out[:, l * (l + 1)] = k * p[l]
            else:
                out[:, l * (l + 1) + m] = sqrt(2) * k * p[l] * np.cos(m * phi)
                out[:, l * (l + 1) - m] = sqrt(2) * k * p[l] * np.sin(m * phi)
    return out


def rotation_about_axis(axis, angle):
    """A right-handed turn by angle about axis (Rodrigues), v -> R v."""
    u = np.asarray(axis, dtype=np.float64)
    u = u / np.linalg.norm(u)
    k = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def random_rotation(rng):
    return rotation_about_axis(rng.standard_normal(3), rng.uniform(0, 2 * pi))


def random_directions(rng, count):
    d = rng.standard_normal((count, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)
