"""Bounds on every count and every number a scene may give (issue 20).

Each keeps an allocation, a loop or a float the kernels see in range, and is checked with
Python integers before anything is allocated; each error message states its bound.
"""

from __future__ import annotations

from typing import Any

from .reader import ConfigError

MAX_GRID_VALUES = 1_000_000  # values of one grid axis, and grid points in all
MAX_INITIAL_CONDITIONS = 10_000_000  # initial conditions of a sweep (plane or random)
MAX_TRAJECTORIES = 10_000_000  # grid points x initial conditions of one sweep (or design)
MAX_SEED = 2**63 - 1  # seeds are stored as int64 attributes
MAX_T0_PERIODS = 1_000_000  # a start time is at most this many forcing periods
MAX_PARAMETER = 1e9  # |value| of any model or coupling parameter
W_RANGE = (1e-3, 1e3)  # forcing frequency: the period 2 pi / w stays representable
MAX_TRAJECTORY_SAMPLES = 10_000_000  # periods x samples_per_period of a trajectory
MAX_NESTING = 8  # tables and arrays inside each other (scenes need 4)


def t0_problem(t0: float, period: float) -> str | None:
    """Past ~1e18 periods the kernels' period count overflows int64; far less is useful."""
    if abs(t0) > MAX_T0_PERIODS * period:
        return f"must be at most {MAX_T0_PERIODS} forcing periods ({MAX_T0_PERIODS}*T)"
    return None


def parameter_problem(name: str, value: float) -> str | None:
    """The range every parameter keeps (beyond the model's own checks)."""
    if name == "w" and not W_RANGE[0] <= value <= W_RANGE[1]:
        return f"must be in [{W_RANGE[0]:g}, {W_RANGE[1]:g}]"
    if abs(value) > MAX_PARAMETER:
        return f"must be within +-{MAX_PARAMETER:g}"
    return None


def check_nesting(source: str, doc: dict) -> None:
    """Refuse tables and arrays nested deeper than MAX_NESTING (iteratively: no recursion)
    and integers beyond 64 bits."""
    stack: list[tuple[Any, str, int]] = [(v, f"[{k}]", 1) for k, v in doc.items()]
    while stack:
        value, where, depth = stack.pop()
        if depth > MAX_NESTING:
            raise ConfigError(f"{source}: {where[:80]}: tables or arrays nested more than "
                              f"{MAX_NESTING} levels deep")
        if isinstance(value, dict):
            stack.extend((v, f"{where} {k}" if depth == 1 else f"{where}.{k}", depth + 1)
                         for k, v in value.items())
        elif isinstance(value, list):
            stack.extend((v, f"{where}[{i}]", depth + 1) for i, v in enumerate(value))
        elif isinstance(value, int) and not -2**63 <= value < 2**63:
            # TOML integers are 64-bit; tomllib reads any size, and float() of it overflows
            raise ConfigError(f"{source}: {where[:80]}: an integer of {len(str(abs(value)))}"
                              " digits is beyond the 64-bit range of TOML integers")


def design_trajectories(analysis, n: int) -> int:
    """Upper bound of the trajectories a design runs (see ``analysis.design``)."""
    screen = min(analysis.screen_n, n)
    robust = min(analysis.robust_n or n, n)
    perturbed = 2 * analysis.perturbation_steps * len(analysis.bounds)
    return analysis.candidates * screen + analysis.refine * n + perturbed * robust + 2 * n
