"""The circle test behind :func:`autobalance.physics.worst_case.residual_bound`: the set of moments
the balls can reach at rest (each ball within s_j of the angles 0 and pi of its required force,
000 eq 20-22), its distance to the moment they would need on a circle |z| = zeta of residual
deflections, and the smallest circle that holds no rest state. The NumPy functions here are the
home; ``core/worst_case.py`` is their compiled twin for one and two balls (tested against them).
"""
from __future__ import annotations

import math

import numpy as np

from ..core.worst_case import N_ARCS, row_min_distance, rows_empty

__all__ = ["COMPILED_GAP"]


#: Most intervals kept in the 1-D Minkowski sum (beyond: neighbours merged, a larger set).
_MAX_INTERVALS = 4096


#: Evaluate the circle test of one or two balls with the compiled twin
#: (core/worst_case.py; same numbers, tests/test_formula_homes.py); False: the NumPy home here.
COMPILED_GAP = True


# -- the reachable set of the balls' moment -----------------------------------------------------
def _x_intervals(c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Sorted disjoint intervals (k, 2) holding every sum_j c_j cos(e_j) with e_j within s_j of
    0 or of pi (the X range of each union box)."""
    iv = np.zeros((1, 2))
    for cj, sj in zip(c, s):
        lo = cj * math.cos(sj)
        parts = np.array([[lo, cj], [-cj, -lo]])
        cand = (iv[:, None, :] + parts[None, :, :]).reshape(-1, 2)
        cand = cand[np.argsort(cand[:, 0])]
        iv = _merge(cand)
    return iv


def _merge(iv: np.ndarray) -> np.ndarray:
    out = [iv[0].copy()]
    for a, b in iv[1:]:
        if a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append(np.array([a, b]))
    iv = np.array(out)
    while len(iv) > _MAX_INTERVALS:            # close the smallest gaps: a larger set, still valid
        gaps = iv[1:, 0] - iv[:-1, 1]
        k = int(np.argmin(gaps))
        iv = np.concatenate([iv[:k], [[iv[k, 0], iv[k + 1, 1]]], iv[k + 2:]])
    return iv


def _x_distance(x: np.ndarray, iv: np.ndarray) -> np.ndarray:
    """Distance of each x to the union of the sorted disjoint intervals iv."""
    starts, ends = iv[:, 0], iv[:, 1]
    n = len(starts)
    k = np.searchsorted(starts, x, side="right") - 1
    d = np.where(k >= 0, np.maximum(x - ends[np.maximum(k, 0)], 0.0), np.inf)
    nxt = np.minimum(k + 1, n - 1)
    return np.minimum(d, np.where(k + 1 < n, starts[nxt] - x, np.inf))


class _Circle:
    """The test 'no rest state on |z| = zeta' for one machine at one speed, one row per
    eccentricity angle beta of ``betas`` (each row covers the beta cell around it)."""

    def __init__(self, c, a, U, h, rho, betas, m_balls, e_f, n_theta):
        self.c, self.a, self.h = c, a, h
        self._tab = np.empty((N_ARCS, 11))          # work array of the compiled twin
        theta = 2.0 * math.pi * (np.arange(n_theta) + 0.5) / n_theta
        rot = np.exp(-1j * theta)[None, :]
        eb = np.exp(1j * np.asarray(betas, float))[:, None]
        self.t0 = -(rho * eb / h + U + m_balls * rho * eb) * rot           # (n_beta, n_theta)
        lip_theta = rho / abs(h) + abs(U) + m_balls * rho
        lip_beta = rho * (1.0 / abs(h) + m_balls)
        self.margin = (lip_theta * math.pi / n_theta + e_f / abs(h)
                       + (lip_beta * math.pi / len(betas) if len(betas) > 1 else 0.0))

    def gap(self, zeta: float) -> np.ndarray:
        """Per row: min distance of the balls' required moment to their reachable set on the
        circle |z| = zeta [m], minus the margin [kg*m]; > 0: no rest state on that circle."""
        s = np.arcsin(np.minimum(1.0, self.a / zeta)) if zeta > 0 else np.zeros(self.a.shape)
        if len(self.c) <= 2 and COMPILED_GAP:      # the compiled twin: row minima directly
            out = np.empty(self.t0.shape[0])
            c2 = float(self.c[1]) if len(self.c) == 2 else 0.0
            s2 = float(s[1]) if len(self.c) == 2 else 0.0
            row_min_distance(self.t0, complex(zeta / self.h), len(self.c), float(self.c[0]), c2,
                             float(s[0]), s2, self._tab, out)
            return out - self.margin
        T = self.t0 + zeta / self.h
        if len(self.c) <= 2:
            d = _arcs_distance(T.ravel(), self.c, s).reshape(T.shape)
        else:
            iv = _x_intervals(self.c, s)
            yh = float(np.sum(self.c * np.sin(s)))
            dx = _x_distance(T.real.ravel(), iv).reshape(T.shape)
            d = np.hypot(dx, np.maximum(np.abs(T.imag) - yh, 0.0))
        return np.min(d, axis=1) - self.margin

    def empty(self, zeta: float) -> np.ndarray:
        """Per row: no rest state on the circle |z| = zeta, i.e. ``gap(zeta) > 0`` (bool); with
        one or two balls the compiled twin stops each row at its first point within the margin."""
        if len(self.c) <= 2 and COMPILED_GAP:
            s = np.arcsin(np.minimum(1.0, self.a / zeta)) if zeta > 0 else np.zeros(self.a.shape)
            out = np.empty(self.t0.shape[0], np.int64)
            c2 = float(self.c[1]) if len(self.c) == 2 else 0.0
            s2 = float(s[1]) if len(self.c) == 2 else 0.0
            rows_empty(self.t0, complex(zeta / self.h), len(self.c), float(self.c[0]), c2,
                       float(s[0]), s2, float(self.margin), self._tab, out)
            return out.astype(bool)
        return self.gap(zeta) > 0


def _within(v, centre: float, half: float):
    """The direction of v lies within half (<= pi) of the angle centre: Re(v e^{-i centre}) >=
    |v| cos(half)."""
    return (v * complex(math.cos(centre), -math.sin(centre))).real >= np.abs(v) * math.cos(half) - 1e-15 * np.abs(v)


def _arc_distance(P, C, r: float, centre: float, half: float):
    """Distance of the points P to the arc C + r e^{i phi}, |phi - centre| <= half."""
    v = P - C
    e0 = C + r * complex(math.cos(centre - half), math.sin(centre - half))
    e1 = C + r * complex(math.cos(centre + half), math.sin(centre + half))
    return np.where(_within(v, centre, half), np.abs(np.abs(v) - r),
                    np.minimum(np.abs(P - e0), np.abs(P - e1)))


def _arcs_distance(T, c, s):
    """Exact distance of T to the moments of one or two balls, ball j on the arcs within s_j of
    the angles 0 and pi (the rotated frame of :class:`_Circle`): for one ball the distance to
    its arcs; for two, 0 inside (the two solutions of the triangle law) and otherwise the
    distance to the image of the boundary of the angle rectangle and of the fold
    (collinear balls), which holds the boundary of the set."""
    if len(c) == 1:
        return np.minimum(_arc_distance(T, 0.0, c[0], 0.0, s[0]),
                          _arc_distance(T, 0.0, c[0], math.pi, s[0]))
    c1, c2 = float(c[0]), float(c[1])
    s1, s2 = float(s[0]), float(s[1])
    r = np.abs(T)
    cg = np.clip((c1 * c1 + r * r - c2 * c2) / (2 * c1 * np.maximum(r, 1e-300)), -1, 1)
    sgn = np.sqrt(1.0 - cg * cg)
    unit = T / np.maximum(r, 1e-300)
    reach = (r <= c1 + c2) & (r >= abs(c1 - c2))
    sols = []
    for sg in (1.0, -1.0):
        u1 = unit * (cg + 1j * sg * sgn)          # direction of ball 1
        sols.append((u1, T - c1 * u1))            # ball 2's moment
    best = np.full(T.shape, np.inf)
    for a1 in (0.0, math.pi):
        for a2 in (0.0, math.pi):
            inside = np.zeros(T.shape, bool)
            for u1, v2 in sols:
                inside |= reach & _within(u1, a1, s1) & _within(v2, a2, s2)
            d = np.minimum.reduce([
                _arc_distance(T, c1 * complex(math.cos(a1 - s1), math.sin(a1 - s1)), c2, a2, s2),
                _arc_distance(T, c1 * complex(math.cos(a1 + s1), math.sin(a1 + s1)), c2, a2, s2),
                _arc_distance(T, c2 * complex(math.cos(a2 - s2), math.sin(a2 - s2)), c1, a1, s1),
                _arc_distance(T, c2 * complex(math.cos(a2 + s2), math.sin(a2 + s2)), c1, a1, s1),
                _fold_distance(T, c1, c2, a1, s1, a2, s2)])
            best = np.minimum(best, np.where(inside, 0.0, d))
    return best


def _fold_distance(T, c1, c2, a1, s1, a2, s2):
    """Distance of T to the collinear configurations of the two arcs: alpha_1 = alpha_2 (radius
    c1 + c2) and alpha_1 = alpha_2 + pi (radius |c1 - c2|), over the overlap of the arcs."""
    out = np.full(T.shape, np.inf)
    for shift, rad in ((0.0, c1 + c2), (math.pi, c1 - c2)):
        # alpha_1 in arc 1 and alpha_1 - shift in arc 2: the overlap of two intervals
        d = float(np.angle(np.exp(1j * (a2 + shift - a1))))
        lo, hi = max(-s1, d - s2), min(s1, d + s2)
        if lo > hi:
            continue
        centre, half = a1 + 0.5 * (lo + hi), 0.5 * (hi - lo)
        if rad < 0:
            rad, centre = -rad, centre + math.pi
        out = np.minimum(out, _arc_distance(T, 0.0, rad, centre, half))
    return out


def _separating_radius(circle: _Circle, a: np.ndarray, zeta_max: float):
    """Largest over the rows of the smallest zeta (scan x1.1 (x2 without rolling resistance),
    then bisection to 1e-10) whose circle
    holds no rest state; None if a row has none below zeta_max. (A scan step that jumps over
    a thin empty window only returns a larger circle: still a bound.)"""
    step = 1.1
    if np.all(a == 0):                 # the balls' sets do not depend on zeta: coarser steps
        tiny = 1e-12 * max(zeta_max, 1e-300)
        if np.all(circle.empty(tiny)):
            return 0.0
        start, step = 1e-6 * zeta_max, 2.0
    else:
        pos = a[a > 0]
        start = float(pos.min()) if np.all(a > 0) else 1e-6 * float(pos.max())
    found = circle.empty(start)
    if np.all(found):
        return start
    lo = hi = start
    while True:                        # rows still without an empty circle at lo
        if lo > zeta_max:
            return None
        hi = step * lo
        g = circle.empty(hi)
        if np.all(found | g):
            break
        found |= g
        lo = hi
    rows = ~found                      # these rows' first empty circle lies in (lo, hi]
    for _ in range(60):
        if hi - lo <= 1e-10 * hi:
            break
        mid = 0.5 * (lo + hi)
        empty = circle.empty(mid)
        if np.all(empty[rows]):
            hi = mid                   # every row has an empty circle <= mid
        else:
            lo = mid                   # rows empty at mid keep that circle; the others go on
            rows = rows & ~empty
    return float(hi)
