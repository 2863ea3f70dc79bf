"""Every integer code of an outcome, in one place.

Three code spaces, each with named constants and no value meaning two things in one space:

1. **Kernel status** (``status`` in results): what an integration returned. Kernels never
   raise; they return one of these. ``OK`` is an advance call that reached its end time;
   a classified trajectory returns ``CONVERGED`` (the same value: nothing went wrong).
2. **Label codes** (``label`` in results, ``code`` in bifurcations): what a trajectory is.
   Catalogue solutions take 0, 1, ... in catalogue order; the others are fixed by kind and
   period, so every chunk and every worker assigns the same code to the same solution
   without coordination. Negative codes are the outcomes that are not a periodic orbit,
   plus two bookkeeping values that never appear in a complete result (``PENDING``,
   ``MIXED_CELL``).
3. **Classification method** (``captured`` in results): how a converged trajectory was
   recognised.

``label_code_of_status`` is the one mapping from a kernel status that is not
``CONVERGED`` to a label code; ``outcome``/``message`` say what a status means to a user.
"""

# ------------------------------------------------------------------ 1. kernel status
OK = 0
CONVERGED = 0
UNRESOLVED = 1
DIVERGED = 2
STEP_BUDGET = 3
TOO_MANY_SWITCHES = 4
STEP_UNDERFLOW = 5

NO_ORBIT = -1  # index of the known orbit that captured a trajectory: none

# ------------------------------------------------------------------ 2. label codes
UNRESOLVED_LABEL = -2  # no period within max_periods, or a budget exhausted
DIVERGED_LABEL = -3  # non-finite, beyond the divergence bound, or step underflow
MIXED_CELL = -4  # a recurrence cell visited on the way to different labels (cells only)
PENDING = -9  # not computed yet (never in a complete result)
CATALOGUE_WIDTH = 1000  # catalogue solutions 0 .. 999 take their index as code, and
EXTENDED_CATALOGUE_BASE = 10_000_000  # the following ones (many bodies' combinations)
# this base + index (analysis.labels.catalogue_code; below 2**31 for 2e9 solutions)
IMPACTING_BASE = 1000  # impacting P{p} -> 1000 + p (the first impacting orbit of period p)
NUMBERED_IMPACTING_BASE = 1_000_000  # impacting P{p}^{m}, m = 2 .. 999: this base
# + 1000 m + p (analysis.labels.impacting_code; distinct impacting orbits of one period)
UNMATCHED_BASE = 2000  # unmatched P{p} -> 2000 + p (non-impacting, in no catalogue)
# Attractors that are not periodic, found by the second stage (analysis/nonperiodic.py):
# base + n names attractor A{n} (n = 1 .. 999, numbered over the whole result in the order
# of their first trajectory's flat index, so every worker count and executor agrees).
CHAOTIC_BASE = 3000  # chaotic A{n}
IMPACTING_CHAOTIC_BASE = 4000  # impacting chaotic A{n}
QUASI_PERIODIC_BASE = 5000  # quasi-periodic A{n}
IMPACTING_QUASI_PERIODIC_BASE = 6000  # impacting quasi-periodic A{n}
NONPERIODIC_BASES = {"chaotic": CHAOTIC_BASE, "impacting chaotic": IMPACTING_CHAOTIC_BASE,
                     "quasi-periodic": QUASI_PERIODIC_BASE,
                     "impacting quasi-periodic": IMPACTING_QUASI_PERIODIC_BASE}
BASE_WIDTH = 1000  # every base above holds codes base + 1 .. base + 999

# ------------------------------------------------------------------ 3. classification method
BY_OWN_REPEAT = 0  # its own section points repeated
BY_KNOWN_ORBIT = 1  # it came within the capture radius of a known stable orbit
BY_CELLS = 2  # recurrence cells of earlier trajectories named it
BY_SECTION = 3  # the second stage followed it on the section (analysis/section_follow.py)
CLASSIFIED_BY = {BY_OWN_REPEAT: "own repeat", BY_KNOWN_ORBIT: "known orbit",
                 BY_CELLS: "recurrence cells", BY_SECTION: "followed on the section"}

# status -> (outcome class, message telling the user what to change)
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
_LABEL_OF_OUTCOME = {"unresolved": UNRESOLVED_LABEL, "diverged": DIVERGED_LABEL}


def outcome(status: int) -> str:
    """The outcome class of a status code: converged, unresolved or diverged."""
    return STATUS_TABLE[int(status)][0]


def message(status: int) -> str:
    return STATUS_TABLE[int(status)][1]


def label_code_of_status(status: int) -> int:
    """The label code of a trajectory that did not converge (``UNRESOLVED_LABEL`` or
    ``DIVERGED_LABEL``); a converged one is labelled by its orbit, not its status."""
    if int(status) == CONVERGED:
        raise ValueError("a converged trajectory is labelled by its orbit (label_orbit)")
    return _LABEL_OF_OUTCOME[outcome(status)]
