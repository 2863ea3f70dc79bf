"""Reproducing the study statement by statement (``softimpact reproduce``).

- ``statements.toml``: the study's 89 checkable statements, each with its rule and check;
- ``statements``: reads and validates them;
- ``runs``: the scenes they need (figure scenes, optionally changed), run once and cached;
- ``measures``: what the statements are about, read from result datasets;
- ``checks``: one function per statement kind, returning softimpact's measure and the
  candidate explanations it tried;
- ``verdicts``: the comparison rules and verdicts;
- ``table``, ``report``: the table (results/reproduce.md) and the driver.
"""
