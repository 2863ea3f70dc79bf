"""[verification]: how a sweep measures its own label error (sweep kinds only).

After a sweep, a random sample of its trajectories is rerun at tightened settings and the
share whose label changes is reported with its 95% Wilson interval (see
``sweep.verification``). Every key has a default, so a scene without the section is
verified as described in README ("How right is a result").
"""

from __future__ import annotations

from dataclasses import dataclass

from .reader import Section

MAX_SAMPLE_LIMIT = 1_000_000  # largest max_sample / min_sample accepted


@dataclass(frozen=True)
class VerificationSettings:
    """The validated [verification] section.

    share : fraction of the sweep's trajectories rerun (0 < share <= 1)
    min_sample, max_sample : bounds on the number rerun (before capping at the total)
    threshold : the largest accepted upper end of the 95% Wilson interval of the label
        disagreement share (0 < threshold < 1; 0.005 = 0.5%)
    tighten : redo the whole sweep at tighter settings when it is over the threshold
    seed : seed of the random sample
    enabled : false records "not verified (disabled by [verification] enabled = false)"
    pilot : before a large sweep, choose the loosest tolerance that labels a pilot sample
        as the tight reference does (``sweep.pilot``)
    pilot_sample : trajectories in that sample; the pilot runs on sweeps of at least
        ``sweep.pilot.MIN_TOTAL_RATIO`` times as many
    """

    share: float = 0.01
    min_sample: int = 50
    max_sample: int = 2000
    threshold: float = 0.005
    tighten: bool = True
    seed: int = 0
    enabled: bool = True
    pilot: bool = True
    pilot_sample: int = 400

    def sample_size(self, total: int) -> int:
        """Trajectories rerun out of ``total``: round(share * total) clamped to
        [min_sample, max_sample], and never more than ``total``."""
        wanted = min(max(round(self.share * total), self.min_sample), self.max_sample)
        return max(0, min(wanted, total))


KEYS = ("share", "min_sample", "max_sample", "threshold", "tighten", "seed", "enabled", "pilot",
        "pilot_sample")


def _open_unit(value: float) -> str | None:
    return None if 0.0 < value < 1.0 else "must be in (0, 1)"


def _share(value: float) -> str | None:
    return None if 0.0 < value <= 1.0 else "must be in (0, 1]"


def read_verification(source: str, doc: dict) -> VerificationSettings:
    """The [verification] section of a sweep scene (defaults when absent)."""
    sec = Section(source, "verification", doc.get("verification", {}))
    d = VerificationSettings()
    settings = VerificationSettings(
        share=sec.number("share", d.share, _share),
        min_sample=sec.integer("min_sample", d.min_sample, 1, MAX_SAMPLE_LIMIT),
        max_sample=sec.integer("max_sample", d.max_sample, 1, MAX_SAMPLE_LIMIT),
        threshold=sec.number("threshold", d.threshold, _open_unit),
        tighten=sec.boolean("tighten", d.tighten),
        seed=sec.integer("seed", d.seed, 0, 2**63 - 1),
        enabled=sec.boolean("enabled", d.enabled),
        pilot=sec.boolean("pilot", d.pilot),
        pilot_sample=sec.integer("pilot_sample", d.pilot_sample, 1, MAX_SAMPLE_LIMIT),
    )
    sec.finish(KEYS)
    if settings.min_sample > settings.max_sample:
        raise sec.fail("min_sample", f"must be <= max_sample ({settings.max_sample}), got "
                                     f"{settings.min_sample}")
    return settings
