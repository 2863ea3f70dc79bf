"""The first-run compile notice and the ahead-of-time warm-up (issue 20, item 5)."""

import io
import os
import signal
import subprocess
import sys

import pytest

from softimpact_cli.analysis import warmup
from softimpact_cli.kernels import METHODS
from softimpact_cli.systems import REGISTRY, get_system

SCENE = """
[system]
model = "duffing"
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-1.0, 1.0], [-1.0, 1.0]]
resolution = [2, 2]
[output]
path = "{out}"
"""


def test_cold_cache_sweep_says_it_compiles_and_where(tmp_path):
    """A sweep on an empty kernel cache prints the notice, naming the cache folder, before
    it starts compiling (the run is killed once the line is read)."""
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.format(out=tmp_path / "r.h5"))
    cache = tmp_path / "cache"
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    proc = subprocess.Popen([sys.executable, "-m", "softimpact_cli", "sweep", str(scene), "-q",
                             "--workers", "1"], stderr=subprocess.PIPE, text=True, env=env)
    try:
        line = proc.stderr.readline()
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    assert line.startswith("softimpact: compiling numerical kernels (first run only"), line
    assert f"cached in {cache}{os.sep}" in line


def test_notice_is_printed_once_per_process(monkeypatch):
    monkeypatch.setattr(warmup, "_announced", False)
    monkeypatch.setattr(warmup, "compile_notice", lambda scene=None: "compiling")
    stream = io.StringIO()
    for _ in range(3):
        warmup.announce_compilation(stream=stream)
    assert stream.getvalue() == "compiling\n"


def test_no_notice_without_missing_kernels(monkeypatch):
    monkeypatch.setattr(warmup, "missing_kernels", lambda *args: [])
    assert warmup.compile_notice() is None
    monkeypatch.setattr(warmup, "missing_kernels", lambda *args: ["orbit.flow"])
    assert "cached in" in warmup.compile_notice()


def test_warm_up_covers_every_system_and_method():
    """Each registered system with each method, and each body's catalogue (variational
    equations): a new system or method must get its warm-up step."""
    names = [what for what, _ in warmup._steps()]
    for (model, bodies), _ in REGISTRY.items():
        kind = "pair" if bodies == 2 else "body"
        for method in METHODS:  # the exact flow only where there is one
            wanted = method != "exact" or get_system(model, bodies).piecewise_linear
            assert (f"{model} {kind}: {method}" in names) == wanted
        if bodies == 1:
            assert f"{model} catalogue (Newton, variational equations)" in names


def test_missing_kernels_are_named_by_module(tmp_path):
    """On an empty cache every kernel a run needs is missing, the method's included."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    code = ("from softimpact_cli.analysis import warmup; "
            "print(' '.join(warmup.missing_kernels('bilinear', 2, 'rodas4')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, check=True).stdout.split()
    assert "softimpact_cli.kernels.driver.advance_rodas4" in out
    assert "softimpact_cli.systems.bilinear.pair_rhs" in out
    assert "softimpact_cli.systems.variational.bilinear_body_rhs" in out


def test_warm_up_compiles_the_chain_family_once():
    """One set of steps for every chain (the model is data): each method, the exact flow
    included (the warm-up chain is piecewise linear), and the Lyapunov exponents."""
    names = [what for what, _ in warmup._steps()]
    assert warmup.warmup_chain().piecewise_linear
    for method in METHODS:
        assert f"chain: {method}" in names
    assert "chain: Lyapunov exponents (Benettin, saltation)" in names
    assert [what for what, _ in warmup._steps("chain")] == [
        n for n in names if n.startswith("chain")]  # "chain with a rigid stop: " too


def test_warm_up_models_option_names_the_models():
    """``--models=a,b`` picks those models' kernels (the benchmarks time the presets' and
    the family's compilation apart); an unknown model is one line naming the allowed."""
    assert warmup._models(["-q"]) is None
    assert warmup._models(["--models=duffing,bilinear"]) == ["duffing", "bilinear"]
    assert warmup._models(["--models=chain"]) == ["chain"]
    with pytest.raises(SystemExit, match="unknown model quartic; models: bilinear, chain"):
        warmup._models(["--models=chain,quartic"])


def test_warm_up_compiles_the_impact_loop_of_every_method_for_rigid_stops():
    """A rigid stop runs each method inside the impact loop (kernels/impacts.py), a
    different advance for classify, record and flow: without these steps a rigid chain's
    first run after the install compiled (about 40 s) and said so. The notice names the
    loop's kernel, not the plain method's."""
    names = [what for what, _ in warmup._steps()]
    rigid = warmup.warmup_rigid_chain()
    assert rigid.extra["rigid"] and not rigid.piecewise_linear
    for method in METHODS:
        wanted = method != "exact"  # a rigid stop has no closed-form flow
        assert (f"chain with a rigid stop: {method}" in names) == wanted
    kernels = warmup._scene_kernels("chain", 1, "rk4", False, rigid)
    assert kernels[2].__name__ == "advance_impacts_rk4_impacts"


def _signatures() -> dict[str, int]:
    """{kernel: compiled signatures} of every jitted function of the kernels' and systems'
    modules in this process, and of the impact loops' advances (``kernels.IMPACT_ADVANCE``,
    closures no module names); loading one from the disk cache counts as compiling it."""
    import importlib
    import pkgutil

    import softimpact_cli.kernels
    import softimpact_cli.systems

    out = {f"impacts.{name}": len(d.signatures)
           for name, d in softimpact_cli.kernels.IMPACT_ADVANCE.items()}
    for package in (softimpact_cli.kernels, softimpact_cli.systems):
        for info in pkgutil.iter_modules(package.__path__):
            module = importlib.import_module(f"{package.__name__}.{info.name}")
            for name, obj in vars(module).items():
                if hasattr(obj, "signatures") and hasattr(obj, "py_func"):
                    out[f"{module.__name__}.{name}"] = len(obj.signatures)
    return out


def test_warm_up_reaches_a_rigid_chains_unresolved_trajectory():
    """One body on a rigid wall at 0.2 (w = 2.5, r = 0.8) ends the first pass unresolved
    and goes on to the second stage, whose Lyapunov spectrum runs Benettin inside the
    impact loop: after the rigid chain's warm-up steps, that trajectory adds no kernel
    signature (before, it compiled for 14 s on its first run after the install)."""
    from softimpact_cli.kinds.run import run_scene
    from softimpact_cli.kinds.scene import parse_scene

    for what, run in warmup._steps("chain"):
        if what.startswith("chain with a rigid stop"):
            run()
    before = _signatures()
    scene = parse_scene(
        '[system]\nmodel = "chain"\nbodies = 1\nc = 0.1\nk1 = 1.0\nF = 1.0\n'
        'phi = "pi/2"\nw = 2.5\n[[stop]]\nbody = 1\nwall = 0.2\nside = "right"\n'
        'law = "rigid"\nr = 0.8\n[analysis]\nkind = "trajectory"\nstate = [0.0, 0.0]\n')
    ds = run_scene(scene)
    assert ds.attrs["second_stage"] != "not run"  # the first pass left it unresolved
    grown = {k: v for k, v in _signatures().items() if v != before.get(k, 0)}
    assert not grown, f"compiled after the warm-up: {grown}"


def test_the_warm_up_compiles_lyapunov_and_continuation_with_a_rigid_stop():
    """Kinds lyapunov and continuation on a rigid stop run the impact loop on the
    variational equations (a new signature of it, of Benettin's kernel and of the flow):
    once the warm-up's rigid steps have run, a rigid lyapunov and continuation scene
    compile nothing more (so after ``make install`` such a run says no "compiling" line;
    without the step "Lyapunov exponents and the shooting's monodromy", Benettin's kernel
    and the flow compiled a new signature here)."""
    from softimpact_cli.kinds.run import run_scene
    from softimpact_cli.kinds.scene import parse_scene

    steps = dict(warmup._steps("chain"))
    assert any(n.startswith("chain with a rigid stop: Lyapunov") for n in steps)
    for name, step in steps.items():
        if name.startswith("chain with a rigid stop:"):
            step()
    before = _signatures()
    head = """[system]
model = "chain"
bodies = 1
c = 0.1
phi = "3*pi/2"
w = 0.8
[[stop]]
body = 1
wall = 1.35
side = "right"
law = "rigid"
r = 0.8
"""
    run_scene(parse_scene(head + """[analysis]
kind = "lyapunov"
state = [-0.5, 0.0]
periods = 4
transient = 0
segments = 2
"""))
    run_scene(parse_scene(head + """[analysis]
kind = "continuation"
parameter = "stop.1.wall"
low = 1.0
high = 2.0
start = "state"
state = [-0.835, -0.339]
max_points = 3
switch_depth = 0
"""))
    after = _signatures()
    assert {k: v for k, v in after.items() if before.get(k, 0) != v} == {}
