"""What the figures share: new figures without pyplot, panels placed on given axes,
the texts of parameters, phases and start times, pi ticks; ``save``. matplotlib is imported
inside the functions that draw."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # matplotlib is imported inside the functions that draw
    pass

# the helpers the figures share, public in ``softimpact_cli.plot`` too
__all__ = ["DEFAULT_DPI", "PARAMETER_TEX", "axis_value_text", "is_figure", "multiple_text",
           "new_figure", "panel_letter", "parameter_text", "phase_text", "pi_ticks",
           "place_panels", "root_figure", "save", "start_text", "start_time", "wrap_tex"]

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


def axis_value_text(axis: str, value: float, T: float) -> str:
    """TeX text of one grid value: phi in multiples of pi, t0 in multiples of T (the
    forcing period)."""
    if axis == "phi":
        return phase_text(value)
    if axis == "t0":
        return multiple_text(value / T, "T", 1.0)
    return f"{value:.6g}"


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
    """(a), (b), ..., (z), (aa), (ab), ... at the top left of a panel, outside the data."""
    letters = chr(ord("a") + k % 26)
    if k >= 26:  # past (z), as spreadsheet columns: (aa), (ab), ...
        letters = chr(ord("a") + k // 26 - 1) + letters
    ax.text(-0.02, 1.02, f"({letters})", transform=ax.transAxes, ha="right",
            va="bottom", fontsize=fontsize, fontweight="bold")


def parameter_text(ds, exclude=()) -> str:
    """The result's parameters as TeX text (phi as a multiple of pi), without ``exclude``.
    A chain's (``stop.1.k_c``...): plain ``name=value``, CHAIN_PARAMETERS_PER_LINE a line."""
    if ds.attrs.get("model") == "chain":
        return _chain_parameter_text(ds, exclude)
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


CHAIN_PARAMETERS_PER_LINE = 8


def _chain_parameter_text(ds, exclude=()) -> str:
    """A chain's parameters, plain text (its names are no TeX), several lines."""
    items = []
    for item in str(ds.attrs.get("parameters", "")).split(", "):
        key, _, value = item.partition("=")
        if key and key not in exclude:
            try:
                items.append(f"{key}={float(value):.6g}")
            except ValueError:
                items.append(item)
    step = CHAIN_PARAMETERS_PER_LINE
    return ",\n".join(", ".join(items[i: i + step]) for i in range(0, len(items), step))


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
