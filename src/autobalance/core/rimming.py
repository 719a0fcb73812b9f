"""Shallow-water equations of the liquid on the outer wall of a chamber turning about a
*horizontal* axis, from a puddle at rest (until it closes into a ring) or from a ring (until it
breaks), at any speed (model: docs/liquid/horizontal-axis.md sec. 3n).

Unknowns per cell of the periodic wall coordinate x = R theta (chamber frame, turning at
Omega(t), spin angle psi): the layer's thickness h [m] and discharge q = h v [m^2/s], v relative
to the wall. The layer is thin-walled as the wall film of :mod:`.shallow_water` (the liquid at
radius R, O(h/R)), but the acceleration that holds it on the wall is the exact one:

    G = omega^2 R + g cos(theta + psi - gamma),    omega = Omega + v / R

the centrifugal, Coriolis and curvature terms of the liquid's *own* rotation omega (a puddle at
rest in the inertial frame feels none of it; the "apparent topography" of rotating shallow
water, Bouchut, Le Sommer & Zeitlin 2004, J. Fluid Mech. 514, 35, as core/spinup.py) plus
gravity g at the inertial angle gamma, normal to the wall. Along the wall the liquid feels
gravity's tangential part -d/dx of the wall's potential P = -g R cos(theta + psi - gamma), the
Euler term -Omega' R and the wall friction. The momentum balance takes the potential of the
surface, -h d/dx (P + G h) (linearised in h), so that at rest the surface is an equipotential:
at Omega = 0 the horizontal chord of a puddle. Where G <= 0 nothing holds
the liquid on the wall: a real liquid falls off; the model keeps it there pressure-less (G is
floored at :data:`G_FLOOR`) and reports the largest share of the liquid in such cells.

Friction: :func:`.shallow_water.friction_rate` (laminar 3 nu / h^2, turbulent Blasius) of the
channel's hydraulic depth h H / (H + 2 h): the outer wall and the two side walls of the chamber's
axial width H (a puddle deeper than the chamber is wide is spun up mostly by its side walls).

Scheme: finite volumes, HLL flux on the hydrostatic reconstruction of Audusse et al. (2004,
SIAM J. Sci. Comput. 25, 2050) written in the potential: at each interface the "bottom" is
max(P_i, P_j), each side's depth (P + G h - max(P_i, P_j)) / G_f with G_f = min(G_i, G_j) (the
same on both sides, so a puddle at rest stays at rest to round-off), clipped to the side's own
depth (positivity under the CFL step). With the larger G as G_f a lump of liquid slower than
the wall choked against a neighbouring film's much larger G and piled up. Second order by the
MUSCL reconstruction of the depth, the surface potential and the velocity (minmod; first order
next to a dry cell) with Audusse et al.'s centred cell term, and Heun's two stages (SSP-RK2) at
half the Courant number; friction implicit in each stage. No partitions (a partitioned ring carries its liquid in its
compartments).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .jit import kernel
from .rhs import profile_eval, profile_segment
from .shallow_water import CFL, DRY_FRACTION, _emit, accept_state, friction_rate, hll_flux

if TYPE_CHECKING:
    import numpy as np

#: Floor of the normal acceleration G, as a fraction of g + Omega^2 R [-]: where G <= 0 the
#: layer is held by nothing and moves pressure-less (module docstring).
G_FLOOR = 1e-9


@kernel
def g_floor(g: float, w: float, R: float) -> float:
    """The floor of G [m/s^2]: :data:`G_FLOOR` of g + w^2 R (g [m/s^2], w [rad/s], R [m]), kept
    above 0 (module docstring)."""
    return G_FLOOR * (g + w * w * R) + 1e-300


@kernel
def rim_fields(h: np.ndarray, q: np.ndarray, theta: np.ndarray, R: float, g: float,
               gdir: float, psi: float, w: float, G: np.ndarray, P: np.ndarray) -> float:
    """Per cell the normal acceleration G [m/s^2] (floored) and the wall's potential P [m^2/s^2]
    (module docstring) of the state h, q [m, m^2/s] at spin w [rad/s] and angle psi [rad];
    theta [rad] the cells' angles, R [m], g [m/s^2] at the inertial angle gdir [rad]. Returns
    the share of the liquid in cells where nothing holds it (G <= 0) [-]."""
    dry = DRY_FRACTION * R
    floor = g_floor(g, w, R)
    tot = 0.0
    loose = 0.0
    for i in range(h.shape[0]):
        c = math.cos(theta[i] + psi - gdir)
        om = w + (q[i] / h[i] / R if h[i] > dry else 0.0)
        gi = om * om * R + g * c
        if h[i] > dry:
            tot += h[i]
            if gi <= 0.0:
                loose += h[i]
        G[i] = gi if gi > floor else floor
        P[i] = -g * R * c
    return loose / tot if tot > 0.0 else 0.0


@kernel
def _minmod(a: float, b: float) -> float:
    """The smaller in magnitude of a and b if they have the same sign, else 0."""
    if a * b <= 0.0:
        return 0.0
    return a if abs(a) < abs(b) else b


@kernel
def rim_faces(h: np.ndarray, q: np.ndarray, theta: np.ndarray, R: float, g: float,
              gdir: float, psi: float, w: float, G: np.ndarray, P: np.ndarray,
              F: np.ndarray) -> None:
    """Each cell's states at its left (-) and right (+) faces for the second-order step
    (module docstring; Audusse et al. 2004, sec. 3): the depth h, the surface potential
    L = P + G h and the velocity v reconstructed linearly with minmod slopes (so the face
    depths are >= 0 and average to h_i), G evaluated at the face with its velocity, and the
    face's potential P~ = L - G h the "bottom" of the interfaces' hydrostatic reconstruction
    (exact, P~ = P, for a puddle at rest); first order (the cell's values) next to a dry cell.
    h, q [m, m^2/s]; theta [rad]; R [m]; g [m/s^2] at gdir [rad]; psi [rad]; w [rad/s]; G, P
    from :func:`rim_fields`. F (10, n) receives h-, h+, v-, v+, G-, G+, P~-, P~+, L-, L+ per
    cell [m, m/s, m/s^2, m^2/s^2]."""
    n = h.shape[0]
    dry = DRY_FRACTION * R
    half = math.pi / n
    floor = g_floor(g, w, R)
    for i in range(n):
        k = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        u = q[i] / h[i] if h[i] > dry else 0.0
        L = P[i] + G[i] * h[i]
        if h[i] <= dry or h[k] <= dry or h[j] <= dry:
            for side in range(2):
                F[side, i] = h[i]
                F[2 + side, i] = u
                F[4 + side, i] = G[i]
                F[6 + side, i] = P[i]
                F[8 + side, i] = L
            continue
        sh = _minmod(h[j] - h[i], h[i] - h[k])
        sl = _minmod(P[j] + G[j] * h[j] - L, L - P[k] - G[k] * h[k])
        su = _minmod(q[j] / h[j] - u, u - q[k] / h[k])
        for side in range(2):
            sg = -0.5 if side == 0 else 0.5
            uf = u + sg * su
            om = w + uf / R
            gf = om * om * R + g * math.cos(theta[i] + 2.0 * sg * half + psi - gdir)
            gf = gf if gf > floor else floor
            hf = h[i] + sg * sh
            lf = L + sg * sl
            F[side, i] = hf
            F[2 + side, i] = uf
            F[4 + side, i] = gf
            F[6 + side, i] = lf - gf * hf
            F[8 + side, i] = lf


@kernel
def rim_step(h: np.ndarray, q: np.ndarray, F: np.ndarray, R: float, H: float, wd: float,
             dt: float, dx: float, nu: float, hn: np.ndarray, qn: np.ndarray, fh: np.ndarray,
             fq: np.ndarray, fqr: np.ndarray) -> None:
    """One forward-Euler stage dt [s] of the module's equations on n periodic cells of width dx
    [m] from the face states F of :func:`rim_faces`: h, q the state [m, m^2/s]; R, H the
    chamber's radius and axial width [m]; wd the spin's rate [rad/s^2]; nu [m^2/s]. At each
    interface the hydrostatic reconstruction (module docstring) of the two face states; in
    each cell the centred term of the second-order hydrostatic scheme (Audusse et al. 2004,
    sec. 3), -(G+ h+^2 - G- h-^2)/2 + (h+ + h-)/2 (L+ - L-), which keeps a puddle at rest
    within the cell and is 0 where the cell is first order. Writes hn, qn; fh, fq, fqr (n,)
    are work arrays: the interface fluxes, the momentum flux with the hydrostatic correction
    as seen from cell i (fq) and from cell i + 1 (fqr)."""
    n = h.shape[0]
    dry = DRY_FRACTION * R
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        hl, ul, gl, pl = F[1, i], F[3, i], F[5, i], F[7, i]
        hr, ur, gr, pr = F[0, j], F[2, j], F[4, j], F[6, j]
        gf = gl if gl < gr else gr
        bs = pl if pl > pr else pr
        hls = min(hl, max(0.0, (pl + gl * hl - bs) / gf))
        hrs = min(hr, max(0.0, (pr + gr * hr - bs) / gf))
        f0, f1 = hll_flux(hls, hls * ul, hrs, hrs * ur, gf, dry)
        fh[i] = f0
        fq[i] = f1 + 0.5 * (gl * hl * hl - gf * hls * hls)
        fqr[i] = f1 + 0.5 * (gr * hr * hr - gf * hrs * hrs)
    for i in range(n):
        k = i - 1 if i > 0 else n - 1
        hi = h[i] - dt / dx * (fh[i] - fh[k])
        centre = -0.5 * (F[5, i] * F[1, i] * F[1, i] - F[4, i] * F[0, i] * F[0, i]) \
            + 0.5 * (F[1, i] + F[0, i]) * (F[9, i] - F[8, i])
        qi = q[i] - dt / dx * (fq[i] - fqr[k] + centre)
        if hi <= dry:
            hn[i] = max(hi, 0.0)
            qn[i] = 0.0
            continue
        qi -= dt * hi * wd * R
        kf = friction_rate(hi * H / (H + 2.0 * hi), qi / hi, nu, R)
        hn[i] = hi
        qn[i] = qi / (1.0 + dt * kf)


#: rim_integrate's stop conditions and statuses [-].
RUN_TO_END = 0
STOP_CLOSED = 1
STOP_BROKEN = 2
#: Statuses of a run that leaves the model: more than :data:`LOOSE_MAX` of the liquid held by
#: nothing, or a layer thicker than the chamber's gap (R - r_i; R in a cylinder).
LEFT_UNHELD = 3
LEFT_TOO_THICK = 4
#: Largest share of the liquid where G <= 0 that the model still takes as on the wall [-] (our
#: criterion: the puddle's thin edges reach past the side walls' horizontal diameter).
LOOSE_MAX = 0.01


@kernel
def _ring_state(h: np.ndarray, theta: np.ndarray, G: np.ndarray, R: float, ring: float,
                centroid: float, floor: float) -> int:
    """Whether the layer h [m] on the cells theta [rad] is a closed ring: 1 if every cell is at
    least ``ring`` [m] thick and held (G [m/s^2] above ``floor``) with its centre of mass
    within ``centroid`` [m] of the axis (R [m]); 0 if it is intact and held but its centre of
    mass is farther out (a film coating the wall beside a puddle); -1 if a cell is thinner or
    not held (a puddle, or a ring broken)."""
    cx = 0.0
    cy = 0.0
    tot = 0.0
    for i in range(h.shape[0]):
        if h[i] < ring or G[i] <= floor:
            return -1
        cx += h[i] * math.cos(theta[i])
        cy += h[i] * math.sin(theta[i])
        tot += h[i]
    return 1 if R * math.sqrt(cx * cx + cy * cy) <= centroid * tot else 0


@kernel
def rim_integrate(h: np.ndarray, q: np.ndarray, theta: np.ndarray, R: float, H: float,
                  g: float, gdir: float, nu: float, ring: float, centroid: float, gap: float,
                  stop: int, t_end: float,
                  tt: np.ndarray, tw: np.ndarray, out_t: np.ndarray, out_h: np.ndarray,
                  out_q: np.ndarray, out_psi: np.ndarray, out_loose: np.ndarray,
                  G: np.ndarray, P: np.ndarray, F: np.ndarray, h1: np.ndarray, q1: np.ndarray,
                  hn: np.ndarray, qn: np.ndarray, fh: np.ndarray, fq: np.ndarray,
                  fqr: np.ndarray) -> tuple[int, int, float, float, float, float]:
    """Integrate from t = 0 (spin angle 0) until t_end [s], or until the event ``stop`` asks
    for (:func:`_ring_state` with ``ring`` [m] and ``centroid`` [m]): :data:`STOP_CLOSED`, the
    liquid closes into a ring; :data:`STOP_BROKEN`, the ring breaks; :data:`RUN_TO_END`, no
    event. It also stops where the state leaves the model (:data:`LEFT_UNHELD`,
    :data:`LEFT_TOO_THICK`: a layer thicker than ``gap`` [m]). The spin from the
    table tt [s], tw [rad/s] (linear; rhs.profile_eval), its angle by the trapezoid rule (exact
    on linear segments). Heun's two stages (SSP-RK2) of :func:`rim_faces` and
    :func:`rim_step`, the step CFL / 2 of the largest |v| + sqrt(G h) of the face states.
    h, q hold the initial state and are overwritten by the final one; out_h, out_q (len(out_t),
    n), out_psi and out_loose (len(out_t),) receive the state, the spin angle [rad] and the
    share of the liquid held by nothing (:func:`rim_fields`) at the sorted output times out_t
    [s]. G, P, h1, q1, hn, qn, fh, fq, fqr (n,) and F (10, n) are work arrays. Returns (status:
    the event, the way it left the model, or 0 at t_end; steps, -1 on a non-finite state; stop
    time [s]; largest share held by nothing over the run [-]; the spin angle [rad] and the
    share held by nothing at the stop)."""
    n = h.shape[0]
    dx = 2.0 * math.pi * R / n
    t = 0.0
    psi = 0.0
    steps = 0
    k = 0
    worst = 0.0
    nout = out_t.shape[0]
    w, wd = profile_eval(t, profile_segment(t, tt), tt, tw)
    while True:
        loose = rim_fields(h, q, theta, R, g, gdir, psi, w, G, P)
        if loose > worst:
            worst = loose
        k1 = _emit(out_t, out_h, out_q, k, t + 1e-12 * max(1.0, t), h, q)
        for r in range(k, k1):
            out_psi[r] = psi
            out_loose[r] = loose
        k = k1
        state = _ring_state(h, theta, G, R, ring, centroid, g_floor(g, w, R))
        if stop == STOP_CLOSED and state == 1 and loose == 0.0:
            return STOP_CLOSED, steps, t, worst, psi, loose
        if stop == STOP_BROKEN and (state < 0 or loose > 0.0):
            return STOP_BROKEN, steps, t, worst, psi, loose
        if loose > LOOSE_MAX:
            return LEFT_UNHELD, steps, t, worst, psi, loose
        deepest = 0.0
        for i in range(n):
            deepest = max(deepest, h[i])
        if deepest > gap:
            return LEFT_TOO_THICK, steps, t, worst, psi, loose
        if t >= t_end:
            return RUN_TO_END, steps, t, worst, psi, loose
        rim_faces(h, q, theta, R, g, gdir, psi, w, G, P, F)
        sp = 0.0
        for i in range(n):
            for side in range(2):
                s = abs(F[2 + side, i]) + math.sqrt(F[4 + side, i] * F[side, i])
                if s > sp:
                    sp = s
        dt = t_end - t
        if sp > 0.0 and 0.5 * CFL * dx / sp < dt:
            dt = 0.5 * CFL * dx / sp
        if k < nout and out_t[k] - t < dt and out_t[k] > t:
            dt = out_t[k] - t
        rim_step(h, q, F, R, H, wd, dt, dx, nu, h1, q1, fh, fq, fqr)
        t1 = t + dt
        w1, wd1 = profile_eval(t1, profile_segment(t1, tt), tt, tw)
        psi1 = psi + 0.5 * (w + w1) * dt
        rim_fields(h1, q1, theta, R, g, gdir, psi1, w1, G, P)
        rim_faces(h1, q1, theta, R, g, gdir, psi1, w1, G, P, F)
        rim_step(h1, q1, F, R, H, wd1, dt, dx, nu, hn, qn, fh, fq, fqr)
        for i in range(n):
            hn[i] = 0.5 * (h[i] + hn[i])
            qn[i] = 0.5 * (q[i] + qn[i])
        steps += 1
        if not accept_state(h, q, hn, qn):
            return RUN_TO_END, -1, t, worst, psi, loose
        w, wd, psi, t = w1, wd1, psi1, t1
