"""The region of a chain's design: where only the target product survives.

Each product of the chain's catalogue survives at stop values v iff ``sign_s (v_s -
crit_s) > 0`` for every stop s (``chain_catalogue.survival``; sign -1 for a left wall).
Stop positions (``stop.s.d``, ``stop.s.wall``) move the stops, not the products: the region
is exact in them. Body parameters change the products: the catalogue is computed on a grid
of their values. :class:`ChainRegion` holds the critical values on that grid and answers
which products survive at a point, and its margins (``analysis.chain_design`` explains
them); :func:`region_map` is the plane the design's figure draws.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..systems import System
from .chain_catalogue import ChainCatalogue
from .chain_dcrit import chain_model, stop_coefficients
from .design import NoRegion

MAP_STEPS = 241  # raster of a stop axis in the region map


def axis_sort(axis: str) -> str:
    """"stop" (a stop's gap or wall), "law" (a stop's law parameter) or "body"."""
    if not axis.startswith("stop."):
        return "body"
    return "stop" if axis.rsplit(".", 1)[1] in ("d", "wall") else "law"


def axis_scale(axis: str, value: float) -> float:
    """What a relative change of ``axis`` is relative to: pi for a phase, else |value|."""
    return float(np.pi) if axis.startswith("phi.") else max(abs(value), 1e-12)


@dataclass(frozen=True)
class ChainRegion:
    """The products' critical values on the body grid, and the target-only region.

    body_axes : (B,) names; grid : (G, B) body values, C order over ``shape``;
    names : (C,) products; critical : (G, C, S), NaN where a product is absent;
    target : index in names; stop_axes : {axis: stop index (0-based)};
    signs : (S,) +1 (between bodies, right wall) or -1 (left wall);
    stops : (S,) the scene's stop values (gap or wall).
    """

    body_axes: tuple[str, ...]
    shape: tuple[int, ...]
    grid: np.ndarray
    names: tuple[str, ...]
    critical: np.ndarray
    target: int
    stop_axes: dict
    signs: np.ndarray
    stops: np.ndarray

    def stop_vector(self, point: dict) -> np.ndarray:
        """(S,) the stop values at ``point`` (the scene's where it gives none)."""
        v = self.stops.copy()
        for axis, s in self.stop_axes.items():
            if axis in point:
                v[s] = point[axis]
        return v

    def survivors(self, critical: np.ndarray, stops: np.ndarray) -> np.ndarray:
        """(C,) bool: which products survive at ``stops`` given ``critical`` (C, S)."""
        with np.errstate(invalid="ignore"):
            return np.all(self.signs * (stops - critical) > 0.0, axis=1)

    def alone(self, critical: np.ndarray, stops: np.ndarray) -> bool:
        alive = self.survivors(critical, stops)
        return bool(alive[self.target] and alive.sum() == 1)

    def nearest(self, point: dict) -> int:
        """The flat index of the body grid point nearest to ``point``, axis by axis."""
        index = []
        for b, axis in enumerate(self.body_axes):
            values = np.unique(self.grid[:, b])
            index.append(int(np.argmin(np.abs(values - point[axis]))))
        return int(np.ravel_multi_index(index, self.shape)) if index else 0

    def stop_margins(self, critical: np.ndarray, stops: np.ndarray
                     ) -> tuple[float, float, float]:
        """(d_to_target, d_to_boundary, relative) over the stop axes (module docstring);
        NaN, NaN, inf without stop axes."""
        if not self.stop_axes:
            return np.nan, np.nan, np.inf
        with np.errstate(invalid="ignore"):
            killed = self.signs * (stops - critical) <= 0.0  # (C, S)
        present = np.isfinite(critical).all(axis=1)
        to_target, to_boundary, relative = [], [], []
        for s in self.stop_axes.values():
            t = self.signs[s] * (stops[s] - critical[self.target, s])
            revive = [self.signs[s] * (critical[p, s] - stops[s])
                      for p in range(len(self.names))
                      if p != self.target and present[p] and killed[p, s]
                      and killed[p].sum() == 1]
            edge = min([t, *revive])
            to_target.append(t)
            to_boundary.append(edge)
            relative.append(edge / max(abs(stops[s]), 1e-12))
        return float(min(to_target)), float(min(to_boundary)), float(min(relative))

    def body_margin(self, point: dict, stops: np.ndarray) -> float:
        """The smallest relative distance along a body axis from ``point`` to the grid
        points outside the region (module docstring); inf without swept body axes."""
        out = np.inf
        if not self.body_axes:
            return out
        at = np.unravel_index(self.nearest(point), self.shape)
        for b, axis in enumerate(self.body_axes):
            if self.shape[b] < 2:
                continue
            line = [int(np.ravel_multi_index((*at[:b], k, *at[b + 1:]), self.shape))
                    for k in range(self.shape[b])]
            values = self.grid[line, b]
            outside = [values[k] for k, g in enumerate(line)
                       if not self.alone(self.critical[g], stops)]
            step = float(values[1] - values[0])
            gap = (float(np.min(np.abs(np.array(outside) - point[axis]))) - 0.5 * step
                   if outside else float(values[-1] - values[0]))
            out = min(out, max(gap, 0.0) / axis_scale(axis, point[axis]))
        return out

    def margins(self, critical: np.ndarray, point: dict) -> dict[str, float]:
        """Margins of ``point`` given the exact critical values (C, S) at its body values."""
        stops = self.stop_vector(point)
        if not self.alone(critical, stops):
            to_target, to_boundary, _ = self.stop_margins(critical, stops)
            return {"relative": 0.0, "d_to_target": to_target,
                    "d_to_boundary": min(to_boundary, 0.0), "body_to_boundary": 0.0}
        to_target, to_boundary, relative = self.stop_margins(critical, stops)
        body = self.body_margin(point, stops)
        rel = min(relative, body)
        return {"relative": float(rel if np.isfinite(rel) else 1.0),
                "d_to_target": to_target, "d_to_boundary": to_boundary,
                "body_to_boundary": float(body if np.isfinite(body) else np.nan)}


def critical_of(cat: ChainCatalogue, names, n_stops: int) -> np.ndarray:
    """(len(names), S) the catalogue's critical values in the order of ``names`` (NaN where
    it has no such product)."""
    out = np.full((len(names), n_stops), np.nan)
    index = {p.name: k for k, p in enumerate(cat.products)}
    for j, name in enumerate(names):
        if name in index:
            out[j] = cat.critical[index[name]]
    return out


def body_grid(bounds: dict, body_axes, points: int) -> tuple[tuple[int, ...], np.ndarray]:
    """(shape, (G, B) values): ``points`` values over each body axis's bounds (one when
    its low and high are equal), every combination, C order."""
    lines = [np.linspace(*bounds[a], points) if bounds[a][0] < bounds[a][1]
             else np.array([bounds[a][0]]) for a in body_axes]
    shape = tuple(len(line) for line in lines)
    points = list(itertools.product(*lines))  # one empty point without body axes
    grid = np.array(points, dtype=float).reshape(len(points), len(body_axes))
    return shape, grid


def build_region(system: System, values: dict, settings, catalogue_at,
                 progress=lambda s: None) -> ChainRegion:
    """The region on the body grid (``catalogue_at(point) -> ChainCatalogue``)."""
    axes = tuple(settings.bounds)
    body_axes = tuple(a for a in axes if axis_sort(a) == "body")
    model = chain_model(system)
    stop_axes = {a: int(a.split(".")[1]) - 1 for a in axes if axis_sort(a) == "stop"}
    signs = np.array([stop_coefficients(system, s)[1]
                      for s in range(1, len(model.stops) + 1)])
    stops = np.array([float(values[f"stop.{s}.{'wall' if st.wall else 'd'}"])
                      for s, st in enumerate(model.stops, 1)])
    shape, grid = body_grid(settings.bounds, body_axes, settings.grid_points)
    progress(f"the chain's catalogue at {len(grid)} body grid points")
    cats = [catalogue_at(dict(zip(body_axes, g, strict=True))) for g in grid]
    names = tuple(dict.fromkeys(n for c in cats for n in c.names))
    if settings.target not in names:
        raise NoRegion(f"{settings.target!r} is not a product of the chain's catalogue "
                       f"({', '.join(names) or 'none found'})")
    critical = np.stack([critical_of(c, names, len(model.stops)) for c in cats])
    return ChainRegion(body_axes, shape, grid, names, critical, names.index(settings.target),
                       stop_axes, signs, stops)


def region_map(region: ChainRegion, bounds: dict, pick: dict) -> dict:
    """The plane the figure draws: x the first stop axis (else the first body axis), y the
    first body axis (else the next stop axis, else none), the other axes at the pick;
    per cell the number of surviving products and whether the target is among them."""
    axes = list(bounds)
    stop_axes = [a for a in axes if a in region.stop_axes]
    order = stop_axes[:1] + list(region.body_axes[:1]) + stop_axes[1:2] + list(
        region.body_axes[1:2])
    x_axis = order[0] if order else axes[0]
    y_axis = next((a for a in order[1:] if a != x_axis), "")

    def values(axis):
        if not axis:
            return np.array([0.0])
        if axis in region.body_axes:
            return np.unique(region.grid[:, region.body_axes.index(axis)])
        return np.linspace(*bounds[axis], MAP_STEPS if axis == x_axis else MAP_STEPS // 2)

    xs, ys = values(x_axis), values(y_axis)
    count = np.zeros((ys.size, xs.size), dtype=np.int64)
    target = np.zeros((ys.size, xs.size), dtype=np.int8)
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            point = {**pick, x_axis: float(x), **({y_axis: float(y)} if y_axis else {})}
            g = region.nearest(point)
            alive = region.survivors(region.critical[g], region.stop_vector(point))
            count[j, i] = alive.sum()
            target[j, i] = alive[region.target]
    return {"x_axis": x_axis, "y_axis": y_axis, "x": xs, "y": ys, "count": count,
            "target": target}
