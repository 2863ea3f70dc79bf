"""The Python API: scenes in, ``xarray.Dataset`` out, figures on your axes.

::

    import softimpact_cli as si

    scene = si.load_scene({"system": {"model": "duffing"}, "analysis": {"kind": "basins"},
                           "initial_conditions": {"resolution": [20, 20]}})
    ds = si.run(scene, workers=2)            # every kind; sweeps run in memory
    fig = si.plot.basins(ds, ax=ax)          # draws on ax, returns its Figure
    si.sweep(scene, "basins.h5", resume=True)  # the resumable result file of the CLI
    fr = si.measure("basins.h5", "fractality.h5")  # basin entropy, alpha, Wada test
    ds.si.shares()                           # each label's share, 95% interval (accessor.py)
    si.System(scene).classify([8, 0, -4, 0]) # one start's label (api_system.py)
    si.kinds()                               # every analysis kind, one help line each

Datasets come in the dim order of their file (``store.layout``: a plane's variables end
in its second axis, then its first, as ``xarray.open_dataset`` reads them); the figures
and :func:`measure` take either order.

The command line is a thin layer over these functions: ``softimpact sweep`` shrinks the
scene with :func:`shrink_scene`, runs it with :func:`sweep`, and ``softimpact plot`` /
``info`` open results with :func:`open_result`. Errors a user can cause raise
:class:`ConfigError` with the CLI's one-line message (the messages name the CLI's flags:
``--overwrite`` is ``overwrite=True`` here).

Progress is off by default (``progress=False``): a notebook cell stays quiet. Pass
``progress=True`` for a ``tqdm.auto`` bar (a widget in Jupyter, text elsewhere), or a
callable ``progress(total, initial) -> update`` as the CLI does; ``echo=print`` prints
the plan and catalogue lines the CLI shows.
"""

from __future__ import annotations

import os
import time
import warnings
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import xarray as xr

from . import (
    __version__,
    accessor,  # noqa: F401  (registers ds.si on the datasets handed out)
)
from .analysis.attributes import attribute_list
from .analysis.fractality import fractality, plane_problem
from .config import ConfigError, Scene, check_writable, result_path
from .config.space import check_disk, check_memory
from .config.toml_text import toml_text
from .kinds import KINDS, sweep_kinds
from .kinds import get as kind_of
from .kinds.run import run_scene
from .kinds.scene import load_scene as load_scene_file
from .kinds.scene import parse_scene
from .kinds.scene import quick as quick_scene
from .store import open_result as read_store
from .store import write_result
from .store.layout import file_order, memory_order
from .store.lock import output_lock
from .store.provenance import command_line, history_line, iso_time
from .store.xarray_dask import install
from .sweep import sweep_in_memory
from .sweep.executors import make_executor
from .sweep.pilot import choose_tolerance
from .sweep.verification import disabled_status, sweep_verified, verify_sweep

__all__ = ["ConfigError", "kinds", "load_scene", "measure", "open_result", "run",
           "shrink_scene", "sweep"]

SceneLike = Scene | str | os.PathLike | Mapping[str, Any]


def _silent(_: str) -> None:
    pass


def load_scene(scene: SceneLike, source: str | None = None) -> Scene:
    """A validated Scene from a scene file path, TOML text, or a mapping of sections.

    - a ``Path`` (or a string without a newline and without "=") is a scene file;
    - other strings are TOML text;
    - a mapping (``{"system": {"model": "duffing"}, "analysis": {...}}``) is validated
      exactly as the TOML it mirrors: it is written as that TOML text (stored in the
      result and hashed for resuming), and the same checks give the same messages;
    - a Scene is returned as it is.

    ``source`` names a text or mapping scene in messages and result attributes (default
    "<string>" / "<dict>"; its result file defaults to results/scene.h5). Raises
    ConfigError with the CLI's one-line message.
    """
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, Mapping):
        name = source or "<dict>"
        return parse_scene(toml_text(scene, name), name)
    if isinstance(scene, str) and ("\n" in scene or "=" in scene or not scene.strip()):
        return parse_scene(scene, source or "<string>")
    if isinstance(scene, str | os.PathLike):
        return load_scene_file(scene)
    raise ConfigError(f"load_scene: expected a scene file path, TOML text or a mapping of "
                      f"sections, got {type(scene).__name__}")


def shrink_scene(scene: Scene, quick: bool = False, resolution: int | None = None) -> Scene:
    """The scene at the CLI's ``--quick`` (planes <= 24 x 24, <= 100 samples, <= 6 values
    per swept grid axis, fewer dcrit phases and d steps) and/or ``--resolution N`` (a
    plane's resolution per axis capped at N, grids kept); the stored scene text says so."""
    if quick:
        scene = quick_scene(scene)
    if resolution:
        if isinstance(resolution, bool) or not isinstance(resolution, int) or resolution < 1:
            raise ConfigError(f"resolution: must be a whole number >= 1, got {resolution!r}")
        scene = quick_scene(scene, plane=resolution, samples=10**12,
                            flag=f"--resolution {resolution}", axis=None)
    return scene


def _progress(progress: bool | Callable | None, unit: str) -> Callable | None:
    """A progress factory ``(total, initial=0) -> update``: None (off), the caller's own,
    or a ``tqdm.auto`` bar that closes itself when full (and stays: how long it took)."""
    if not progress:
        return None
    if callable(progress):
        return progress

    def start(total: int, initial: int = 0):
        from tqdm.auto import tqdm

        bar = tqdm(total=total, initial=initial, unit=unit, smoothing=0.1)

        def update(work) -> None:
            bar.update(len(work) if hasattr(work, "__len__") else work)
            if bar.n >= total:
                bar.close()

        return update

    return start


def run(scene: SceneLike, *, quick: bool = False, resolution: int | None = None,
        workers: int | None = None, scheduler: str | None = None,
        chunk_size: int | None = None, progress: bool | Callable = False,
        echo: Callable[[str], None] | None = None, verify: bool = True,
        verify_sample: int | None = None) -> xr.Dataset:
    """Run any scene and return its ``xarray.Dataset``; no file is read or written.

    ``scene``: a Scene or anything :func:`load_scene` takes. ``quick`` and
    ``resolution``: the CLI's ``--quick`` and ``--resolution N``. ``workers``: local
    processes (default all cores; 1 runs in this process) or ``scheduler`` a Dask
    address (``tcp://HOST:PORT``, ``local:N``), for the kinds that use them (sweeps,
    dcrit, bifurcation, design). Sweep kinds (basins, stability, map) run their chunks in
    memory (``chunk_size`` trajectories each; not resumable: use :func:`sweep` for
    that) and return the dataset their result file would hold. ``progress``: False
    (default), True for a ``tqdm.auto`` bar, or a factory as in the module docstring.

    ``verify`` (default True): a sweep reruns a random sample at tight settings, bounds
    its label error and, over the [verification] threshold, redoes itself at tighter
    settings (``sweep.verification``); its ``verify_*`` attributes say what was found.
    ``verify_sample``: the number rerun (default from [verification]). ``verify=False``
    records "not verified (disabled by --no-verify)".
    """
    install()  # no dask imported for datasets that hold none (store/xarray_dask.py)
    _check_verify_sample(verify_sample)
    sc = shrink_scene(load_scene(scene), quick, resolution)
    kind = kind_of(sc.analysis.kind)
    bar = _progress(progress, kind.progress_unit)
    if kind.sweep:
        return _handed_out(_sweep_in_memory(sc, workers, scheduler, chunk_size,
                                            echo or _silent, bar, verify, verify_sample))

    return _handed_out(run_scene(sc, progress=bar, workers=workers, scheduler=scheduler,
                                 echo=echo or _silent))


def _handed_out(ds: xr.Dataset) -> xr.Dataset:
    """A dataset as the API hands it out: in the dim order of its file (a plane's
    variables end in (second axis, first axis), as ``xarray.open_dataset`` reads them, so
    that ``ds.label.plot()`` puts the first axis horizontally; ``store.layout``), with
    the ``ds.si`` accessor registered (``accessor.py``)."""
    return file_order(ds)


def kinds() -> dict[str, str]:
    """Every analysis kind (``[analysis] kind = ...``) with its one-line help, in the
    order ``softimpact sweep --help`` lists them (the kinds registry)."""
    return {name: kind.description for name, kind in KINDS.items()}


def _check_verify_sample(verify_sample) -> None:
    if verify_sample is not None and (isinstance(verify_sample, bool) or
                                      not isinstance(verify_sample, int) or verify_sample < 1):
        raise ConfigError(f"verify_sample: must be a whole number >= 1 (or None: from "
                          f"[verification]), got {verify_sample!r}")


def _sweep_in_memory(sc: Scene, workers, scheduler, chunk_size, echo, bar, verify: bool,
                     verify_sample: int | None) -> xr.Dataset:
    """A sweep kind run in memory, then verified (or recorded as not verified)."""
    if not (verify and (sc.verification is None or sc.verification.enabled)):
        ds = sweep_in_memory(sc, workers, scheduler, chunk_size, echo, bar)
        ds.attrs["verify_status"] = disabled_status(
            "--no-verify" if not verify else "[verification] enabled = false")
        return ds
    executor = make_executor(workers, scheduler)
    sc, pilot = choose_tolerance(sc, verify_sample, executor, echo)
    ds = sweep_in_memory(sc, workers, scheduler, chunk_size, echo, bar)
    ds.attrs.update(pilot)
    return verify_sweep(sc, ds, lambda tighter, _: sweep_in_memory(
        tighter, workers, scheduler, chunk_size, echo, bar), verify_sample, executor, echo)


def sweep(scene: SceneLike, out: str | os.PathLike | None = None, *, resume: bool = False,
          overwrite: bool = False, workers: int | None = None, scheduler: str | None = None,
          chunk_size: int | None = None, quick: bool = False, resolution: int | None = None,
          progress: bool | Callable = False, echo: Callable[[str], None] | None = None,
          verify: bool = True, verify_sample: int | None = None) -> xr.Dataset:
    """Run a scene into its result file ``out`` (default: its [output] path), as
    ``softimpact sweep`` does, and return the complete dataset.

    Sweep kinds write chunk by chunk: an interrupted run (a killed kernel, Ctrl-C) keeps
    its finished chunks, and ``resume=True`` finishes it (same scene required; with
    nothing to resume it starts afresh). Other kinds run whole and write at the end
    (``resume`` is refused). An existing result needs ``overwrite=True``. The other
    options are those of :func:`run`.

    A sweep is verified after it completes (``verify``, ``verify_sample``: see
    :func:`run`); a redo at tighter settings is written beside ``out`` and replaces it
    when done, and ``resume=True`` also finishes an interrupted verification.
    """
    install()  # no dask imported for datasets that hold none (store/xarray_dask.py)
    _check_verify_sample(verify_sample)
    sc = shrink_scene(load_scene(scene), quick, resolution)
    target = result_path(sc, None if out is None else str(out))
    check_writable(target, str(sc.source) if out is None else "sweep", "[output] path"
                   if out is None else "out")
    kind = kind_of(sc.analysis.kind)
    bar = _progress(progress, kind.progress_unit)
    echo = echo or _silent
    if kind.sweep:
        return _handed_out(sweep_verified(
            sc, target, verify=verify, sample=verify_sample, resume=resume, echo=echo,
            workers=workers, scheduler=scheduler, overwrite=overwrite, chunk_size=chunk_size,
            progress=bar))
    if resume:
        raise ConfigError(f"{sc.source}: resume is for sweeps (kinds "
                          f"{', '.join(sweep_kinds())}); a {kind.name} reruns whole")

    # held for the whole run: a second run on the same output is refused at once, not
    # after it has computed everything
    with output_lock(target, command_line()):
        if target.exists() and not overwrite:
            raise ConfigError(f"{target}: result exists; pass --overwrite to replace it")
        if kind.result_bytes is not None:  # a full disk said now, not after the run
            need = kind.result_bytes(sc)
            check_memory(need, f"{sc.source}: [analysis]", "reduce what it records")
            check_disk(target, need)
        ds = run_scene(sc, progress=bar, workers=workers, scheduler=scheduler, echo=echo)
        write_result(ds, target)
    return _handed_out(ds)


def open_result(path: str | os.PathLike) -> xr.Dataset:
    """A softimpact result file as an ``xarray.Dataset`` (loaded; the file is closed), in
    the dim order ``xarray.open_dataset`` gives it (as :func:`run` hands results out).
    ConfigError when it is missing, a directory, or not a softimpact result."""
    return _handed_out(read_result(path))


def read_result(path: str | os.PathLike) -> xr.Dataset:
    """:func:`open_result` in the package's in-memory dim order (``store.layout``): what
    the command line's ``plot``, ``info`` and ``compare`` read."""
    p = Path(path)
    if p.is_dir():
        raise ConfigError(f"{path}: is a directory, not a result file")
    if not p.is_file():
        raise ConfigError(f"{path}: no such result file")
    try:
        with warnings.catch_warnings():  # a foreign HDF5 file: the reader's warnings are noise
            warnings.simplefilter("ignore")
            ds = read_store(p)
    except Exception as exc:  # any reader failure is the file's fault, said in one line
        raise ConfigError(f"{path}: not a softimpact result file ({exc.__class__.__name__})"
                          ) from None
    if "analysis" not in ds.attrs or "scene_text" not in ds.attrs:
        raise ConfigError(f"{path}: not a softimpact result file (an HDF5 file without the "
                          "'analysis' and 'scene_text' attributes softimpact writes)")
    problem = _result_problem(ds)
    if problem:
        raise ConfigError(f"{path}: {problem}")
    return ds


def _result_problem(ds: xr.Dataset) -> str | None:
    """What keeps ``ds``, which carries softimpact's attributes, from being a result the
    commands can read (None: nothing): its ``analysis`` names no kind, its ``complete``
    is not 0 or 1, or a complete result lacks a variable every result of its kind holds
    (a hand-made file, or one another tool took variables from)."""
    analysis = ds.attrs["analysis"]
    kind = KINDS.get(analysis) if isinstance(analysis, str) else None
    if kind is None:
        return (f"not a softimpact result file (its 'analysis' attribute is {analysis!r}, "
                f"not one of the kinds {', '.join(KINDS)})")
    complete = ds.attrs.get("complete", 1)
    if isinstance(complete, bool | str | bytes) or getattr(complete, "shape", ()) != () \
            or complete not in (0, 1):
        return (f"not a softimpact result file (its 'complete' attribute is {complete!r}, "
                "not 0 or 1)")
    if complete == 0 and not kind.sweep:  # only a sweep is written in parts
        return (f"not a softimpact result file (its 'complete' attribute is 0, and a "
                f"{kind.name} result is written whole)")
    # a sweep over model parameters also has an axis for each (``grid_parameters``)
    swept = attribute_list(ds.attrs, "grid_parameters") if kind.sweep else []
    missing = [name for name in (*kind.variables, *swept) if name not in ds]
    if complete == 1 and missing:
        return (f"a {kind.name} result without its variable{'s' * (len(missing) > 1)} "
                f"{', '.join(missing)} (damaged, or not written by softimpact)")
    return None


def measure(result: str | os.PathLike | xr.Dataset, out: str | os.PathLike | None = None, *,
            box_sizes=None, radii=None, wada_radius: int = 5, wada_tol: float = 0.05,
            overwrite: bool = False) -> xr.Dataset:
    """How fractal the planes of a basins result are: its ``fractality`` dataset.

    ``result``: a basins result file over a plane of initial conditions, or its dataset.
    Basin entropy S_b and S_bb at ``box_sizes`` (cells), the uncertainty exponent from
    the uncertain share at ``radii`` (cells) with its 95% fit interval and D = 2 - alpha,
    and the Wada merging test up to ``wada_radius`` cells with mismatch tolerance
    ``wada_tol`` (``analysis.fractality``; defaults there). ``out``: also write the
    dataset there (atomically; an existing file needs ``overwrite=True``); ``softimpact
    info`` and ``softimpact plot fractality`` read it. ConfigError (one line naming the
    file) for anything else than a complete basins result over a plane, or sizes that do
    not fit it; nothing is written then.
    """
    name = "result" if isinstance(result, xr.Dataset) else os.fspath(result)
    ds = memory_order(result) if isinstance(result, xr.Dataset) else read_result(result)
    problem = plane_problem(ds)
    if problem:
        raise ConfigError(f"{name}: {problem}")
    if out is not None:
        check_writable(out, "measure", "out")
        if Path(out).exists() and not overwrite:
            raise ConfigError(f"{out}: result exists; pass --overwrite to replace it")
    try:
        measured = fractality(ds, box_sizes, radii, wada_radius, wada_tol)
    except ValueError as exc:
        raise ConfigError(f"{name}: {exc}") from None

    measured.attrs.update({"source_result": name, "softimpact_version": __version__,
                           "measured": iso_time(time.time()),
                           "history": history_line(time.time())})
    if "scene_text" not in measured.attrs:  # a dataset built by hand
        measured.attrs["scene_text"] = ""
    if out is not None:
        write_result(measured, out)
    return measured
