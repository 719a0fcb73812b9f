"""Compiled twin of the circle test of :mod:`autobalance.physics.worst_case` for one and two balls:
the distance of the balls' required moment T to the set their moments can reach (arcs within s_j
of the angles 0 and pi, the triangle law for two balls, the fold of collinear balls), reduced to
its minimum per row. The Python home (``physics.reachable_set._arcs_distance``) is the reference;
tests/test_formula_homes.py checks this twin against it. Same operations per point; the arcs' geometry
(the same for every point) is tabulated once per call, and the home's ~40 temporary arrays per
call are scalars here.
"""
from __future__ import annotations

import cmath
import math
from typing import TYPE_CHECKING

from .jit import kernel

if TYPE_CHECKING:
    import numpy as np


#: Columns of the arc table: combination (a1, a2) index, centre C (re, im), radius, cos and sin of
#: the arc's mid angle, cos of its half-width, and its end points e0, e1 (re, im).
_K, _CR, _CI, _R, _COS, _SIN, _CH, _E0R, _E0I, _E1R, _E1I = range(11)
#: Rows of the arc table: 4 combinations x (4 arcs + 2 fold arcs).
N_ARCS = 24


@kernel
def _put(tab, k, combo, C, r, centre, half):
    """Row k of the arc table: the arc C + r e^{i phi}, |phi - centre| <= half."""
    tab[k, _K] = combo
    tab[k, _CR] = C.real
    tab[k, _CI] = C.imag
    tab[k, _R] = r
    tab[k, _COS] = math.cos(centre)
    tab[k, _SIN] = math.sin(centre)
    tab[k, _CH] = math.cos(half)
    e0 = C + r * complex(math.cos(centre - half), math.sin(centre - half))
    e1 = C + r * complex(math.cos(centre + half), math.sin(centre + half))
    tab[k, _E0R] = e0.real
    tab[k, _E0I] = e0.imag
    tab[k, _E1R] = e1.real
    tab[k, _E1I] = e1.imag


@kernel
def arc_table(n: int, c1: float, c2: float, s1: float, s2: float, tab: np.ndarray) -> int:
    """The arcs whose distances make the home's ``_arcs_distance`` (one ball: 2 arcs; two balls:
    per combination (a1, a2) in {0, pi}^2 the 4 boundary arcs and the fold's 0-2 arcs); the
    geometry is the same for every point, so it is computed once. Returns the row count."""
    k = 0
    if n == 1:
        _put(tab, 0, -1.0, 0j, c1, 0.0, s1)
        _put(tab, 1, -1.0, 0j, c1, math.pi, s1)
        return 2
    for i1 in range(2):
        a1 = 0.0 if i1 == 0 else math.pi
        for i2 in range(2):
            a2 = 0.0 if i2 == 0 else math.pi
            combo = float(2 * i1 + i2)
            _put(tab, k, combo, c1 * complex(math.cos(a1 - s1), math.sin(a1 - s1)), c2, a2, s2)
            _put(tab, k + 1, combo, c1 * complex(math.cos(a1 + s1), math.sin(a1 + s1)), c2, a2, s2)
            _put(tab, k + 2, combo, c2 * complex(math.cos(a2 - s2), math.sin(a2 - s2)), c1, a1, s1)
            _put(tab, k + 3, combo, c2 * complex(math.cos(a2 + s2), math.sin(a2 + s2)), c1, a1, s1)
            k += 4
            for f in range(2):                   # the fold: collinear balls (home: _fold_distance)
                shift = 0.0 if f == 0 else math.pi
                rad = c1 + c2 if f == 0 else c1 - c2
                d = cmath.phase(cmath.exp(1j * (a2 + shift - a1)))
                lo = max(-s1, d - s2)
                hi = min(s1, d + s2)
                if lo > hi:
                    continue
                centre = a1 + 0.5 * (lo + hi)
                half = 0.5 * (hi - lo)
                if rad < 0:
                    rad = -rad
                    centre = centre + math.pi
                _put(tab, k, combo, 0j, rad, centre, half)
                k += 1
    return k


@kernel
def _within_cs(v, cc, sc, ch):
    """Re(v e^{-i centre}) >= |v| cos(half) with cos/sin(centre) and cos(half) given (the home's
    ``_within``)."""
    av = abs(v)
    return (v * complex(cc, -sc)).real >= av * ch - 1e-15 * av


@kernel
def _arc_row(P, tab, k):
    """Distance of P to the arc of table row k (the home's ``_arc_distance``)."""
    C = complex(tab[k, _CR], tab[k, _CI])
    v = P - C
    if _within_cs(v, tab[k, _COS], tab[k, _SIN], tab[k, _CH]):
        return abs(abs(v) - tab[k, _R])
    return min(abs(P - complex(tab[k, _E0R], tab[k, _E0I])),
               abs(P - complex(tab[k, _E1R], tab[k, _E1I])))


@kernel
def arcs_distance(T: complex, n: int, c1: float, c2: float, cs1: float, cs2: float,
                  tab: np.ndarray, nrow: int) -> float:
    """Distance of T [kg*m] to the moments of n = 1 or 2 balls (moments c1, c2 [kg*m]; cs1, cs2
    the cosines of their half-widths s1, s2) with the arcs of :func:`arc_table` (the home's
    ``_arcs_distance`` for one point)."""
    if n == 1:
        return min(_arc_row(T, tab, 0), _arc_row(T, tab, 1))
    r = abs(T)
    rr = max(r, 1e-300)
    cg = min(max((c1 * c1 + r * r - c2 * c2) / (2 * c1 * rr), -1.0), 1.0)
    sgn = math.sqrt(1.0 - cg * cg)
    unit = T / rr
    reach = (r <= c1 + c2) and (r >= abs(c1 - c2))
    ua = unit * complex(cg, sgn)
    ub = unit * complex(cg, -sgn)
    va = T - c1 * ua
    vb = T - c1 * ub
    best = math.inf
    k = 0
    for combo in range(4):
        c1s = 1.0 if combo < 2 else -1.0          # cos(a1), a1 in {0, pi}; sin(a1) = 0
        c2s = 1.0 if combo % 2 == 0 else -1.0
        # home: sin(pi) = 1.2e-16, not 0: keep its value for identical rounding
        sa1 = 0.0 if combo < 2 else math.sin(math.pi)
        sa2 = 0.0 if combo % 2 == 0 else math.sin(math.pi)
        inside = reach and ((_within_cs(ua, c1s, sa1, cs1) and _within_cs(va, c2s, sa2, cs2))
                            or (_within_cs(ub, c1s, sa1, cs1) and _within_cs(vb, c2s, sa2, cs2)))
        d = math.inf
        while k < nrow and tab[k, _K] == combo:
            d = min(d, _arc_row(T, tab, k))
            k += 1
        best = min(best, 0.0 if inside else d)
    return best


@kernel
def row_min_distance(t0: np.ndarray, shift: complex, n: int, c1: float, c2: float, s1: float,
                     s2: float, tab: np.ndarray, out: np.ndarray) -> None:
    """out[i] = min over j of the distance of t0[i, j] + shift [kg*m] to the balls' reachable
    moments (:func:`arcs_distance`), for a (rows, points) array t0 and a common complex shift
    [kg*m] (zeta / h of the circle test); tab: a work array (N_ARCS, 11)."""
    nrow = arc_table(n, c1, c2, s1, s2, tab)
    cs1 = math.cos(s1)
    cs2 = math.cos(s2)
    for i in range(t0.shape[0]):
        m = math.inf
        for j in range(t0.shape[1]):
            d = arcs_distance(t0[i, j] + shift, n, c1, c2, cs1, cs2, tab, nrow)
            if d < m:
                m = d
        out[i] = m


@kernel
def rows_empty(t0: np.ndarray, shift: complex, n: int, c1: float, c2: float, s1: float,
               s2: float, margin: float, tab: np.ndarray, out: np.ndarray) -> None:
    """out[i] = 1 if every point of row i is farther than ``margin`` [kg*m] from the balls'
    reachable moments (the circle test's "no rest state on this circle", i.e. the row minimum of
    :func:`row_min_distance` minus the margin is > 0), else 0; a row stops at its first point
    within the margin."""
    nrow = arc_table(n, c1, c2, s1, s2, tab)
    cs1 = math.cos(s1)
    cs2 = math.cos(s2)
    for i in range(t0.shape[0]):
        ok = 1
        for j in range(t0.shape[1]):
            if arcs_distance(t0[i, j] + shift, n, c1, c2, cs1, cs2, tab, nrow) - margin <= 0.0:
                ok = 0
                break
        out[i] = ok
