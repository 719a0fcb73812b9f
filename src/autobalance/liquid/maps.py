"""Linear modes of a scheme's maps (docs/liquid/stability.md sec. 3j, 3k, horizontal-axis.md
sec. 3m): the Jacobian of a one-step or one-period map by central differences, its eigenvalues
as growth rates, and Newton shooting for the periodic state of a one-period map. The liquid's
stability analyses (liquid/stability.py, studies/liquid_balanced.py) linearise the film runs'
own schemes with these.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Callable

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Sequence

    from .film import FilmsState

__all__ = ["EPS", "FinerGrid", "compartments", "jacobian", "linear_modes", "multiplier_modes",
           "periodic_state"]

#: Relative size of the state's perturbations of the central differences [-].
EPS = 1e-6
#: Newton iterations of the shooting for the periodic state on a horizontal axis [-].
SHOOT_ITERS = 12
#: Halvings of a Newton step of the shooting that does not lower the residual [-].
SHOOT_HALVINGS = 6
#: Scaled residual max |P(x) - x| / scale at which the shooting stops [-].
SHOOT_STOP = 1e-10
#: ... and up to which the periodic state counts as found [-]. The scheme's map is continuous
#: but only piecewise smooth (the wall friction's larger of the laminar and turbulent laws,
#: core/shallow_water.friction_rate; the HLL flux's wave speeds), so Newton can stall near a
#: kink. Before the friction law was made continuous it stalled at 6.4e-6 on 003's bench at
#: 50 1/s (150 ml), alternating between two states whose multipliers agreed to 1e-4; it now
#: reaches 8.5e-15 there.
SHOOT_TOL = 1e-4


class FinerGrid(Exception):
    """The shooting (:func:`periodic_state`) needs a finer grid of the period map at the state
    ``x`` it reached."""

    def __init__(self, x: np.ndarray):
        super().__init__("a finer grid")
        self.x = x


def compartments(st: FilmsState) -> list[np.ndarray]:
    """The cells of each compartment of the films (a chamber without partitions is one; with
    them, the cells from one radial wall to the next, :func:`autobalance.liquid.film.
    partition_walls`), as index arrays into the films' layout.

    Parameters
    ----------
    st : autobalance.liquid.film.FilmsState
        The films.

    Returns
    -------
    list of ndarray of int
    """
    out = []
    for o0, o1 in zip(st.starts[:-1], st.starts[1:]):
        cuts = np.nonzero(st.wall[o0:o1])[0] + 1
        out += [c for c in np.split(np.arange(o0, o1), cuts) if c.size]
    return out


def periodic_state(P: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, scale: np.ndarray,
                   conserved: Sequence[np.ndarray], what: str) -> tuple[np.ndarray, np.ndarray,
                                                                       float]:
    """Newton shooting for the periodic state x* = P(x*) of a one-period map P from the guess
    x0 (as :func:`autobalance.studies.equilibria.floquet_full` does for the balls): each step
    solves (J - 1) s = x - P(x) with J the Jacobian of P (:func:`jacobian`) in the scaled
    state x / scale, by least squares, with the rows sum(s[c]) = 0 of every ``conserved`` set c
    (a compartment's volume: P keeps it, so J - 1 is singular along it and the shooting must not
    move it). Each step is halved until it lowers the residual's 2-norm (at most SHOOT_HALVINGS
    times: damped Newton). Ends after SHOOT_ITERS steps, below SHOOT_STOP or where no step lowers the
    residual. P raises ValueError where its grid is too coarse for a state: such a trial counts
    as no lower residual, and :class:`FinerGrid` (with the state reached) is raised where that
    stalls the shooting, or the guess or a difference step needs it.

    Parameters
    ----------
    P : callable
        The one-period map x -> x.
    x0 : ndarray
        The first guess [mixed: each entry's own unit].
    scale : ndarray
        Each entry's scale [mixed] (the differences' steps are EPS x scale).
    conserved : sequence of ndarray of int
        Index sets whose sum P conserves [-].
    what : str
        The caller, for the error message.

    Returns
    -------
    (ndarray, ndarray, float)
        x* [mixed], the monodromy J = dP/dx at x* [-] and the scaled residual
        max |P(x*) - x*| / scale [-].
    """
    x = x0.astype(float).copy()
    n = x.size
    rows = np.zeros((len(conserved), n))
    for i, c in enumerate(conserved):
        rows[i, c] = 1.0
    grid = []

    def residual(x):
        try:
            G = (P(x) - x) / scale
        except ValueError:          # the state needs a finer grid than P's
            grid.append(True)
            return math.inf, None
        r = float(np.linalg.norm(G))
        return (r, G) if np.isfinite(r) else (math.inf, None)

    def jac(x):
        try:
            return jacobian(P, x, scale)
        except ValueError:
            raise FinerGrid(x) from None

    res, G = residual(x)
    if G is None:
        raise FinerGrid(x)
    J = None
    for _ in range(SHOOT_ITERS):
        J = jac(x)
        if np.max(np.abs(G)) < SHOOT_STOP:
            break
        A = (J - np.eye(n)) * scale[None, :] / scale[:, None]
        s = np.linalg.lstsq(np.vstack([A, rows]), np.concatenate([-G, np.zeros(len(conserved))]),
                            rcond=1e-12)[0] * scale
        grid.clear()
        for _ in range(SHOOT_HALVINGS + 1):     # damped: a step must lower |G|
            r1, G1 = residual(x + s)
            if r1 < res:
                break
            s = 0.5 * s
        else:                                   # no lower residual along the step: stalled
            if grid:                            # ... where P's grid was too coarse
                raise FinerGrid(x)
            break
        x, res, G = x + s, r1, G1
    else:
        J = jac(x)
    return x, J, float(np.max(np.abs(G)))


def linear_modes(f: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, scale: np.ndarray,
                 dt: float, n_neutral: int, what: str) -> np.ndarray:
    """The eigenvalues lambda = ln(mu) / dt [1/s] of a one-step map f about its fixed point x0,
    largest real part first: the Jacobian by central differences (step EPS x ``scale`` per
    state entry), its eigenvalues mu, and the ``n_neutral`` closest to 1 dropped after checking
    |mu - 1| < 1e-7 (the conserved volumes, a balanced family: steady states that decide
    nothing; ``what`` names the caller in the error).

    Parameters
    ----------
    f : callable
        x -> x after one step dt of the linearised scheme (state units as x0's).
    x0 : ndarray
        The fixed point [mixed: each entry's own unit].
    scale : ndarray
        Each entry's perturbation scale [mixed: the entry's unit].
    dt : float
        The map's step [s].
    n_neutral : int
        Neutral modes to drop [-].
    what : str
        The caller, for the error message.

    Returns
    -------
    ndarray of complex
        lambda [1/s], sorted by decreasing real part (a mode the map sends to 0: -inf).
    """
    return multiplier_modes(jacobian(f, x0, scale), dt, n_neutral, what)


def jacobian(f: Callable[[np.ndarray], np.ndarray], x0: np.ndarray,
             scale: np.ndarray) -> np.ndarray:
    """The Jacobian of the map f at x0 by central differences, the step EPS x ``scale`` per
    state entry.

    Parameters
    ----------
    f : callable
        The map x -> x (state units as x0's).
    x0 : ndarray
        Where [mixed: each entry's own unit].
    scale : ndarray
        Each entry's perturbation scale [mixed: the entry's unit].

    Returns
    -------
    ndarray (n, n)
        df/dx [-, in the entries' units].
    """
    J = np.empty((x0.size, x0.size))
    for j in range(x0.size):
        e = EPS * scale[j]
        xp = x0.copy()
        xm = x0.copy()
        xp[j] += e
        xm[j] -= e
        J[:, j] = (f(xp) - f(xm)) / (2.0 * e)
    return J


def multiplier_modes(J: np.ndarray, dt: float, n_neutral: int, what: str) -> np.ndarray:
    """The eigenvalues lambda = ln(mu) / dt [1/s] of a map's Jacobian J over dt [s] (its
    multipliers mu), largest real part first, the ``n_neutral`` multipliers closest to 1
    dropped after checking |mu - 1| < 1e-7 (``what`` names the caller in the error).

    Parameters
    ----------
    J : ndarray (n, n)
        The Jacobian of a one-step or one-period map [-].
    dt : float
        The map's time [s].
    n_neutral : int
        Neutral modes to drop [-].
    what : str
        The caller, for the error message.

    Returns
    -------
    ndarray of complex
        lambda [1/s], sorted by decreasing real part (a mode the map sends to 0: -inf).
    """
    mu = np.linalg.eigvals(J).astype(complex)
    near = np.argsort(np.abs(mu - 1.0))[:n_neutral]
    if n_neutral and np.max(np.abs(mu[near] - 1.0)) > 1e-7:
        raise RuntimeError(f"{what}: the neutral modes were not found "
                           f"(|mu - 1| = {np.max(np.abs(mu[near] - 1.0)):.3g})")
    mu = np.delete(mu, near)
    with np.errstate(divide="ignore"):
        lam = np.log(mu) / dt
    return lam[np.argsort(-lam.real)]
