"""Reference runs for the tests: the kernel with its fast paths turned off.

The kernel takes closed-form holds, stuck ramps without stepping and slip jumps wherever
``autobalance.simulate.pack.fast_paths`` says their conditions hold; everywhere else it steps
by DOPRI5 (the general path). ``stepped`` runs the same machine with some of those flags
cleared in the packed parameters, so the phase they would jump is stepped by DOPRI5: the
general path is the oracle of each fast path. This is not an option of the package.
"""
from __future__ import annotations

from autobalance.core.layout import P_ETD, P_HOLDS, P_RAMPS
from autobalance.models import InitialState, SimOptions
from autobalance.simulate.pack import run_inputs
from autobalance.simulate.run import run_packed


def stepped(system, spin, *, initial=None, options=None, holds=True, ramps=True,
            slip_jumps=True, throw=True):
    """One run of ``system`` through ``spin`` with the fast paths named False stepped instead.

    Parameters
    ----------
    holds, ramps, slip_jumps : bool
        Keep the closed-form holds / the stuck ramps without stepping / the slip jumps where
        they apply (False steps them by DOPRI5). No holds implies no ramps and no ramps no slip
        jumps (fast_paths derives the jumps' conditions from the ramps' and theirs from the
        holds').
    """
    initial = initial or InitialState()
    options = options or SimOptions()
    r = run_inputs(system, spin, initial, options)
    paths_off(r.P, holds=holds, ramps=ramps, slip_jumps=slip_jumps)
    return run_packed(system, spin, initial, options, r, throw)


def paths_off(P, *, holds=True, ramps=True, slip_jumps=True):
    """Clear, in the packed parameters P (in place), the flags of the fast paths named False
    (see :func:`stepped`); returns P."""
    if not holds:
        P[P_HOLDS] = P[P_RAMPS] = P[P_ETD] = 0.0
    if not ramps:
        P[P_RAMPS] = P[P_ETD] = 0.0
    if not slip_jumps:
        P[P_ETD] = 0.0
    return P
