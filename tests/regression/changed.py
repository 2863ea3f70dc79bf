"""Did only formerly unresolved trajectories change? The check a new classification stage
must pass against the stored references before they are rewritten. And ``--impacting``:
did only impacting orbits split (``analysis/impacting.py``: the second impacting orbit of
a period at a point is ``impacting P{p}^2`` now, one label with the first before)?

``python -m tests.regression.changed [--impacting] NAME ...`` reruns the named reference scenes (as
``reference compare`` does) and reports, per scene, either "identical", "only formerly
unresolved entries changed (...)" or what else changed. A scene that passes is then
rewritten with ``python -m tests.regression.reference write NAME``. Sweep results: every
per-trajectory variable may differ only where the stored label was ``unresolved``, and
every stored label's code, name and attractor points are kept. Design results: per
point, every group's count is kept except ``unresolved``, whose loss equals what the
groups new to the result gained, and the two sums ("impacting (all)", "non-impacting
(sum)"), which gain what their new members gained.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

from softimpact_cli.analysis.impacting import impacting_number
from softimpact_cli.analysis.labels import parse_label
from softimpact_cli.kernels.codes import UNRESOLVED_LABEL
from tests.regression.reference import SCENES, arrays_of, differences, load_stored, run_scene

LABEL_TABLE = ("label_code", "label_name", "label_latex", "label_index")


def _sweep_changes(stored: dict, now: dict) -> list[str]:
    was = stored["label"] == UNRESOLVED_LABEL
    problems = []
    shape = stored["label"].shape
    for name in sorted(set(stored) & set(now)):
        a, b = stored[name], now[name]
        if name in LABEL_TABLE or name == "attractor_points":
            continue
        if name == "orbit_point" and np.array_equal(b[: a.size], a):
            continue  # more points per orbit: an attractor's cloud is longer
        if a.shape == shape and b.shape == shape:
            moved = ~((a == b) | (np.isnan(a) & np.isnan(b)) if a.dtype.kind == "f"
                      else a == b)
            if (moved & ~was).any():
                problems.append(f"{name}: {int((moved & ~was).sum())} values changed where "
                                "the label was not unresolved")
        elif differences({name: a}, {name: b}):
            problems.append(f"{name}: changed")
    old = dict(zip(stored["label_code"].tolist(), stored["label_name"].tolist(), strict=True))
    new = dict(zip(now["label_code"].tolist(), now["label_name"].tolist(), strict=True))
    for code, name in old.items():
        if code != UNRESOLVED_LABEL and new.get(code) != name:
            problems.append(f"label {code} ({name}) is {new.get(code)!r} now")
        if code in new and code != UNRESOLVED_LABEL:
            i, j = old_index(stored, code), old_index(now, code)
            before, after = stored["attractor_points"][i], now["attractor_points"][j]
            q = before.shape[-2]  # orbit points; the rest of `after` is NaN padding
            if not (np.array_equal(before, after[..., :q, :], equal_nan=True)
                    and np.isnan(after[..., q:, :]).all()):
                problems.append(f"attractor_points of {name} changed")
    return problems


def old_index(arrays: dict, code: int) -> int:
    return int(np.flatnonzero(arrays["label_code"] == code)[0])


def _design_changes(stored: dict, now: dict) -> list[str]:
    old, new = list(stored["group"]), list(now["group"])
    problems = [f"{name}: changed" for name in sorted(set(stored) & set(now))
                if name not in ("group", "count", "share", "ci_low", "ci_high")
                and differences({name: stored[name]}, {name: now[name]})]
    fresh = [g for g in new if g not in old]  # solutions met only now (none is a sum)
    into = {"impacting (all)": [g for g in fresh if g.startswith("impacting")],
            "non-impacting (sum)": [g for g in fresh if not g.startswith("impacting")
                                    and parse_label(g).kind not in ("unresolved",
                                                                    "diverged")]}

    def counts(arrays, groups, g):
        return arrays["count"][:, groups.index(g)]

    for g in old:
        if g == "unresolved":
            continue
        if g not in new:
            problems.append(f"group {g} vanished")
            continue
        expected = counts(stored, old, g) + sum((counts(now, new, f) for f in into.get(g, ())),
                                                start=0)
        if not np.array_equal(counts(now, new, g), expected):
            problems.append(f"group {g}: counts changed")
    lost = counts(stored, old, "unresolved") if "unresolved" in old else 0
    left = counts(now, new, "unresolved") if "unresolved" in new else 0
    gained = sum((counts(now, new, f) for f in fresh if f != "unresolved"), start=0)
    if not np.array_equal(np.asarray(lost - left), np.asarray(gained)):
        problems.append("the new groups' counts are not the unresolved ones lost")
    return problems


def formerly_unresolved_only(stored: dict, now: dict) -> list[str]:
    """What changed beyond formerly unresolved entries (empty when nothing else did)."""
    if "label" in stored and "label" in now and stored["label"].shape == now["label"].shape:
        return _sweep_changes(stored, now)
    if "group" in stored and "count" in stored and "group" in now:
        return _design_changes(stored, now)
    return [f"{p} (not a sweep or design result)" for p in differences(stored, now)]


def impacting_split_only(stored: dict, now: dict) -> list[str]:
    """What changed beyond impacting orbits split into numbered ones (empty when nothing
    else did). Sweeps: a label may change only from ``impacting P{p}`` to ``impacting
    P{p}^m`` (m >= 2, same p); the other per-trajectory variables only where the stored
    label is impacting (a trajectory the cells named takes its own orbit's penetration);
    every stored code keeps its name and attractor points; other variables are listed.
    Designs: a new group ``impacting P{p}^m`` gains only what ``impacting P{p}`` lost."""
    if "label" in stored and "label" in now and stored["label"].shape == now["label"].shape:
        return _sweep_split(stored, now)
    if "group" in stored and "count" in stored and "group" in now:
        return _design_split(stored, now)
    return [f"{p} (not a sweep or design result)" for p in differences(stored, now)]


def _split_from(code_before: int, code_after: int) -> bool:
    before, after = impacting_number(code_before), impacting_number(code_after)
    return (before is not None and after is not None and before[1] == 1
            and after[1] >= 2 and before[0] == after[0])


def _sweep_split(stored: dict, now: dict) -> list[str]:
    a, b = stored["label"], now["label"]
    moved = a != b
    problems = []
    if any(not _split_from(x, y) for x, y in set(zip(a[moved].tolist(), b[moved].tolist(),
                                                     strict=True))):
        problems.append("label: a change that is not impacting P{p} -> impacting P{p}^m")
    impacting = np.array([impacting_number(c) is not None for c in a.ravel()]).reshape(a.shape)
    for name in sorted(set(stored) & set(now)):
        x, y = stored[name], now[name]
        if name in LABEL_TABLE or name in ("label", "attractor_points"):
            continue
        if x.shape == a.shape and y.shape == a.shape:
            differ = ~((x == y) | (np.isnan(x) & np.isnan(y)) if x.dtype.kind == "f"
                       else x == y)
            if (differ & ~impacting).any():
                problems.append(f"{name}: {int((differ & ~impacting).sum())} values changed "
                                "where the label was not impacting")
        elif differences({name: x}, {name: y}):
            problems.append(f"{name}: changed (check by hand)")
    old = dict(zip(stored["label_code"].tolist(), stored["label_name"].tolist(), strict=True))
    new = dict(zip(now["label_code"].tolist(), now["label_name"].tolist(), strict=True))
    for code, name in old.items():
        if new.get(code) != name:
            problems.append(f"label {code} ({name}) is {new.get(code)!r} now")
            continue
        before = stored["attractor_points"][old_index(stored, code)]
        after = now["attractor_points"][old_index(now, code)]
        if not np.array_equal(before, after[..., : before.shape[-2], :], equal_nan=True):
            problems.append(f"attractor_points of {name} changed")
    return problems


def _design_split(stored: dict, now: dict) -> list[str]:
    old, new = list(stored["group"]), list(now["group"])
    problems = [f"{name}: changed" for name in sorted(set(stored) & set(now))
                if name not in ("group", "count", "share", "ci_low", "ci_high")
                and differences({name: stored[name]}, {name: now[name]})]
    fresh = [g for g in new if g not in old]
    for g in old:
        if g not in new:
            problems.append(f"group {g} vanished")
            continue
        parts = [f for f in fresh if f.startswith("impacting P") and "^" in f
                 and f.split("^")[0] == g]
        expected = stored["count"][:, old.index(g)] - sum(
            (now["count"][:, new.index(f)] for f in parts), start=0)
        if not np.array_equal(now["count"][:, new.index(g)], expected):
            problems.append(f"group {g}: counts changed")
    for f in fresh:
        if f.split("^")[0] not in old or not f.startswith("impacting P"):
            problems.append(f"group {f} is new and not an impacting orbit split off")
    return problems


def main(names: list[str]) -> int:
    check = formerly_unresolved_only
    what = "only formerly unresolved entries changed"
    if "--impacting" in names:
        names = [n for n in names if n != "--impacting"]
        check, what = impacting_split_only, "only impacting orbits split"
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, options in SCENES:
            if name not in names:
                continue
            now = arrays_of(run_scene(scene, options, Path(tmp) / f"{name}.h5"))
            stored = load_stored(name)
            if not differences(stored, now):
                print(f"{name}: identical", flush=True)
                continue
            problems = check(stored, now)
            failed += bool(problems)
            print(f"{name}: " + ("; ".join(problems) if problems else
                                 f"{what} (" + "; ".join(differences(stored, now)) + ")"),
                  flush=True)
    return failed


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
