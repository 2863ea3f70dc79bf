"""Status codes returned by the kernels, and what they mean to a user.

Kernels never raise; they return one of these codes. ``OK`` is what an advance call
returns when it reached its end time; a classified trajectory returns ``CONVERGED``.
"""

OK = 0
CONVERGED = 0
UNRESOLVED = 1
DIVERGED = 2
STEP_BUDGET = 3
TOO_MANY_SWITCHES = 4
STEP_UNDERFLOW = 5

# code -> (outcome class, message telling the user what to change)
STATUS_TABLE = {
    CONVERGED: ("converged", "converged to a periodic orbit of the stroboscopic map"),
    UNRESOLVED: (
        "unresolved",
        "no period <= max_orbit_period found within max_periods "
        "(chaotic, quasi-periodic or slow transient: raise `max_periods`)",
    ),
    DIVERGED: (
        "diverged",
        "state became non-finite or exceeded `divergence_bound` "
        "(unstable step: use a finer `steps_per_period`, method 'dopri5', or 'stiff' for "
        "hard stops)",
    ),
    STEP_BUDGET: (
        "unresolved",
        "step budget of one forcing period exhausted (stiff contact? use method 'stiff' or "
        "raise `max_steps_per_period`)",
    ),
    TOO_MANY_SWITCHES: (
        "unresolved",
        "too many mode switches in one forcing period (chattering at a switching surface)",
    ),
    STEP_UNDERFLOW: (
        "diverged",
        "adaptive step fell below its floor: the error estimate cannot be met",
    ),
}

OUTCOMES = ("converged", "unresolved", "diverged")


def outcome(code: int) -> str:
    """The outcome class of a status code: converged, unresolved or diverged."""
    return STATUS_TABLE[int(code)][0]


def message(code: int) -> str:
    return STATUS_TABLE[int(code)][1]
