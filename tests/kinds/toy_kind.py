"""A toy analysis kind in its own module, as a new kind is added: this file and its line
in ``softimpact_cli.kinds.REGISTRY`` (the tests add the line with monkeypatch)."""

import xarray as xr

from softimpact_cli.kinds.base import AnalysisKind, PlotOption, PlotSpec


def _toy_read(sec, ctx):
    from dataclasses import make_dataclass

    settings = make_dataclass("ToyAnalysis", [("kind", str), ("scale", float)], frozen=True)
    return settings("toy", sec.number("scale", 1.0))


def _toy_run(scene, progress=None, **_):
    w = float(scene.values["w"])
    return xr.Dataset({"omega": ((), scene.analysis.scale * w)},
                      attrs={"analysis": "toy", "outcome": "done"})


def toy_figure(ds, ax=None, marker="o"):
    """The toy kind's figure: its one number as a point."""
    from softimpact_cli.plot import new_figure

    fig = new_figure() if ax is None else ax.figure
    (fig.add_subplot() if ax is None else ax).plot([0.0], [float(ds["omega"])], marker)
    return fig


KINDS = (AnalysisKind("toy", "a kind added by one registry entry", _toy_read,
                   lambda scene, workers=None, chunk_size=None: "toy: scale the frequency",
                   run=_toy_run, summary=lambda ds: {"omega": float(ds["omega"])},
                   plot=PlotSpec("The toy's frequency.", draw=f"{__name__}:toy_figure",
                                 options=(PlotOption("--marker", "marker", "A marker.",
                                                     kind="choice", choices=("o", "x")),))),)
