"""Uncertainty exponent alpha and the box-counting dimension D = 2 - alpha of a basin
boundary on a plane (Grebogi, McDonald, Ott, Yorke, Phys. Lett. A 99 (1983) 415).

A start is *eps-uncertain* when a perturbation of size eps can change its outcome. On a
grid of labels: the cell at (i, j) is uncertain at radius r (cells) when a cell within
Chebyshev distance r holds another label, i.e. when the (2r + 1) x (2r + 1) window
centred on it is not of one label. The share f(r) of uncertain cells (over the cells
whose window lies inside the plane) scales as

    f(r) ~ r^alpha,    D = 2 - alpha

(a smooth boundary: D = 1, alpha = 1; a fractal one: 1 < D < 2, 0 < alpha < 1; D is the
boundary's box-counting dimension). alpha is the least-squares slope of ln f against
ln r. Its interval is the regression's (standard error and a 95% Student-t interval):
f at neighbouring radii are correlated (their windows overlap), so the interval is a
fit interval, not a statistical guarantee; the slopes over the lower and the upper half
of the radii (``alpha_small``, ``alpha_large``) show whether ln f is straight over the
range, which matters more. Windows are centred on every cell (sliding, not a fixed
box grid), so a boundary aligned with box edges cannot hide. Radii where no cell is
uncertain are left out of the fit; with fewer than three left alpha is NaN.

Every distinct label is a basin of its own (see ``basin_entropy``).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from .basin_entropy import encode

Z975 = 1.959963984540054
EXACT_T975 = (12.706204736174707, 4.302652729749464, 3.182446305284263, 2.7764451051977987,
              2.570581835636314)


def t975(df: int) -> float:
    """The 97.5% quantile of Student's t with ``df`` degrees of freedom (two-sided 95%):
    exact up to 5, the Cornish-Fisher series of Abramowitz & Stegun 26.7.5 beyond
    (error < 1.1e-4 at df = 6, falling as 1 / df^5)."""
    if df < 1:
        return math.nan
    if df <= 5:
        return EXACT_T975[df - 1]
    z = Z975
    g = ((z**3 + z) / 4,
         (5 * z**5 + 16 * z**3 + 3 * z) / 96,
         (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384,
         (79 * z**9 + 776 * z**7 + 1482 * z**5 - 1920 * z**3 - 945 * z) / 92160)
    return z + sum(gk / df ** (k + 1) for k, gk in enumerate(g))


def window_extremes(codes: np.ndarray, r: int) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) of ``codes`` over every (2r + 1)-square window lying inside the plane:
    shape (rows - 2r, cols - 2r); separable running extremes."""
    w = 2 * r + 1
    lo = hi = codes
    for axis in (0, 1):
        m = lo.shape[axis] - w + 1
        take = [slice(None), slice(None)]
        parts_lo, parts_hi = [], []
        for k in range(w):
            take[axis] = slice(k, k + m)
            parts_lo.append(lo[tuple(take)])
            parts_hi.append(hi[tuple(take)])
        lo = np.minimum.reduce(parts_lo)
        hi = np.maximum.reduce(parts_hi)
    return lo, hi


def uncertain_fraction(codes: np.ndarray, r: int) -> float:
    """The share of cells uncertain at radius ``r`` (cells; only cells whose window is
    inside the plane count)."""
    lo, hi = window_extremes(np.asarray(codes), r)
    return float(np.count_nonzero(lo != hi)) / lo.size


def default_radii(shape: tuple[int, int]) -> tuple[int, ...]:
    """Radii 1 .. side / 10 cells (at least 1..3), about 12 spread evenly in ln r."""
    top = max(3, min(shape) // 10)
    return tuple(int(v) for v in np.unique(np.round(np.geomspace(1, top, 12))))


def fit_slope(x: np.ndarray, y: np.ndarray) -> dict:
    """Least-squares line y = a + b x: slope b, its standard error and 95% t interval."""
    m = len(x)
    if m < 3:
        return {"slope": math.nan, "stderr": math.nan, "low": math.nan, "high": math.nan,
                "intercept": math.nan}
    xm, ym = x.mean(), y.mean()
    sxx = float(((x - xm) ** 2).sum())
    b = float(((x - xm) * (y - ym)).sum() / sxx)
    a = float(ym - b * xm)
    resid = y - (a + b * x)
    se = math.sqrt(float((resid**2).sum()) / (m - 2) / sxx)
    half = t975(m - 2) * se
    return {"slope": b, "stderr": se, "low": b - half, "high": b + half, "intercept": a}


def uncertainty_exponent(labels: np.ndarray, radii=None) -> xr.Dataset:
    """f(r) over ``radii`` (cells; default :func:`default_radii`), alpha with its fit
    interval, D = 2 - alpha, and the radii the fit used (dims ``radius``)."""
    codes, _ = encode(labels)
    radii = tuple(radii) if radii is not None else default_radii(codes.shape)
    if not radii or any(isinstance(r, bool) or int(r) != r or r < 1 for r in radii) \
            or 2 * max(radii) + 1 > min(codes.shape):
        raise ValueError(f"radii: whole numbers of cells >= 1 with 2 r + 1 <= "
                         f"{min(codes.shape)} (the plane's shorter side), got {radii!r}")
    f = np.array([uncertain_fraction(codes, int(r)) for r in radii])
    r = np.asarray(radii, dtype=float)
    used = f > 0
    lx, ly = np.log(r[used]), np.log(f[used])
    fit = fit_slope(lx, ly)
    half = len(lx) // 2
    small = fit_slope(lx[: half + 1], ly[: half + 1])["slope"] if half >= 2 else math.nan
    large = fit_slope(lx[half:], ly[half:])["slope"] if len(lx) - half >= 3 else math.nan
    scalar = {
        "alpha": (fit["slope"], "uncertainty exponent alpha"),
        "alpha_stderr": (fit["stderr"], "standard error of alpha (least squares)"),
        "alpha_ci_low": (fit["low"], "alpha, 95% fit interval, low"),
        "alpha_ci_high": (fit["high"], "alpha, 95% fit interval, high"),
        "alpha_intercept": (fit["intercept"], "ln f at r = 1 cell (fitted)"),
        "alpha_small": (small, "alpha over the lower half of the radii"),
        "alpha_large": (large, "alpha over the upper half of the radii"),
        "dimension": (2.0 - fit["slope"], "box-counting dimension of the boundary, 2 - alpha"),
        "dimension_ci_low": (2.0 - fit["high"], "dimension, 95% fit interval, low"),
        "dimension_ci_high": (2.0 - fit["low"], "dimension, 95% fit interval, high"),
        "fit_radius_min": (float(r[used].min()) if used.any() else math.nan,
                           "smallest radius in the fit (cells)"),
        "fit_radius_max": (float(r[used].max()) if used.any() else math.nan,
                           "largest radius in the fit (cells)"),
    }
    data = {k: ((), v, {"long_name": name}) for k, (v, name) in scalar.items()}
    data["uncertain_fraction"] = ("radius", f, {"long_name": "share of uncertain cells f(r)",
                                                "units": "1"})
    data["in_fit"] = ("radius", used, {"long_name": "radius used in the fit (f > 0)"})
    return xr.Dataset(data, coords={"radius": ("radius", np.asarray(radii, dtype=np.int64),
                                               {"long_name": "perturbation radius eps",
                                                "units": "cells"})})
