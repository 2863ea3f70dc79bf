"""CPU seconds of two test runs (``pytest_cpu_per_test``) over the tests both hold.

    python benchmarks/compare_test_cpu.py BEFORE_PREFIX AFTER_PREFIX [SLOW_IDS]

SLOW_IDS: a file of node ids (one per line) left out of the second run, e.g. the tests
marked slow, to compare a `make test-fast` with a whole suite's run.
"""

import glob
import json
import sys


def load(prefix: str) -> dict[str, float]:
    out: dict[str, float] = {}
    for path in glob.glob(prefix + ".*.json"):
        with open(path) as f:
            out.update(json.load(f))
    return out


def main(argv: list[str]) -> None:
    before, after = load(argv[1]), load(argv[2])
    if len(argv) > 3:
        with open(argv[3]) as f:
            left_out = set(f.read().split())
        after = {k: v for k, v in after.items() if k not in left_out}
    common = sorted(set(before) & set(after))
    b, a = sum(before[k] for k in common), sum(after[k] for k in common)
    print(f"before: {len(before)} tests, {sum(before.values()):.1f} s CPU")
    print(f"after: {len(after)} tests, {sum(after.values()):.1f} s CPU")
    print(f"common: {len(common)} tests: before {b:.1f} s, after {a:.1f} s, "
          f"ratio after/before {a / b:.3f}")
    for k in sorted(common, key=lambda k: after[k] - before[k], reverse=True)[:10]:
        print(f"  {after[k] - before[k]:+7.2f}  {before[k]:6.2f} -> {after[k]:6.2f}  {k}")


if __name__ == "__main__":
    main(sys.argv)
