"""Error against run time: rerun (part of) a scene at tighter settings and compare.

Tightened settings: rtol and atol / 100, convergence_tol / 10, twice the period budget,
4x the RK4 steps, no capture near known orbits, no recurrence cells. Sweeps compare the
labels of a random subset of trajectories (after a sweep, its stored labels against the
tightened rerun); the share that changes is the estimated label error (the default
verification of every sweep, ``sweep.verification``, is built on it). Critical-distance
scenes compare d_crit at a subset of phases; bifurcation scenes compare destruction
points. Each report carries both wall times and their ratio.
"""

from __future__ import annotations

from ..config import Scene
from . import KINDS, analysis_kinds


def check_scene(scene: Scene, sample: int = 200, seed: int = 0, result=None) -> dict:
    """A report comparing the scene's settings with tightened ones on a random subset.

    ``result``: the sweep's own finished dataset; its stored labels then stand for the
    scene's settings (so that what depends on the order of a run, recurrence cells, is
    checked as it ran) and its wall time per trajectory for their cost.
    """
    kind = KINDS[scene.analysis.kind]
    if kind.check is None:
        covered = ", ".join(k for k in analysis_kinds() if KINDS[k].check is not None)
        raise ValueError(f"check covers the kinds {covered}, not {kind.name!r}")
    return kind.check(scene, sample, seed, result)


def over_limit(report: dict, fail_over: float | None) -> str | None:
    """Why the report fails ``--fail-over`` (None: it passes): the label change share of a
    sweep, or the largest change of d_crit / a destruction point, above ``fail_over``."""
    if fail_over is None:
        return None
    if report["kind"] == "labels":
        value, what = report["changed_share"], "label change share"
    else:
        value, what = report["max_change"], f"largest {report['kind']} change"
    if report.get("appeared_or_vanished"):
        return f"{report['appeared_or_vanished']} destruction points appeared or vanished"
    return f"{what} {value:.4g} > --fail-over {fail_over:g}" if value > fail_over else None


def check_text(report: dict) -> str:
    """The report of :func:`check_scene` as one line (``softimpact check``)."""
    head = (f"check ({report['kind']}, {report['sample']} sampled, tightened settings: "
            f"rtol and atol / 100, convergence_tol / 10, 2x periods, 4x RK4 steps): ")
    if report["kind"] == "labels":
        body = (f"{report['changed']} labels changed ({100 * report['changed_share']:.2f}%)"
                + (f" [{', '.join(f'{k}: {v}' for k, v in report['changes'].items())}]"
                   if report["changes"] else ""))
    else:
        body = f"largest change {report['max_change']:.3g}"
    return (head + body + f"; wall {report['wall_s']:.2f} s vs {report['tight_wall_s']:.2f} s "
            f"tightened (x{report['wall_ratio']:.2f})")
