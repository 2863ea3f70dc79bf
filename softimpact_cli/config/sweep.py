"""Sweep sections: [grid], [initial_conditions] and [catalogue].

[grid] sweeps any of d, phi, k_c, c_c and t0 and, where the kind allows, any other model
parameter (``config.axes``): a single value, a list, ``{start, stop, num}`` or ``{start,
stop, step}`` (phi also in the pi-string forms, t0 in T-strings). Values not swept come
from [system] and [coupling] (t0 from [initial_conditions]).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..systems.base import check_bodies
from .axes import COUPLING_AXES, GRID_AXES
from .expressions import parse_multiple
from .limits import (
    MAX_GRID_VALUES,
    MAX_INITIAL_CONDITIONS,
    MAX_SEED,
    t0_problem,
)
from .reader import ConfigError, Section, positive


@dataclass(frozen=True)
class Grid:
    """The parameter points of a sweep.

    Cartesian (default): ``axes`` holds the values of every axis (length 1 when not swept)
    and the points are their product, dims ``parameters + GRID_AXES``. Panels (``[grid]
    panels = [{d = .., phi = ..}, ...]``): an explicit list of points along one dim
    ``panel``, each axis a coordinate of it (``axes`` then holds the per-panel values).
    ``parameters``: the model parameters swept besides GRID_AXES (``config.axes``), each a
    dim of its own; they take their values from ``axes`` at every point.
    """

    axes: Mapping[str, tuple[float, ...]]
    swept: tuple[str, ...]
    panels: bool = False
    parameters: tuple[str, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        """Every axis with a value at each point: the swept parameters, then GRID_AXES."""
        return self.parameters + GRID_AXES

    @property
    def dims(self) -> tuple[str, ...]:
        return ("panel",) if self.panels else self.names

    @property
    def shape(self) -> tuple[int, ...]:
        if self.panels:
            return (len(self.axes["d"]),)
        return tuple(len(self.axes[a]) for a in self.names)

    @property
    def size(self) -> int:
        # Python integers: np.prod wraps around in int64 (65536**4 gives 0)
        return math.prod(self.shape)

    def point(self, flat: int) -> dict[str, float]:
        """Axis values of grid point number ``flat`` (C order over the dims)."""
        if self.panels:
            return {a: self.axes[a][flat] for a in self.names}
        index = np.unravel_index(flat, self.shape)
        return {a: self.axes[a][i] for a, i in zip(self.names, index, strict=True)}

    def distinct(self, axis: str) -> tuple[float, ...]:
        """The distinct values ``axis`` takes over the grid, in first-seen order."""
        return tuple(dict.fromkeys(self.axes[axis]))


@dataclass(frozen=True)
class InitialConditions:
    """Initial states of a sweep.

    plane: ``axes`` two state variables on a ``resolution`` grid over ``ranges``, the
    others at ``fixed``; random: uniform in ``box`` (n samples, seed); list: ``states``.
    ``t0``: time at which the state is imposed (None: uniform in [0, T) per sample).
    """

    kind: str
    state_names: tuple[str, ...]
    axes: tuple[str, ...] = ()
    ranges: tuple[tuple[float, float], ...] = ()
    resolution: tuple[int, ...] = ()
    fixed: Mapping[str, float] | None = None
    box: Mapping[str, tuple[float, float]] | None = None
    n: int = 0
    seed: int = 0
    states: tuple[tuple[float, ...], ...] = ()
    t0: float | None = 0.0

    @property
    def count(self) -> int:
        if self.kind == "plane":
            return math.prod(self.resolution)
        if self.kind == "random":
            return self.n
        return len(self.states)

    @property
    def dims(self) -> tuple[str, ...]:
        return self.axes if self.kind == "plane" else ("sample",)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(self.resolution) if self.kind == "plane" else (self.count,)

    def coords(self) -> dict[str, np.ndarray]:
        if self.kind == "plane":
            return {a: np.linspace(lo, hi, n) for a, (lo, hi), n
                    in zip(self.axes, self.ranges, self.resolution, strict=True)}
        return {"sample": np.arange(self.count)}

    def array(self) -> np.ndarray:
        """(count, dim) initial states in C order over ``dims``."""
        names = self.state_names
        if self.kind == "list":
            return np.array(self.states, dtype=float).reshape(-1, len(names))
        out = np.zeros((self.count, len(names)))
        if self.kind == "plane":
            for name, value in (self.fixed or {}).items():
                out[:, names.index(name)] = value
            c = self.coords()
            mesh = np.meshgrid(c[self.axes[0]], c[self.axes[1]], indexing="ij")
            for axis, values in zip(self.axes, mesh, strict=True):
                out[:, names.index(axis)] = values.ravel()
            return out
        rng = np.random.default_rng(self.seed)
        samples = rng.uniform(size=(self.count, len(names)))
        for j, name in enumerate(names):
            lo, hi = self.box[name]
            out[:, j] = lo + (hi - lo) * samples[:, j]
        return out

    def random_t0(self, period: float) -> np.ndarray:
        """Per-sample start times in [0, T) for ``t0 = "random"`` (own stream of the seed)."""
        rng = np.random.default_rng([self.seed, 1])
        return rng.uniform(0.0, period, self.count)


@dataclass(frozen=True)
class CatalogueSettings:
    """[catalogue]: how the labels' catalogue is searched (see the catalogue analysis)."""

    box: Mapping[str, tuple[float, float]]
    grid: int = 16
    random: int = 200
    seed: int = 0
    match_tol: float = 1e-3


def _values(sec: Section, key: str, symbol: str | None, unit: float) -> tuple[float, ...]:
    """One grid axis: a value, a list, {start, stop, num} or {start, stop, step}."""
    raw = sec.raw(key)

    def one(v, where=key):
        if symbol is not None:
            try:
                return parse_multiple(v, symbol, unit)
            except ValueError as exc:
                raise sec.fail(where, str(exc)) from None
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise sec.fail(where, f"must be finite numbers, got {v!r}")
        return float(v)

    if isinstance(raw, list):
        if not raw:
            raise sec.fail(key, "is an empty list; give at least one value")
        values = tuple(one(v) for v in raw)
    elif isinstance(raw, dict):
        keys = set(raw)
        if keys not in ({"start", "stop", "num"}, {"start", "stop", "step"}):
            raise sec.fail(key, "a range is {start, stop, num} or {start, stop, step}, got "
                                f"keys {sorted(keys)}")
        start = one(raw["start"], f"{key}.start")
        stop = one(raw["stop"], f"{key}.stop")
        if "num" in raw:
            num = raw["num"]
            if isinstance(num, bool) or not isinstance(num, int) or num < 1:
                raise sec.fail(f"{key}.num", f"must be a whole number >= 1, got {num!r}")
            if num > MAX_GRID_VALUES:  # before np.linspace allocates it
                raise sec.fail(f"{key}.num", f"{num} values; at most {MAX_GRID_VALUES} per axis")
            if num > 1 and start == stop:
                raise sec.fail(key, "start == stop with num > 1 repeats one value")
            values = tuple(np.linspace(start, stop, num).tolist())
        else:
            step = one(raw["step"], f"{key}.step")
            if step == 0 or (stop - start) * step < 0:
                raise sec.fail(f"{key}.step", f"must be nonzero and lead from start {start:g} "
                                              f"to stop {stop:g}, got {step!r}")
            span = (stop - start) / step  # inf when stop - start overflows
            if not span < MAX_GRID_VALUES:
                raise sec.fail(key, f"{span:.3g} steps from start to stop; at most "
                                    f"{MAX_GRID_VALUES} values per axis")
            num = int(math.floor(span + 1e-9)) + 1
            values = tuple((start + step * np.arange(num)).tolist())
    else:
        values = (one(raw),)
    if len(values) > MAX_GRID_VALUES:
        raise sec.fail(key, f"{len(values)} values; at most {MAX_GRID_VALUES} per axis")
    return values


def read_grid(source: str, doc: dict, values: Mapping, bodies: int, period: float,
              check_value, parameters: tuple[str, ...] = (), chain: bool = False) -> Grid:
    """[grid] for a sweep; ``check_value(axis, value)`` returns a problem or None.

    ``parameters``: the model parameters the kind can sweep besides the coupling and t0
    (``config.axes.parameter_axes``; empty where it sweeps those only). A parameter absent
    from ``values`` (the exponent of a law without one) is refused. ``chain``: a chain's
    grid, its axes named as the chain names its parameters (``stop.1.d = [..]``, TOML
    dotted or quoted: :func:`flat_grid`), no pair's coupling.
    """
    table = doc.get("grid", {})
    sec = Section(source, "grid", flat_grid(table) if chain else table)
    if not chain:
        check_bodies(bodies, "[grid] (coupling axes of one pair)")
    coupling = COUPLING_AXES if bodies == 2 and not chain else ()
    allowed = tuple(parameters) + coupling + ("t0",)
    if sec.has("panels"):
        return _read_panels(sec, values, allowed, period, check_value)
    axes: dict[str, tuple[float, ...]] = {}
    for axis in allowed:
        if sec.has(axis):
            _check_parameter(sec, axis, axis, values)
            if axis == "phi" or axis.startswith("phi."):  # a chain's body phase too
                axes[axis] = _values(sec, axis, "pi", math.pi)
            elif axis == "t0":
                axes[axis] = _values(sec, axis, "T", period)
            else:
                axes[axis] = _values(sec, axis, None, 1.0)
            for v in axes[axis]:
                problem = check_value(axis, v)
                if problem:
                    raise sec.fail(axis, f"{problem}, got {v!r}")
    sec.finish(allowed)
    if "w" in axes and "t0" in axes:
        raise sec.fail("t0", W_SWEPT_T0)
    swept = tuple(axes)
    points = math.prod(len(v) for v in axes.values())
    if points > MAX_GRID_VALUES:
        shape = " x ".join(str(len(v)) for v in axes.values())
        raise sec.fail(None, f"{points} grid points ({shape}); at most {MAX_GRID_VALUES}")
    for axis in GRID_AXES:
        if axis not in axes:
            axes[axis] = (float(values.get(axis, 0.0)),) if axis != "t0" else (0.0,)
    return Grid(axes, swept, parameters=tuple(a for a in parameters if a in swept))


# why a start time cannot go with a swept w (the t0 of [grid] or [initial_conditions])
W_SWEPT_T0 = ("cannot be set while w is swept: the forcing period 2 pi / w changes from "
              "point to point, so one start time would be another phase at each; every "
              "point starts at t0 = 0, its section time")


def _check_parameter(sec: Section, where: str, axis: str, values: Mapping) -> None:
    """A model parameter the scene does not have (a stop law's key under another law)."""
    if axis not in GRID_AXES and axis not in values:
        raise sec.fail(where, f"is not a parameter of this scene (its stop law "
                              f"{values.get('law', 'paper')!r} has no {axis})")


def _read_panels(sec: Section, values: Mapping, allowed: tuple[str, ...], period: float,
                 check_value) -> Grid:
    """[grid] panels = [{d = .., phi = ..}, ...]: an explicit list of parameter points."""
    panels = sec.raw("panels")
    sec.finish(("panels",))  # panels exclude the other grid keys
    if isinstance(panels, list):  # a chain's {stop.1.d = ..}: TOML nests dotted keys
        panels = [flat_grid(p) if isinstance(p, dict) else p for p in panels]
    if not isinstance(panels, list) or not panels or not all(isinstance(p, dict)
                                                            for p in panels):
        raise sec.fail("panels", "must be a non-empty list of tables like {d = 10.0, "
                                 "phi = \"pi\"}")
    if len(panels) > MAX_GRID_VALUES:
        raise sec.fail("panels", f"{len(panels)} panels; at most {MAX_GRID_VALUES}")
    parameters = tuple(a for a in allowed if a not in GRID_AXES
                       and any(a in p for p in panels))
    axes: dict[str, list[float]] = {a: [] for a in parameters + GRID_AXES}
    swept = []
    for i, panel in enumerate(panels):
        for key in panel:
            if key not in allowed:
                raise sec.fail(f"panels[{i}].{key}", f"unknown key; allowed: "
                                                     f"{', '.join(allowed)}")
            _check_parameter(sec, f"panels[{i}].{key}", key, values)
        if "w" in panel and "t0" in panel:
            raise sec.fail(f"panels[{i}].t0", W_SWEPT_T0)
        for axis in axes:
            where = f"panels[{i}].{axis}"
            if axis in panel:
                raw = panel[axis]
                try:
                    if axis == "phi" or axis.startswith("phi."):
                        v = parse_multiple(raw, "pi", math.pi)
                    elif axis == "t0":
                        v = parse_multiple(raw, "T", period)
                    elif isinstance(raw, bool) or not isinstance(raw, int | float):
                        raise ValueError(f"must be a number, got {raw!r}")
                    else:
                        v = float(raw)
                except ValueError as exc:
                    raise sec.fail(where, str(exc)) from None
                problem = check_value(axis, v)
                if problem:
                    raise sec.fail(where, f"{problem}, got {v!r}")
                if axis not in swept:
                    swept.append(axis)
            else:
                v = float(values.get(axis, 0.0)) if axis != "t0" else 0.0
            axes[axis].append(v)
    if "w" in swept and "t0" in swept:
        raise sec.fail("panels", W_SWEPT_T0.replace("cannot be set", "t0 cannot be set"))
    return Grid({a: tuple(v) for a, v in axes.items()}, tuple(swept), panels=True,
                parameters=parameters)


def read_box(sec: Section, key: str, names: tuple[str, ...], default=None, required=True):
    """A box {name = [lo, hi], ...} over ``names``; missing names take ``default``."""
    raw = sec.raw(key, None)
    if raw is None:
        if required and default is None:
            raise sec.fail(key, f"is required: a table {{{names[0]} = [lo, hi], ...}} over "
                                f"{', '.join(names)}")
        raw = {}
    if not isinstance(raw, dict):
        raise sec.fail(key, f"must be a table like {{{names[0]} = [-1, 1]}}, got {raw!r}")
    for name in raw:
        if name not in names:
            raise sec.fail(f"{key}.{name}", f"is not a state variable; allowed: "
                                           f"{', '.join(names)}")
    box = {}
    for name in names:
        lo_hi = raw.get(name, default[name] if default and name in default else None)
        if lo_hi is None:
            raise sec.fail(f"{key}.{name}", "is missing: give [low, high]")
        ok = (isinstance(lo_hi, list | tuple) and len(lo_hi) == 2
              and all(isinstance(v, int | float) and not isinstance(v, bool)
                      and math.isfinite(v) for v in lo_hi))
        if not ok or not lo_hi[0] < lo_hi[1]:
            raise sec.fail(f"{key}.{name}", f"must be [low, high] with low < high, got "
                                           f"{lo_hi!r}")
        box[name] = (float(lo_hi[0]), float(lo_hi[1]))
    return box


def read_initial_conditions(source: str, doc: dict, names: tuple[str, ...], period: float,
                            t0_swept: bool, w_swept: bool = False) -> InitialConditions:
    """[initial_conditions]; ``w_swept``: the grid sweeps w, so t0 stays 0 (W_SWEPT_T0)."""
    if "initial_conditions" not in doc:
        raise ConfigError(f"{source}: [initial_conditions]: is required for this analysis "
                          "(kind = \"plane\", \"random\" or \"list\")")
    sec = Section(source, "initial_conditions", doc["initial_conditions"])
    kind = sec.choice("kind", "plane", ("plane", "random", "list"))
    t0: float | None = 0.0
    if sec.has("t0"):
        if t0_swept:
            raise sec.fail("t0", "is also swept in [grid]; give it in one place")
        if w_swept and sec.raw("t0") not in (0, 0.0):
            raise sec.fail("t0", W_SWEPT_T0)
        raw = sec.raw("t0")
        if raw == "random":
            if kind != "random":
                raise sec.fail("t0", 't0 = "random" needs kind = "random"')
            t0 = None
        else:
            t0 = sec.multiple("t0", 0.0, "T", period)
            problem = "must be >= 0" if t0 < 0 else t0_problem(t0, period)
            if problem:
                raise sec.fail("t0", f"{problem}, got {t0!r}")
    if kind == "plane":
        axes = sec.raw("axes", list(names[::2][:2]) if len(names) == 4 else list(names))
        if isinstance(axes, list):  # a state variable by its index (0: x1, 1: v1, ...)
            axes = [names[a] if isinstance(a, int) and not isinstance(a, bool)
                    and 0 <= a < len(names) else a for a in axes]
        if (not isinstance(axes, list) or len(axes) != 2 or any(a not in names for a in axes)
                or axes[0] == axes[1]):
            raise sec.fail("axes", f"must be two different state variables out of "
                                   f"{', '.join(names)} (or their indices 0 to "
                                   f"{len(names) - 1}), got {axes!r}")
        ranges = sec.raw("ranges")
        if (not isinstance(ranges, list) or len(ranges) != 2
                or any(not isinstance(r, list) or len(r) != 2 for r in ranges)):
            raise sec.fail("ranges", f"must be two [low, high] pairs, got {ranges!r}")
        box = read_box(Section(source, "initial_conditions", {"ranges": dict(zip(axes, ranges,
                                                                             strict=True))}),
                   "ranges", tuple(axes))
        res = sec.raw("resolution", [100, 100])
        if isinstance(res, int) and not isinstance(res, bool):
            res = [res, res]
        if (not isinstance(res, list) or len(res) != 2
                or any(isinstance(r, bool) or not isinstance(r, int) or r < 1 for r in res)):
            raise sec.fail("resolution", f"must be two whole numbers >= 1, got {res!r}")
        if math.prod(res) > MAX_INITIAL_CONDITIONS:  # Python integers: no int64 wrap-around
            raise sec.fail("resolution", f"{res[0]} x {res[1]} = {math.prod(res)} initial "
                                         f"conditions; at most {MAX_INITIAL_CONDITIONS}")
        fixed_raw = sec.raw("fixed", {})
        if not isinstance(fixed_raw, dict):
            raise sec.fail("fixed", f"must be a table like {{v1 = 0.0}}, got {fixed_raw!r}")
        fixed = {}
        for name, value in fixed_raw.items():
            off_plane = [n for n in names if n not in axes]
            if name not in off_plane:
                raise sec.fail(f"fixed.{name}", "must be a state variable off the plane; "
                                                f"allowed: {', '.join(off_plane)}")
            if (isinstance(value, bool) or not isinstance(value, int | float)
                    or not math.isfinite(value)):
                raise sec.fail(f"fixed.{name}", f"must be a finite number, got {value!r}")
            fixed[name] = float(value)
        sec.finish(("kind", "axes", "ranges", "resolution", "fixed", "t0"))
        return InitialConditions(kind, names, tuple(axes), tuple(box[a] for a in axes),
                                 tuple(res), fixed, t0=t0)
    if kind == "random":
        box = read_box(sec, "box", names)
        n = sec.integer("n", 1000, 1, MAX_INITIAL_CONDITIONS)
        seed = sec.integer("seed", 0, 0, MAX_SEED)
        sec.finish(("kind", "box", "n", "seed", "t0"))
        return InitialConditions(kind, names, box=box, n=n, seed=seed, t0=t0)
    states = sec.raw("states")
    if not isinstance(states, list) or not states:
        raise sec.fail("states", f"must be a non-empty list of [{', '.join(names)}] states")
    rows = []
    for row in states:
        if (not isinstance(row, list) or len(row) != len(names)
                or any(isinstance(v, bool) or not isinstance(v, int | float)
                       or not math.isfinite(v) for v in row)):
            raise sec.fail("states", f"each state must be {len(names)} finite numbers "
                                     f"({', '.join(names)}), got {row!r}")
        rows.append(tuple(float(v) for v in row))
    sec.finish(("kind", "states", "t0"))
    return InitialConditions(kind, names, states=tuple(rows), t0=t0)


def read_catalogue(source: str, doc: dict, default_box) -> CatalogueSettings:
    sec = Section(source, "catalogue", doc.get("catalogue", {}))
    settings = CatalogueSettings(
        box=read_box(sec, "box", ("x", "v"), default_box),
        grid=sec.integer("grid", 16, 0, 2000),
        random=sec.integer("random", 200, 0, 10_000_000),
        seed=sec.integer("seed", 0, 0, MAX_SEED),
        match_tol=sec.number("match_tol", 1e-3, positive),
    )
    if settings.grid == 0 and settings.random == 0:
        raise sec.fail("grid", "grid and random are both 0: no initial conditions")
    sec.finish()
    return settings


_RANGE_KEYS = ({"start", "stop", "num"}, {"start", "stop", "step"})


def flat_grid(table: Mapping, prefix: str = "") -> dict:
    """[grid] with TOML dotted keys joined back into parameter names: ``phi.3 = [..]``
    (read by TOML as ``{"phi": {"3": [..]}}``) and ``"phi.3" = [..]`` both give
    ``{"phi.3": [..]}``; a range table ({start, stop, num|step}) stays a value."""
    out: dict = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and set(value) not in _RANGE_KEYS:
            out.update(flat_grid(value, name + "."))
        else:
            out[name] = value
    return out


def read_parameter_axis(source: str, doc: dict, parameters, what: str
                        ) -> tuple[str, tuple[float, ...]] | None:
    """[grid] of one model parameter named as the system names it (a chain's ``phi.3``,
    ``F.1``, ``w``, ``stop.2.d``): (name, values), or None without [grid].

    parameters : the system's :class:`~softimpact_cli.systems.base.Parameter` the kind can
        sweep (each value is checked against its limits); what : the kind, for errors.
    A phase (``phi`` or ``phi.i``) also takes the pi forms ("5*pi/8").
    """
    if "grid" not in doc:
        return None
    sec = Section(source, "grid", flat_grid(doc["grid"]))
    allowed = {p.name: p for p in parameters}
    given = list(sec.table)
    if len(given) != 1:
        raise sec.fail(None, f"{what} sweeps one parameter; got {len(given)} "
                             f"({', '.join(given) or 'none'})")
    axis = given[0]
    if axis not in allowed:
        raise sec.fail(axis, f"is not a parameter {what} can sweep; parameters: "
                             f"{', '.join(allowed)}")
    phase = axis == "phi" or axis.startswith("phi.")
    values = _values(sec, axis, "pi" if phase else None, math.pi if phase else 1.0)
    for v in values:
        problem = allowed[axis].check(v)
        if problem:
            raise sec.fail(axis, f"{problem}, got {v!r}")
    sec.finish((axis,))
    return axis, values
