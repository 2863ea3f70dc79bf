"""``info`` of a lyapunov result: the spectra as a dict (JSON) and as a table."""

from __future__ import annotations

import numpy as np


def lyapunov_summary(ds) -> dict:
    """Per run its solution, exponents, standard errors and Floquet exponents (1/time)."""
    spectra = []
    for i in range(ds.sizes["run"]):
        row = {"solution": str(ds["solution"].values[i]),
               "exponents": [float(x) for x in ds["exponent"].values[i]],
               "stderr": [float(x) for x in ds["exponent_stderr"].values[i]],
               "status": int(ds["status"].values[i]),
               "switches": int(ds["switches"].values[i])}
        floquet = ds["floquet_exponent"].values[i]
        if np.all(np.isfinite(floquet)):
            row["floquet"] = [float(x) for x in floquet]
        spectra.append(row)
    return {"lyapunov_source": ds.attrs.get("source"), "spectra": spectra}


def format_lyapunov(ds) -> str:
    """One line per spectrum: exponents +- standard error (1/time), Floquet beside."""
    a = ds.attrs
    T = float(a.get("forcing_period", np.nan))
    salt = "with saltation matrices" if a.get("saltation", 1) else "WITHOUT saltation"
    lines = [f"Lyapunov exponents (1/time; x T = {T:.4g} per forcing period), {salt}; "
             f"{a.get('transient')} + {a.get('periods')} periods, mean +- standard error of "
             f"{a.get('segments')} segments"]
    width = max(10, max((len(str(s)) for s in ds["solution"].values), default=10))
    for i in range(ds.sizes["run"]):
        exps = ds["exponent"].values[i]
        errs = ds["exponent_stderr"].values[i]
        cells = "  ".join(f"{e:+.5f} +- {s:.1e}" for e, s in zip(exps, errs, strict=True))
        line = f"  {str(ds['solution'].values[i]):{width}s}  {cells}"
        floquet = ds["floquet_exponent"].values[i]
        if np.all(np.isfinite(floquet)):
            line += "   Floquet " + " ".join(f"{f:+.5f}" for f in floquet)
        if a.get("source") == "catalogue" and int(ds["switches"].values[i]) > 0:
            line += "   (collides at this d: the spectrum of where it went)"
        if int(ds["status"].values[i]) != 0:
            line += f"   (failed: status {int(ds['status'].values[i])})"
        lines.append(line)
    return "\n".join(lines)
