"""Figures drawn from result files. Plots read the store and never integrate.

matplotlib is imported inside the plotting functions only, with the Agg backend.
"""


def pyplot():
    """matplotlib.pyplot on the non-interactive Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def parameter_text(ds, exclude=()) -> str:
    """The result's parameters as text, phi as a multiple of pi, without ``exclude``."""
    import math

    from ..expressions import format_multiple

    parts = []
    for item in str(ds.attrs.get("parameters", "")).split(", "):
        key, _, value = item.partition("=")
        if not key or key in exclude:
            continue
        if key == "phi":
            try:
                value = format_multiple(float(value), "pi", math.pi)
            except ValueError:
                pass
        parts.append(f"{key}={value}")
    return ", ".join(parts)
