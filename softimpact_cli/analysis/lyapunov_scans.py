"""Lyapunov spectra as datasets: of one trajectory, of every catalogue solution, along a
parameter (``analysis/lyapunov.py`` computes each spectrum).

Every dataset has dims ``run`` (one spectrum each: the trajectory, a catalogue solution, a
grid point) and ``order`` (1 .. dim, largest first), with ``exponent`` and
``exponent_stderr`` (run, order; 1/time), ``segment_exponent`` (run, segment, order),
``section_state`` (run, section, variable: the states every forcing period while averaging,
for a bifurcation-style panel), ``floquet_exponent`` (ln|mu| / (q T) of a catalogue
solution's multipliers; NaN elsewhere), and per run its ``solution`` name, ``status``,
``switches`` (the integration's wall time is ``attrs["spectra_wall_s"]``: a variable
would differ run to run). ``attrs["source"]`` is "state", "catalogue" or "grid"; a grid
run has the swept axis as a coordinate along ``run``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .chain_catalogue import ChainCatalogue
from .engine import Problem
from .lyapunov import Spectrum, floquet_exponents, lyapunov_spectrum


@dataclass(frozen=True)
class Averaging:
    """How each spectrum is averaged (see :func:`lyapunov.lyapunov_spectrum`)."""

    periods: int = 500
    transient: int = 50
    segments: int = 10
    per_period: int = 8
    saltation: bool = True

    def run(self, problem: Problem, state, t0: float) -> Spectrum:
        return lyapunov_spectrum(problem, state, t0, periods=self.periods,
                                 transient=self.transient, segments=self.segments,
                                 per_period=self.per_period, saltation=self.saltation)


def trajectory_spectrum(problem: Problem, state, t0: float, avg: Averaging):
    """The spectrum of the trajectory through ``state`` at ``t0``, as a dataset."""
    spec = avg.run(problem, state, t0)
    return spectra_dataset(problem, [spec], ["trajectory"], avg, "state")


def catalogue_spectra(problem: Problem, catalogue, avg: Averaging, progress=None):
    """The spectrum of every catalogue solution, from its section point 0 at t = 0: one
    body's attractors, a pair's combinations or a chain's products (joint orbits, every
    one of the catalogue as for a pair, whether or not a stop destroys it), with the
    Floquet exponents beside them (a combination's multipliers over its joint period q are
    the left and right bodies' over theirs, to the power q / p; their exponents are the
    bodies' ln|mu| / (p T), unchanged; a chain's product: every body's, likewise)."""
    T = problem.period
    specs, names, floquet = [], [], []
    if isinstance(catalogue, ChainCatalogue):
        for product in catalogue.products:
            specs.append(avg.run(problem, product.orbit[0], 0.0))
            names.append(product.name)
            floquet.append(np.sort(np.concatenate([
                floquet_exponents(a.multipliers, a.period, T)
                for a in product.attractors]))[::-1])
            if progress:
                progress(1)
    elif problem.system.bodies == 1:
        for a in catalogue.attractors:
            specs.append(avg.run(problem, a.points[0], 0.0))
            names.append(a.name)
            floquet.append(floquet_exponents(a.multipliers, a.period, T))
            if progress:
                progress(1)
    else:
        for c in catalogue.combinations:
            specs.append(avg.run(problem, c.orbit[0], 0.0))
            names.append(c.name)
            floquet.append(np.sort(np.concatenate([
                floquet_exponents(c.left.multipliers, c.left.period, T),
                floquet_exponents(c.right.multipliers, c.right.period, T)]))[::-1])
            if progress:
                progress(1)
    return spectra_dataset(problem, specs, names, avg, "catalogue", np.array(floquet))


def parameter_spectra(problem: Problem, state, t0: float, axis: str, values, avg: Averaging,
                      follow: bool = True, progress=None):
    """The spectrum at each value of ``axis`` (a coupling parameter or t0): from ``state``
    at the first value, and from the previous value's end state when ``follow`` (as a
    bifurcation diagram follows a branch) or from ``state`` at every value."""
    specs, current = [], np.asarray(state, dtype=float)
    for v in values:
        p = problem if axis == "t0" else problem.with_values(**{axis: float(v)})
        start_t = float(v) if axis == "t0" else t0
        spec = avg.run(p, current, start_t)
        specs.append(spec)
        if follow and spec.ok:
            current = spec.state  # at t_end = t0 + (transient + periods) T: same phase
        if progress:
            progress(1)
    names = [f"{axis} = {v:.6g}" for v in values]
    ds = spectra_dataset(problem, specs, names, avg, "grid")
    ds = ds.assign_coords({axis: ("run", np.asarray(values, dtype=float))})
    ds.attrs["axis"] = axis
    ds.attrs["follow"] = int(follow)
    return ds


def spectra_dataset(problem: Problem, specs: list[Spectrum], names: list[str],
                    avg: Averaging, source: str, floquet: np.ndarray | None = None):
    """The dataset of a list of spectra (see the module docstring)."""
    import xarray as xr

    n = problem.system.dim
    k = len(specs)
    exps = np.array([s.exponents for s in specs]).reshape(k, n)
    errs = np.array([s.stderr for s in specs]).reshape(k, n)
    segs = np.array([s.segments for s in specs]).reshape(k, avg.segments, n)
    sections = np.array([s.sections for s in specs]).reshape(k, -1, n)
    if floquet is None:
        floquet = np.full((k, n), np.nan)
    per_t = "1/time (dimensionless; times T: per forcing period)"
    data = {
        "exponent": (("run", "order"), exps,
                     {"long_name": "Lyapunov exponent (mean over segments)", "units": per_t}),
        "exponent_stderr": (("run", "order"), errs,
                            {"long_name": "standard error of the segment mean",
                             "units": per_t}),
        "segment_exponent": (("run", "segment", "order"), segs,
                             {"long_name": "each segment's estimate", "units": per_t}),
        "floquet_exponent": (("run", "order"), np.asarray(floquet, dtype=float),
                             {"long_name": "ln|mu| / (q T) of the catalogue's Floquet "
                                           "multipliers", "units": per_t}),
        "section_state": (("run", "section", "variable"), sections,
                    {"long_name": "state every forcing period while averaging",
                     "units": "1"}),
        "solution": (("run",), list(names)),
        "status": (("run",), [s.status for s in specs], {"long_name": "kernel status"}),
        "switches": (("run",), [s.switches for s in specs],
                     {"long_name": "switches crossed (saltation applied at each)"}),
    }
    coords = {"run": np.arange(k), "order": np.arange(1, n + 1),
              "segment": np.arange(avg.segments), "section": np.arange(sections.shape[1]),
              "variable": list(problem.system.state_names)}
    attrs = {"analysis": "lyapunov", "source": source, "forcing_period": problem.period,
             "periods": avg.periods, "transient": avg.transient, "segments": avg.segments,
             "per_period": avg.per_period, "saltation": int(avg.saltation),
             "spectra_wall_s": float(sum(s.wall for s in specs)),
             "method": "Benettin (Gram-Schmidt) on the variational equations, saltation "
                       "matrices at switches" if avg.saltation else
                       "Benettin on the variational equations WITHOUT saltation matrices"}
    return xr.Dataset(data, coords=coords, attrs=attrs)
