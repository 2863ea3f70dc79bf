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

import math
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..analysis.attributes import attribute_list
from ..store.layout import memory_order

if TYPE_CHECKING:  # matplotlib is imported inside the functions that draw
    from matplotlib.figure import Figure

DEFAULT_DPI = 150
# TeX symbols of the parameters named in a result's ``parameters`` attribute
PARAMETER_TEX = {"c": "c", "k1": "k_1", "k2": "k_2", "F": "F", "w": r"\omega", "d": "d",
                 "phi": r"\varphi", "k_c": "k_c", "c_c": "c_c", "d1": "d_1", "c1": "c_1",
                 "exponent": "n"}


def new_figure(**kwargs):
    """A matplotlib Figure with constrained layout, not registered with pyplot."""
    from matplotlib.figure import Figure

    kwargs.setdefault("layout", "constrained")
    return Figure(**kwargs)


def is_figure(target) -> bool:
    from matplotlib.figure import FigureBase

    return isinstance(target, FigureBase)  # a Figure or a SubFigure


def root_figure(container):
    """The top-level Figure of a Figure, SubFigure or Axes."""
    from matplotlib.figure import Figure

    fig = container
    while not isinstance(fig, Figure):
        fig = fig.figure if is_figure(fig) else fig.get_figure()
    return fig


def place_panels(ax, shape: tuple[int, int], order: list[tuple[int, int]], figsize,
                 **subplots):
    """(container, panels): where a kind's figure draws its ``len(order)`` panels.

    The kind's own layout is a grid of ``shape`` (rows, columns) with panel k at grid
    cell ``order[k]``. ``ax`` None: a new Figure of ``figsize``, its grid from
    ``subplots(*shape, squeeze=False, **subplots)``; a Figure or SubFigure: that grid in
    it; cells not in ``order`` are switched off. An Axes (for one panel) or a sequence of
    exactly ``len(order)`` Axes: those. ``container`` is the figure or subfigure that
    receives figure-level text (suptitle, colour bars, legends).
    """
    import numpy as np

    n = len(order)
    if ax is None or is_figure(ax):
        container = new_figure(figsize=figsize) if ax is None else ax
        grid = container.subplots(*shape, squeeze=False, **subplots)
        for r, c in np.ndindex(*shape):
            if (r, c) not in order:
                grid[r, c].axis("off")
        return container, [grid[r, c] for r, c in order]
    from matplotlib.axes import Axes

    given = [ax] if isinstance(ax, Axes) else list(np.ravel(np.asarray(ax, dtype=object)))
    if len(given) != n or not all(isinstance(a, Axes) for a in given):
        what = "an Axes" if isinstance(ax, Axes) else f"{len(given)} items"
        raise ValueError(f"ax: this figure has {n} panel{'s' if n > 1 else ''}; pass "
                         f"{'one Axes or ' if n == 1 else ''}a sequence of {n} Axes or a "
                         f"Figure (got {what})")
    return given[0].figure, given


def save(fig, out: str | Path, dpi: int = DEFAULT_DPI) -> Path:
    """Write ``fig`` to ``out`` (format from the suffix), creating the folder."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=dpi)
    return out


def multiple_text(x: float, symbol: str = r"\pi", unit: float = math.pi,
                  rel_tol: float = 1e-9, max_denominator: int = 64, digits: int = 4) -> str:
    """TeX text (no dollars) of ``x`` as a multiple of ``unit`` where it is one: a fraction
    (``5\\pi/8``, ``-\\pi``) or a short decimal (``0.573\\pi``, at most ``digits``
    significant digits), within ``rel_tol``; otherwise ``x`` itself ('%.6g')."""
    if not math.isfinite(x):
        return f"{x}"
    if x == 0:
        return "0"
    r = x / unit
    tol = rel_tol * abs(r)
    frac = Fraction(r).limit_denominator(max_denominator)
    if abs(float(frac) - r) <= tol:
        a, b = frac.numerator, frac.denominator
        head = symbol if a == 1 else "-" + symbol if a == -1 else f"{a}{symbol}"
        return head if b == 1 else f"{head}/{b}"
    for n in range(1, digits + 1):
        short = f"{r:.{n}g}"
        if abs(float(short) - r) <= tol:
            return f"{short}{symbol}"
    return f"{x:.6g}"


def phase_text(phi: float) -> str:
    """A phase in TeX: a multiple of pi where it is one (``0.573\\pi``), else radians."""
    return multiple_text(float(phi))


def start_time(ds, index=None) -> tuple[str, float | None]:
    """(mode, t0/T) of a result: mode 'fixed', 'grid' or 'random'; t0/T for 'fixed' (at
    the grid point ``index`` of a sweep when given) else None. Reads, in order: the mode;
    a ``t0`` coordinate that varies over the grid; the global attribute ``t0_over_T``; a
    constant ``t0`` coordinate; the global attribute ``t0`` (time); else 0."""
    T = float(ds.attrs.get("forcing_period", 1.0))
    mode = str(ds.attrs.get("t0_mode", "fixed"))
    if mode == "random":
        return mode, None
    values = ds["t0"].values if "t0" in ds.coords or "t0" in ds.data_vars else None
    varies = values is not None and values.size > 1 and bool(np.ptp(values) > 0)
    if varies and index is not None and values.ndim == len(index):
        return "fixed", float(values[tuple(index)]) / T
    if mode == "grid" or varies:
        return "grid", None
    if "t0_over_T" in ds.attrs:
        return "fixed", float(ds.attrs["t0_over_T"])
    if values is not None and values.size:
        return "fixed", float(values.ravel()[0]) / T
    return "fixed", float(ds.attrs.get("t0", 0.0)) / T


def start_text(ds, index=None) -> str:
    """The start phase as TeX text: '$t_0 = T/2$', 'random $t_0$' or '$t_0$ swept'."""
    mode, fraction = start_time(ds, index)
    if mode == "random":
        return "random $t_0$ (uniform in $[0, T)$)"
    if fraction is None:
        return "$t_0$ swept"
    return f"$t_0 = {multiple_text(fraction, 'T', 1.0)}$"


def wrap_tex(text: str, width: int) -> str:
    """``text`` in lines of about ``width`` visible characters, broken only after ', '
    or '; ' (never inside a $...$ formula), existing line breaks kept."""
    import re

    def visible(part: str) -> int:
        return len(re.sub(r"\\[a-zA-Z]+", "x", re.sub(r"[${}_^]", "", part)))

    lines = []
    for paragraph in text.split("\n"):
        line = ""
        for token in re.split(r"(?<=[,;]) ", paragraph):
            if line and visible(line) + 1 + visible(token) > width and \
                    line.count("$") % 2 == 0:
                lines.append(line)
                line = token
            else:
                line = f"{line} {token}" if line else token
        lines.append(line)
    return "\n".join(lines)


def panel_letter(ax, k: int, fontsize: int = 11) -> None:
    """(a), (b), ... at the top left of a panel, outside the data."""
    ax.text(-0.02, 1.02, f"({chr(ord('a') + k)})", transform=ax.transAxes, ha="right",
            va="bottom", fontsize=fontsize, fontweight="bold")


def parameter_text(ds, exclude=()) -> str:
    """The result's parameters as TeX text (phi as a multiple of pi), without ``exclude``."""
    parts = []
    law = None
    for item in str(ds.attrs.get("parameters", "")).split(", "):
        key, _, value = item.partition("=")
        if not key or key in exclude:
            continue
        if key == "law":
            law = value
            continue
        try:
            number = float(value)
        except ValueError:
            parts.append(f"{key}={value}")
            continue
        text = phase_text(number) if key == "phi" else f"{number:.6g}"
        parts.append(f"${PARAMETER_TEX.get(key, key)} = {text}$")
    if law and law != "paper":
        parts.append(f"contact law: {law}")
    return ", ".join(parts)


def pi_ticks(axis, lo: float, hi: float, max_ticks: int = 9) -> None:
    """Ticks of a phase axis (``ax.xaxis`` or ``ax.yaxis``) at multiples of pi/8 ... 2 pi
    between ``lo`` and ``hi``, labelled as such (``3\\pi/4``); on a window too narrow
    for three of them, at round decimal multiples of pi (``0.32\\pi``)."""
    from matplotlib.ticker import FuncFormatter, MultipleLocator

    for step in (np.pi / 8, np.pi / 4, np.pi / 2, np.pi, 2 * np.pi):
        ticks = np.arange(np.ceil(lo / step - 1e-9), np.floor(hi / step + 1e-9) + 1) * step
        if len(ticks) <= max_ticks:
            break
    if len(ticks) >= 3:
        axis.set_ticks(ticks, [f"${multiple_text(t)}$" for t in ticks])
        return
    # a narrow window: round decimal multiples of pi (0.32 pi, 0.34 pi, ...)
    raw = (hi - lo) / np.pi / 5
    mag = 10.0 ** np.floor(np.log10(raw)) if raw > 0 else 0.01
    step = next(k * mag for k in (1, 2, 5, 10) if k * mag >= raw)
    digits = max(0, -int(np.floor(np.log10(step))))
    axis.set_major_locator(MultipleLocator(step * np.pi))
    axis.set_major_formatter(FuncFormatter(
        lambda x, _: "0" if abs(x) < 1e-12 else f"${x / np.pi:.{digits}f}\\pi$"))


# ---------------------------------------------------------------- one function per kind


def trajectory(ds, ax=None, *, last_periods: int | None = None) -> Figure:
    """Time series, phase portraits and Poincaré points of a trajectory result
    (``last_periods`` drawn strongly as the steady state; default a quarter, <= 20).
    Panels: 2 (one body) or 6 (a pair, the last a text summary)."""
    from .trajectory_figure import draw_trajectory

    return draw_trajectory(_expect(ds, "trajectory"), last_periods, ax)


def catalogue(ds, ax=None) -> Figure:
    """Attractors on the phase plane, then one panel per combination."""
    from .catalogue_figure import draw_catalogue

    return draw_catalogue(_expect(ds, "catalogue"), ax)


def lyapunov(ds, ax=None) -> Figure:
    """Lyapunov exponents with standard errors: against the parameter above the section
    states for a grid run (2 panels), else per run with Floquet exponents beside (1)."""
    from .lyapunov_figure import draw_lyapunov

    return draw_lyapunov(_expect(ds, "lyapunov"), ax)


def continuation(ds, ax=None) -> Figure:
    """Branches against the continued parameter (one panel per body; stable solid,
    unstable dashed, bifurcations marked, brute-force sweeps overlaid) above the moduli
    of their Floquet multipliers."""
    from .continuation_figure import draw_continuation

    return draw_continuation(_expect(ds, "continuation"), ax)


def error_note(fig, ds) -> Figure:
    """Print the result's verification line (its measured label error, see
    ``report.verification``) at the foot of ``fig``; returns ``fig``."""
    import textwrap

    from ..report.verification import verification_line

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
    from .basins_figure import draw_basins

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
    from ..analysis.stability import basin_stability
    from .stability_figure import draw_stability

    ds = _expect(ds, "stability")
    swept = attribute_list(ds.attrs, "grid_swept")
    axis = against or (swept[0] if swept else "c_c")
    if attractors:
        from .section_clouds import draw_clouds

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
    from .dcrit_figure import draw_dcrit

    ds = _expect(ds, "dcrit")
    names = [str(n) for n in ds["combination_label"].values]
    if combination is not None and combination not in names:
        raise ValueError(f"combination: {combination!r} is not one of {', '.join(names)}")
    return draw_dcrit(ds, combination, ax)


def bifurcation(ds, ax=None) -> Figure:
    """Section displacements of the left, then the right body against d."""
    from .bifurcation_figure import draw_bifurcation

    return draw_bifurcation(_expect(ds, "bifurcation"), ax)


def map(ds, ax=None) -> Figure:  # noqa: A001 (named after the kind, as the CLI's `plot map`)
    """Predicted and found numbers of coexisting solutions over the two swept axes,
    then their difference."""
    from .map_figure import draw_map

    return draw_map(_expect(ds, "map"), ax)


def tipping(ds, ax=None, *, no_basins: bool = False, show_error: bool = False) -> Figure:
    """The tipping matrix P(i -> j) with 95% Wilson intervals; over a plane also the
    basins before and after (panels: before, after, matrix; ``no_basins`` or an Axes: the
    matrix alone). ``show_error``: the measured label error at the foot."""
    from .tipping_figure import draw_tipping

    ds = _expect(ds, "tipping")
    fig = draw_tipping(ds, no_basins, ax)
    return error_note(fig, ds) if show_error else fig


def fatal_shock(ds, ax=None) -> Figure:
    """The fatal shocks of a solution against the phase of its orbit (one panel)."""
    from .fatal_shock_figure import draw_fatal_shock

    return draw_fatal_shock(_expect(ds, "fatal_shock"), ax)


def design(ds, ax=None) -> Figure:
    """The (d, phi) plane with the target-only region, a zoom around the pick, the
    basin stability at the pick, the perturbations."""
    from .design_figure import draw_design

    return draw_design(_expect(ds, "design"), ax)


def fractality(ds, ax=None, *, max_panels: int = 8) -> Figure:
    """Per plane (at most ``max_panels``; a row of three panels each): S_b and S_bb
    against the box size with ln 2, the uncertainty exponent's log-log fit, the boundary
    cells coloured by how many merged boundaries (Wada test) lie near them."""
    from .fractality_figure import draw_fractality

    return draw_fractality(_expect(ds, "fractality"), max_panels, ax)


KINDS = ("trajectory", "catalogue", "basins", "stability", "dcrit", "bifurcation", "map",
         "tipping", "fatal_shock", "design", "fractality",
         "lyapunov", "continuation")  # the functions above, by analysis kind


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
