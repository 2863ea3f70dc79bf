"""Index constants of the small arrays the kernels share (numba treats them as constants).

``opts`` (float64): integrator options, built once per scene by ``engine.integrator_options``.
``istate`` (int64) and ``fstate`` (float64): the integrator's running state and counters,
carried across calls so that a trajectory can be advanced section by section.
"""

# opts
RTOL = 0
ATOL = 1
H_FIXED = 2  # rk4: the step T / steps_per_period
LOCATE = 3  # 1.0: locate every switch and restart there; 0.0: the plain (paper) scheme
H_MAX = 4  # adaptive methods: largest step
MAX_STEPS = 5  # step budget of one advance call (one forcing period)
BOUND = 6  # |state| beyond this is "diverged"
SAMPLE_DT = 7  # > 0: write dense samples every SAMPLE_DT
SAMPLE_T0 = 8  # time of sample 0
MAX_SWITCHES = 9  # switch budget of one advance call (chattering guard)
N_OPTS = 10

# istate
MODE = 0
N_STEPS = 1
N_REJECTED = 2
N_RHS = 3
N_SWITCHES = 4
N_CONTACTS = 5
N_SAMPLES = 6
N_STIFF_STEPS = 7  # accepted steps of the stiff method (rodas4, alone or inside auto)
N_METHOD_SWITCHES = 8  # auto: changes between the explicit and the stiff method
N_COUNTERS = 9  # istate[:N_COUNTERS] are what engine.COUNTER_NAMES names (mode, counters)
# the stepper's running state, carried across calls like the mode
VARIANT = 9  # which kind of step the method takes now (see ``driver``; 0 for most)
AUTO_STIFF = VARIANT  # auto (kernels/auto.py): 1 while the stiff method runs
AUTO_STIFF_MODES = 10  # bit m set: a phase in mode m starts with the stiff method
AUTO_HITS = 11  # Hairer's stiffness test: recent steps that looked stability bound
AUTO_CALM = 12  # ... and steps in a row that did not
AUTO_COOLDOWN = 13  # stiffness tests still to skip after a return to the explicit method
# rigid impacts (kernels/impacts.py; 0 without rigid stops)
N_IMPACTS = 14  # impacts (velocity resets)
N_CHATTERS = 15  # chatter sequences ended by their accumulation point
N_STICKS = 16  # sticking phases begun
N_ISTATE = 17

# fstate
H = 0  # the step the adaptive controller proposes next
MAX_G = 1  # running max of the contact function x1 - x2 - d (reset per period by callers)
T_SWITCH = 2  # the time of the switch after which an advance call stopped on its switch
#               budget (TOO_MANY_SWITCHES); ``opts[MAX_SWITCHES] = 0`` stops at every switch
T_STUCK = 3  # time spent stuck on rigid stops (kernels/impacts.py)
N_FSTATE = 4

# rows of the work array (shape (work_rows(dim), dim)); one array holds every method's
# scratch, so the driver passes it alone
K0 = 0  # explicit stages K0..K6 use rows 0..6
YTMP = 7
YNEW = 8  # the step's solution (every method)
M0 = 9  # monomial coefficients of the step's dense output, rows 9..13
# Rodas4 (kernels/rosenbrock.py)
F0 = 14  # f(t, y) at the step's start
DFDT = 15  # df/dt there
YT = 16  # a stage's state
FT = 17  # a stage's right-hand side
U0 = 18  # stage increments U_1..U_6, rows 18..23
PIV = 24  # LU pivot rows (as floats: exact for any dimension that fits in memory)
JAC = 25  # the Jacobian (dim rows), then its LU factors (dim rows), then a squaring
WORK_ROWS = JAC  # scratch of auto's spectral bound (dim rows): MATRICES blocks of dim rows
MATRICES = 3


def work_rows(dim):
    """Rows of the work array for a state of ``dim`` variables."""
    return WORK_ROWS + MATRICES * dim
