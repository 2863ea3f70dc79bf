"""Figures drawn from result files. Plots read the store and never integrate.

matplotlib is imported inside the plotting functions only, with the Agg backend.
"""


def pyplot():
    """matplotlib.pyplot on the non-interactive Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
