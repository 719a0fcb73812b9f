"""Index layout of the flat arrays passed to the numba kernels (plain SI floats, no units).

State vector y (length 2*nq, nq = NR + N + 1):
    y[0] = u, y[1] = v               rotor displacement in the rotor-fixed frame [m] (the NR = 2
                                      rotor coordinates ahead of the balls)
    y[NR + i] = alpha_i               ball angle from the unbalance direction [rad]
    y[nq - 1] = psi                   spin angle [rad]
    y[nq + j]                         time derivative of y[j]
Scalar parameter vector P: indices below. Ball table B[i, :]: columns below.
"""
from __future__ import annotations

import enum

# --- the generalised coordinates q (y = (q, q')) --------------------------------------------
NR = 2            # rotor coordinates ahead of the balls: u, v [m]; ball i is q[NR + i],
                  # psi is q[nq - 1]

# --- scalar parameters P ------------------------------------------------------------------
P_MT = 0          # total translating mass M + sum(m_i) [kg]
P_KX = 1          # stiffness x [N/m]
P_KY = 2          # stiffness y [N/m]
P_CX = 3          # damping x [N*s/m]
P_CY = 4          # damping y [N*s/m]
P_FDRY = 5        # dry friction force per damper [N]
P_GDRY = 6        # damper inclination to x [rad]
P_VDRY = 7        # regularisation speed of the damper friction [m/s]
P_R = 8           # race radius [m]
P_RHO = 9         # race eccentricity [m]
P_BETA = 10       # race eccentricity angle [rad]
P_G = 11          # gravity [m/s^2]
P_GDIR = 12       # direction of gravity in the (x, y) plane [rad]
P_BZ = 13         # spin inertia [kg*m^2]
P_CPHI = 14       # spin viscous loss [N*m*s/rad]
P_SPIN = 15       # 0 prescribed, 1 motor-driven
P_LAW = 16        # motor law: 0 constant, 1 linear, 2 harmonic
P_T0 = 17         # motor torque [N*m]
P_WF = 18         # motor final speed [rad/s]
P_WHOLD = 19      # speed at which the controller takes over [rad/s]
P_BAX = 20        # base amplitude x [m]
P_BAY = 21        # base amplitude y [m]
P_BW = 22         # base frequency [rad/s]
P_BPX = 23        # base phase x [rad]
P_BPY = 24        # base phase y [rad]
P_FLAW = 25       # friction law: 0 exact stick-slip, 1 tanh, 2 stick-slip + tanh creep
P_VSAT = 26       # tanh saturation speed [rad/s]
P_NMODEL = 27     # normal force: 0 ball (centrifugal of the ball + gravity), 1 drum (m R psi_dot^2)
P_DELTA = 28      # contact angle between neighbouring balls [rad]
P_WNOM = 29       # nominal speed for the grade [rad/s]
P_MROT = 30       # rotor mass M (without balls) [kg]
P_HOLDS = 31      # 1: stuck constant-speed holds may be solved in closed form (hold.py)
P_ISO = 32        # 1: isotropic linear suspension force in the rotor frame (rhs.py)
P_SYM = 33        # 1: rotationally symmetric: max|x| = max|y| = max|w| (integrate.py)
P_RAMPS = 34      # 1: stuck linear speed ramps may be solved without stepping (ramp.py)
P_LQX = 35        # a liquid beside the balls (core/hybrid.py): its first moment U about the
P_LQY = 36        #   chamber centre, rotor frame [kg*m], and its rate U' [kg*m/s], frozen over
P_LQDX = 37       #   a coupling step; all 0 without a liquid
P_LQDY = 38
P_LQI = 39        #   with a motor-driven spin: the films' second moment about the chamber
P_LQT = 40        #   centre [kg*m^2] and their torque on the spin [N*m], held likewise
P_ETD = 41        # 1: phases where a ball slips may be jumped by ETDRK4-B (core/expo.py)
P_HC = 42         # largest DOPRI5 step while two balls touch [s] (0: none): pack.contact_step / w_c
N_P = 43
# P_HOLDS, P_RAMPS, P_ETD, P_ISO and P_SYM are derived from the model in one place only:
# autobalance.simulate.pack.fast_paths. The kernels read them and decide nothing themselves.

# --- per-ball table B ---------------------------------------------------------------------
B_M = 0           # mass [kg]
B_I = 1           # rolling inertia [kg*m^2]
B_RR = 2          # R / r [-]
B_D = 3           # viscous damping [N*m*s/rad]
B_MU = 4          # kinetic rolling-resistance coefficient [-]
B_MUS = 5         # static coefficient [-]
B_KC = 6          # contact stiffness with the next ball [N*m/rad]
B_CC = 7          # contact damping with the next ball [N*m*s/rad]
N_B = 8

# --- statistics returned per run ----------------------------------------------------------
S_STATUS = 0      # see STATUS below
S_STEPS = 1
S_REJECTED = 2
S_EVENTS = 3
S_RHS = 4
S_TFINAL = 5
S_AMAX = 6        # max rotor amplitude |w| [m]
S_TAMAX = 7
S_XMAX = 8        # max |x| [m]
S_YMAX = 9        # max |y| [m]
S_THOLD = 10      # time the motor-driven spin reached the hold speed [s] (-1 never)
S_IMPACTS = 11    # number of ball-ball contacts started
S_HOLDS = 12      # constant-speed holds solved in closed form (core/hold.py)
S_RAMPS = 13      # stuck speed ramps (or parts of them) solved without stepping (core/ramp.py)
N_S = 14

# --- the integrator's carried state at a pause (core/integrate.integrate_span) ---------------
# A run paused at a profile knot continues from these, bit for bit as if it had not paused.
C_WHERE = 0       # 0: start from y at t = 0; 1-4: paused on arriving at a knot by a ramp jump (1),
#                   a closed-form hold (2), a hold until its breakaway (3) or a step (4)
C_T = 1           # time [s]
C_H = 2           # next trial step [s]
C_EN = 3          # error norm of the last step [-]
C_ENOLD = 4       # previous error norm of the PI controller [-]
C_HACC = 5        # accepted length of the last step [s]
C_NSTEPS = 6
C_NREJ = 7
C_NEV = 8
C_STALL = 9
C_NEXT = 10       # step count at which the next closed-form jump is tried
C_NHOLD = 11
C_NRAMP = 12
C_NRHS = 13
C_KOUT = 14       # outputs filled
C_SPIN0 = 15      # spin mode (0 prescribed, 1 motor, 2 motor at its hold speed)
C_SPIN1 = 16      # the hold speed of mode 2 [rad/s]
C_EVK = 17        # the event of the step that arrived at the knot (-1 none)
C_EVI = 18        # its ball; at a hold's end (C_WHERE = 3) the ball that breaks away there (< 0 none)
C_NETD = 19       # time before which no slip jump is tried [s] (core/expo.py)
C_HETD = 20       # the slip jump's step [s]
N_C = 21
# then per ball: stuck (N), slip sign (N), in contact (N), stick margin (N); the constraint
# forces lam (3N + 1); the derivative f0 at the pause (2 nq)


def carry_size(n_balls: int) -> int:
    """Length of the carried state of a paused run of N balls (C_* above) [-]."""
    return N_C + 7 * int(n_balls) + 1 + 2 * n_q(n_balls)



class RunStatus(enum.IntEnum):
    """The one status of a run: the code the kernel writes to stats[S_STATUS], the name results
    and sweeps report, and the sentence a user reads. UNKNOWN (9) marks a code no kernel writes."""
    OK = 0
    MAX_STEPS = 1
    STEP_SIZE_UNDERFLOW = 2
    NON_FINITE = 3
    RUNNING = 4
    OUTSIDE_MODEL = 5
    UNKNOWN = 9

    @property
    def label(self) -> str:
        """snake_case name ("ok", "max_steps", ...)."""
        return self.name.lower()

    @property
    def message(self) -> str:
        """What the status means, for messages to the user."""
        return _MESSAGES[self]

    @classmethod
    def of(cls, code: int | float) -> "RunStatus":
        """The status of a kernel code (UNKNOWN for any other value)."""
        try:
            return cls(int(code))
        except ValueError:
            return cls.UNKNOWN

    @classmethod
    def from_label(cls, label: str) -> "RunStatus":
        """The status of a snake_case name (UNKNOWN for any other name)."""
        return cls.__members__.get(str(label).upper(), cls.UNKNOWN)


_MESSAGES = {
    RunStatus.OK: "completed",
    RunStatus.MAX_STEPS: "step budget exhausted before the end time (options.max_steps)",
    RunStatus.STEP_SIZE_UNDERFLOW: "step size underflow (stiff or chattering dynamics)",
    RunStatus.NON_FINITE: "the state became non-finite (NaN/inf)",
    RunStatus.RUNNING: "running",
    RunStatus.OUTSIDE_MODEL: "the run left the model's domain (the liquid film reached the "
                             "chamber's inner wall)",
    RunStatus.UNKNOWN: "unknown",
}

#: kernel code -> name (the statuses a kernel writes)
STATUS = {int(s): s.label for s in RunStatus if s is not RunStatus.UNKNOWN}


# --- the state vector (the one Python-side description; the kernels index it the same way) ---
def n_q(n_balls: int) -> int:
    """Number of generalised coordinates nq = NR + N + 1 (u, v, alpha_1..N, psi) [-]."""
    return NR + int(n_balls) + 1


def state_size(n_balls: int) -> int:
    """Length 2 nq of the state vector y (coordinates then their rates) [-]."""
    return 2 * n_q(n_balls)


def psi_index(n_balls: int) -> int:
    """Index of the spin angle psi [rad] in y."""
    return n_q(n_balls) - 1


def speed_index(n_balls: int) -> int:
    """Index of the spin speed psi_dot [rad/s] in y."""
    return 2 * n_q(n_balls) - 1


def rate_index(j: int, n_balls: int) -> int:
    """Index of the time derivative of y[j] in y."""
    return n_q(n_balls) + j


def alpha_slice(n_balls: int) -> slice:
    """Slice of the ball angles alpha_i [rad] in y."""
    return slice(NR, NR + n_balls)


def alpha_dot_slice(n_balls: int) -> slice:
    """Slice of the ball angular rates alpha_dot_i [rad/s] in y."""
    return slice(n_q(n_balls) + NR, n_q(n_balls) + NR + n_balls)
