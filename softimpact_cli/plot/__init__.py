"""Figures of results, one function per analysis kind: ``plot.<kind>(ds, ax=None, ...)``.

``ds`` is a result (``softimpact_cli.kinds.run`` or ``open_result``); each function returns a
matplotlib Figure and never writes a file or changes the backend: without ``ax`` it
builds a new Figure without pyplot (so it is not shown twice in Jupyter; display it with
``display(fig)``, or draw on your own axes). ``ax`` says where to draw instead:

- an Axes: for a figure of one panel (basins of one grid point, stability; trajectory,
  dcrit and catalogue when they have one panel);
- a sequence of Axes (``fig.subplots(...)``, nested or flat): one per panel, in the
  order each function's docstring gives;
- a Figure or SubFigure (``fig.subfigures(...)``): the kind's own layout drawn in it.

Figure-level text (a title over several panels, colour bars, a shared legend) goes to the
figure or subfigure the axes belong to. The command line's ``plot`` calls the same
functions and saves with ``save``. Plots read results and never integrate.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..analysis.attributes import attribute_list
from ..analysis.stability import basin_stability
from ..report.verification import verification_line
from ..store.layout import memory_order
from .atlas_figure import draw_atlas
from .basins_figure import draw_basins
from .bifurcation_figure import draw_bifurcation, draw_chain_bifurcation
from .catalogue_figure import draw_catalogue
from .common import *  # noqa: F403  (the helpers the figures share: common.__all__)
from .common import is_figure, new_figure, root_figure
from .continuation_figure import draw_continuation
from .dcrit_figure import draw_chain_dcrit, draw_dcrit
from .design_figure import draw_design
from .fatal_shock_figure import draw_fatal_shock
from .fractality_figure import draw_fractality
from .lyapunov_figure import draw_lyapunov
from .map_figure import draw_map
from .section_clouds import draw_clouds
from .stability_figure import draw_stability
from .tipping_figure import draw_tipping
from .trajectory_figure import draw_trajectory

if TYPE_CHECKING:  # matplotlib is imported inside the functions that draw
    from matplotlib.figure import Figure


# ---------------------------------------------------------------- one function per kind


def trajectory(ds, ax=None, *, last_periods: int | None = None) -> Figure:
    """Time series, phase portraits and Poincaré points of a trajectory result
    (``last_periods`` drawn strongly as the steady state; default a quarter, <= 20).
    Panels: 2 (one body), 6 (a pair, the last a text summary) or n + 3 (a chain of n
    bodies: time series, n phase portraits, the stops' compressions, a summary)."""

    return draw_trajectory(_expect(ds, "trajectory"), last_periods, ax)


def catalogue(ds, ax=None) -> Figure:
    """Attractors on the phase plane, then one panel per combination."""

    return draw_catalogue(_expect(ds, "catalogue"), ax)


def lyapunov(ds, ax=None) -> Figure:
    """Lyapunov exponents with standard errors: against the parameter above the section
    states for a grid run (2 panels), else per run with Floquet exponents beside (1)."""

    return draw_lyapunov(_expect(ds, "lyapunov"), ax)


def continuation(ds, ax=None) -> Figure:
    """Branches against the continued parameter (one panel per body; stable solid,
    unstable dashed, bifurcations marked, brute-force sweeps overlaid) above the moduli
    of their Floquet multipliers."""

    return draw_continuation(_expect(ds, "continuation"), ax)


def atlas(ds, ax=None, *, over=None) -> Figure:
    """The atlas's curves (fold, period doubling, Neimark-Sacker, grazing) and its
    codimension-two points in its two parameters, one panel; ``over``: a map or dcrit
    result of the same rectangle drawn beneath (its counts or d_crit curves)."""

    return draw_atlas(_expect(ds, "atlas"), over, ax)


def error_note(fig, ds) -> Figure:
    """Print the result's verification line (its measured label error, see
    ``report.verification``) at the foot of ``fig``; returns ``fig``."""
    import textwrap

    line = verification_line(ds.attrs) or ("label error: not measured (a result written "
                                           "before sweeps were verified)")
    root = root_figure(fig)
    width = max(40, int(14 * root.get_figwidth()))  # characters of 7 pt text per line
    root.supxlabel("\n".join(textwrap.wrap(line, width)), fontsize=7)
    return fig


def basins(ds, ax=None, *, max_panels: int = 36, show_error: bool = False) -> Figure:
    """Basins of attraction of a plane sweep, one panel per grid point (at most
    ``max_panels``); an Axes for a result of one grid point. ``show_error``: print the
    measured label error at the foot (``error_note``)."""

    ds = _in_memory_order(ds)
    if ds.attrs.get("ic_kind") != "plane":
        raise ValueError(f"plot.basins: needs a sweep over a plane of initial conditions, "
                         f"got a {ds.attrs.get('analysis')!r} result with "
                         f"{ds.attrs.get('ic_kind')!r} initial conditions")
    fig = draw_basins(ds, max_panels, ax)
    return error_note(fig, ds) if show_error else fig


def stability(ds, ax=None, *, against: str | None = None, show_error: bool = False,
              entropy: bool = False, attractors: bool = False) -> Figure:
    """Basin-stability curves with 95% Wilson bands against the grid axis ``against``
    (default: the swept one). One panel. ``show_error``: print the measured label error
    at the foot (``error_note``); ``entropy``: the basin entropy of the shares on a
    right-hand axis; ``attractors``: a second panel with the section points of the
    attractors that are not periodic (``ax`` then a Figure or None)."""

    ds = _expect(ds, "stability")
    swept = attribute_list(ds.attrs, "grid_swept")
    axis = against or (swept[0] if swept else "c_c")
    if attractors:
        if ax is not None and not is_figure(ax):
            raise ValueError("plot.stability: attractors=True draws two panels: pass a "
                             "Figure or None, not an Axes")
        container = new_figure(figsize=(15.0, 5.2)) if ax is None else ax
        left, right = container.subplots(1, 2, width_ratios=[3, 2])
        draw_stability(ds, basin_stability(ds), axis, left, entropy)
        draw_clouds(ds, right)
        fig = root_figure(container)
        return error_note(fig, ds) if show_error else fig
    fig = draw_stability(ds, basin_stability(ds), axis, ax, entropy)
    return error_note(fig, ds) if show_error else fig


def dcrit(ds, ax=None, *, combination: str | None = None) -> Figure:
    """Critical-distance curves with the surviving-combination regions, then the
    x1 - x2 traces (only ``combination``'s when given: a name of
    ``ds.combination_label``)."""

    ds = _expect(ds, "dcrit")
    if "stop" in ds["d_crit"].dims:  # a chain's: per stop, no traces
        if combination is not None:
            raise ValueError("combination: a chain's critical values hold no traces")
        return draw_chain_dcrit(ds, ax)
    names = [str(n) for n in ds["combination_label"].values]
    if combination is not None and combination not in names:
        raise ValueError(f"combination: {combination!r} is not one of {', '.join(names)}")
    return draw_dcrit(ds, combination, ax)


def bifurcation(ds, ax=None) -> Figure:
    """Section displacements of the left, then the right body against d."""

    ds = _expect(ds, "bifurcation")
    if "body" in ds.dims:  # a chain's: a panel per body
        return draw_chain_bifurcation(ds, ax)
    return draw_bifurcation(ds, ax)


def map(ds, ax=None) -> Figure:  # noqa: A001 (named after the kind, as the CLI's `plot map`)
    """Predicted and found numbers of coexisting solutions over the two swept axes,
    then their difference."""

    return draw_map(_expect(ds, "map"), ax)


def tipping(ds, ax=None, *, no_basins: bool = False, show_error: bool = False) -> Figure:
    """The tipping matrix P(i -> j) with 95% Wilson intervals; over a plane also the
    basins before and after (panels: before, after, matrix; ``no_basins`` or an Axes: the
    matrix alone). ``show_error``: the measured label error at the foot."""

    ds = _expect(ds, "tipping")
    fig = draw_tipping(ds, no_basins, ax)
    return error_note(fig, ds) if show_error else fig


def fatal_shock(ds, ax=None) -> Figure:
    """The fatal shocks of a solution against the phase of its orbit (one panel)."""

    return draw_fatal_shock(_expect(ds, "fatal_shock"), ax)


def design(ds, ax=None) -> Figure:
    """The (d, phi) plane with the target-only region, a zoom around the pick, the
    basin stability at the pick, the perturbations."""

    return draw_design(_expect(ds, "design"), ax)


def fractality(ds, ax=None, *, max_panels: int = 8) -> Figure:
    """Per plane (at most ``max_panels``; a row of three panels each): S_b and S_bb
    against the box size with ln 2, the uncertainty exponent's log-log fit, the boundary
    cells coloured by how many merged boundaries (Wada test) lie near them."""

    return draw_fractality(_expect(ds, "fractality"), max_panels, ax)


KINDS = ("trajectory", "catalogue", "basins", "stability", "dcrit", "bifurcation", "map",
         "tipping", "fatal_shock", "design", "fractality",
         "lyapunov", "continuation", "atlas")  # the functions above, by analysis kind


def _expect(ds, kind: str):
    """``ds`` (in the in-memory dim order) when it holds a ``kind`` result (or says
    nothing), else a ValueError."""
    found = ds.attrs.get("analysis")
    if found is not None and found != kind:
        raise ValueError(f"plot.{kind}: ds holds a {found!r} result, not a {kind} result")
    return _in_memory_order(ds)


def _in_memory_order(ds):
    """A result as the figures index it: a plane's variables ending in (first axis,
    second axis), whichever order it came in (``si.run`` and ``xarray.open_dataset``
    hand it out in the file's order; ``store.layout``)."""
    return memory_order(ds)
