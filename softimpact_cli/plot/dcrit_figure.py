"""Critical-distance figures: d_crit(phi) curves with regions labelled by how many
combinations survive (Roman numerals, as in the study), and x1 - x2 traces (fig. 5)."""

from __future__ import annotations

from collections import deque

import numpy as np

from ..analysis.labels import latex_of
from ..config.axes import COUPLING_AXES
from .common import panel_letter, parameter_text, phase_text, pi_ticks, place_panels, root_figure
from .palette import colour_of, solution_order


def roman(n: int) -> str:
    if n == 0:
        return "0"
    out = ""
    for value, letters in ((1000, "M"), (900, "CM"), (500, "D"), (400, "CD"), (100, "C"),
                           (90, "XC"), (50, "L"), (40, "XL"), (10, "X"), (9, "IX"), (5, "V"),
                           (4, "IV"), (1, "I")):
        while n >= value:
            out += letters
            n -= value
    return out


def regions(count: np.ndarray) -> list[tuple[int, float, float, int]]:
    """Connected regions of equal count: (count, row centre, column centre, size)."""
    seen = np.zeros(count.shape, dtype=bool)
    out = []
    rows, cols = count.shape
    for r0 in range(rows):
        for c0 in range(cols):
            if seen[r0, c0]:
                continue
            value = count[r0, c0]
            queue = deque([(r0, c0)])
            seen[r0, c0] = True
            members = []
            while queue:
                r, c = queue.popleft()
                members.append((r, c))
                for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                    rr, cc = r + dr, c + dc
                    if 0 <= rr < rows and 0 <= cc < cols and not seen[rr, cc] and \
                            count[rr, cc] == value:
                        seen[rr, cc] = True
                        queue.append((rr, cc))
            m = np.array(members)
            # a member near the centroid, so the numeral sits inside a non-convex region
            centre = m.mean(axis=0)
            best = m[np.argmin(((m - centre) ** 2).sum(axis=1))]
            out.append((int(value), float(best[0]), float(best[1]), len(members)))
    return out


def jumps(values: np.ndarray, factor: float = 8.0) -> np.ndarray:
    """Indices i where a named curve jumps between samples i and i + 1.

    A name's shift s is defined by the canonical order of each body's section points
    (point 0 = largest x). As phi moves the right body's points, the point with the
    largest x can change, and the same physical state then carries another s: its named
    curve jumps. Such jumps are drawn as gaps, not as vertical lines.
    """
    step = np.abs(np.diff(values))
    typical = np.median(step) if step.size else 0.0
    return np.where(step > factor * max(typical, 1e-12) + 0.05 * np.ptp(values))[0]


def draw_dcrit(ds, combination: str | None = None, ax=None):
    """d_crit(phi) with the surviving-count regions, beside x1 - x2 over one period at
    the trace phases (only ``combination``'s when given); returns the Figure.

    ``ax``: 1 + one per trace phase Axes (the curves first), or a Figure (see ``plot``).
    """
    names = [str(n) for n in ds["combination_label"].values]
    order = solution_order(ds) or names
    phi = ds["phi"].values
    dc = ds["d_crit"].values
    n_traces = ds.sizes.get("trace_phi", 0)
    ncols = 1 + min(n_traces, 3)
    nrows = 1 + (max(n_traces - 3, 0) + 2) // 3 if n_traces > 3 else 1
    cells = [(0, 0)] + [(0, 1 + k) if k < 3 else (1 + (k - 3) // 3, (k - 3) % 3)
                        for k in range(n_traces)]
    fig, axs = place_panels(ax, (nrows, ncols), cells,
                            figsize=(5.5 + 3.6 * (ncols - 1), 4.6 * nrows),
                            gridspec_kw={"width_ratios": [1.6] + [1] * (ncols - 1)})
    ax = axs[0]
    d_lo = max(0.0, 0.9 * float(np.nanmin(dc)))
    d_hi = 1.1 * float(np.nanmax(dc))
    d_axis = np.linspace(d_lo, d_hi, 240)
    # surviving combinations: those whose critical distance lies below d
    count = (dc[:, None, :] < d_axis[None, :, None]).sum(axis=0)  # (d, phi)
    ax.imshow(count, origin="lower", aspect="auto", cmap="Greys", alpha=0.35,
              extent=(phi[0], phi[-1], d_lo, d_hi), vmin=0, vmax=2 * len(names))
    for value, r, c, size in regions(count):
        if size < 0.004 * count.size:
            continue
        ax.text(phi[int(c)], d_axis[int(r)], roman(value), ha="center", va="center",
                fontsize=10, fontweight="bold", color="k")
    for i, name in enumerate(names):
        cut = jumps(dc[i]) + 1
        ax.plot(np.insert(phi, cut, np.nan), np.insert(dc[i], cut, np.nan),
                color=colour_of(name, order), lw=1.6, label=latex_of(name))
    ax.set_xlabel(r"$\varphi$")
    ax.set_ylabel("$d$")
    ax.set_xlim(phi[0], phi[-1])
    ax.set_ylim(d_lo, d_hi)
    pi_ticks(ax.xaxis, float(phi[0]), float(phi[-1]))
    ax.set_title("critical distances $d_{crit}(\\varphi)$; numerals: combinations that "
                 "survive", fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0) if len(names) > 8
              else None, ncols=1 + len(names) // 12)
    chosen = [combination] if combination else names
    spp = int(ds.attrs.get("trace_samples_per_period", 512))
    for k in range(n_traces):
        tax = axs[1 + k]
        tphi = float(ds["trace_phi"].values[k])
        for name in chosen:
            i = names.index(name)
            g = ds["relative_trace"].values[k, i]
            g = g[np.isfinite(g)]
            t = np.arange(g.size) / spp
            tax.plot(t, g, color=colour_of(name, order), lw=1.2, label=latex_of(name))
            j = int(np.argmax(g))
            tax.plot(t[j], g[j], "o", color=colour_of(name, order), mec="k")
            tax.annotate(f"{g[j]:.4f}", (t[j], g[j]), textcoords="offset points",
                         xytext=(4, 4), fontsize=7)
        tax.set_xlabel("$t/T$")
        tax.set_ylabel("$x_1 - x_2$")
        tax.set_title(f"$x_1 - x_2$ at $\\varphi = {phase_text(tphi)}$", fontsize=9)
        if len(chosen) == 1:
            tax.legend(fontsize=7, loc="lower right")
    for a in axs:
        if not a.has_data():
            a.axis("off")
    shown = [a for a in axs if a.has_data()]
    if len(shown) > 1:
        for k, a in enumerate(shown):
            panel_letter(a, k)
    # d_crit depends on the uncoupled orbits only: not on d, phi (the axis), k_c, c_c, t0
    fig.suptitle(f"{ds.attrs.get('model')} pair (uncoupled orbits): "
                 + parameter_text(ds, exclude=COUPLING_AXES), fontsize=9)
    return root_figure(fig)


def draw_chain_dcrit(ds, ax=None):
    """A chain's critical values (dims stop, combination, point): one panel per stop, a
    curve per non-impacting product against the swept parameter (one point: markers)."""
    stops = [int(s) for s in ds["stop"].values]
    container, panels = place_panels(ax, (1, len(stops)), [(0, k) for k in range(len(stops))],
                                     (4.0 * len(stops), 3.6))
    axis = str(ds.attrs.get("axis", ""))
    x = ds["point"].values
    names = [str(n) for n in ds["combination_label"].values]
    for k, (stop, panel) in enumerate(zip(stops, panels, strict=True)):
        for c, name in enumerate(names):
            panel.plot(x, ds["d_crit"].values[k, c], "o-" if x.size < 3 else "-",
                       label=name, lw=1.2, ms=3)
        panel.set_xlabel(axis)
        panel.set_ylabel("critical value")
        panel.set_title(f"stop {stop}")
        panel_letter(panel, k)
    if names:
        panels[0].legend(fontsize="x-small")
    return root_figure(container)
