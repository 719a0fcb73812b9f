"""Index layout of the flat arrays passed to the numba kernels (plain SI floats, no units).

State vector y (length 2*nq, nq = N + 3):
    y[0] = u, y[1] = v               rotor displacement in the rotor-fixed frame [m]
    y[2 + i] = alpha_i                ball angle from the unbalance direction [rad]
    y[nq - 1] = psi                   spin angle [rad]
    y[nq + j]                         time derivative of y[j]
Scalar parameter vector P: indices below. Ball table B[i, :]: columns below.
"""

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
P_FLAW = 25       # friction law: 0 exact stick-slip, 1 tanh
P_VSAT = 26       # tanh saturation speed [rad/s]
P_NMODEL = 27     # normal force: 0 ball (centrifugal of the ball + gravity), 1 drum (m R psi_dot^2)
P_DELTA = 28      # contact angle between neighbouring balls [rad]
P_WNOM = 29       # nominal speed for the grade [rad/s]
P_MROT = 30       # rotor mass M (without balls) [kg]
P_HOLDS = 31      # 1: solve stuck constant-speed holds in closed form (hold.py)
N_P = 32

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
N_S = 13

STATUS = {0: "ok", 1: "max_steps", 2: "step_size_underflow", 3: "non_finite", 4: "running"}
