"""si.System (softimpact_cli/api_system.py): one parameter point of a scene's model that
labels single initial conditions as a sweep labels them, records trajectories, finds its
catalogue, and gives new parameter values without compiling anything again."""

import gc
import sys

import numpy as np
import pytest

import softimpact_cli as si

PAIR = {"system": {"model": "duffing"},
        "coupling": {"d": 6.0, "phi": 0.0, "k_c": 8.0, "c_c": 10.0},
        "catalogue": {"grid": 4, "random": 20}}
# starts of figure 6(d)'s plane reaching both its solutions (L1^1 R1-0^1, L1^2 R1-0^2)
STATES = [[8.0, 0.0, -4.0, 0.0], [-12.0, 0.0, -12.0, 0.0], [-12.0, 0.0, 1.7, 0.0],
          [-12.0, 0.0, -5.1, 0.0], [2.0, 1.0, -2.0, -1.0], [11.0, 3.0, -11.0, 2.0]]


@pytest.fixture(scope="module")
def system():
    return si.System(PAIR)


def compiled_signatures() -> int:
    """How many compiled specialisations the process's numba functions hold (each
    function compiled or loaded from numba's cache adds one per signature): every
    Dispatcher, those that factories keep in closures and tables as well."""
    from numba.core.dispatcher import Dispatcher

    found = {id(o): o for o in gc.get_objects() if isinstance(o, Dispatcher)}
    for name, module in list(sys.modules.items()):
        if name.startswith("softimpact_cli.") and module is not None:
            found.update({id(v): v for v in vars(module).values() if isinstance(v, Dispatcher)})
    return sum(len(o.overloads) for o in found.values())


def test_classify_labels_each_start_as_a_basins_sweep_does(system):
    swept = si.run({**PAIR, "analysis": {"kind": "basins"},
                    "initial_conditions": {"kind": "list", "states": STATES}},
                   workers=1, verify=False)
    names = dict(zip(swept["label_code"].values.tolist(), swept["label_name"].values.tolist(),
                     strict=True))
    labels = swept["label"].values.ravel()
    periods = swept["period"].values.ravel()
    found = [system.classify(u0) for u0 in STATES]
    assert [f.label for f in found] == [names[int(c)] for c in labels]
    assert [f.period for f in found] == periods.tolist()
    assert [f.code for f in found] == labels.tolist()
    assert len({f.label for f in found}) >= 2 and {f.outcome for f in found} == {"converged"}


def test_with_gives_a_new_system_and_compiles_nothing(system):
    u0 = STATES[0]
    system.classify(u0)
    system.trajectory(u0, periods=5)
    before = compiled_signatures()
    assert before > 0
    wider = system.with_(d=8.0)
    assert wider.parameters["d"] == 8.0 and system.parameters["d"] == 6.0  # unchanged
    changed = np.flatnonzero(wider.parameter_array != system.parameter_array)
    assert changed.tolist() == [system.scene.system.parameter_names.index("d")]
    assert wider.classify(u0).outcome == "converged"
    wider.trajectory(u0, periods=5)
    assert compiled_signatures() == before
    assert "d = 8.0" in wider.scene.text  # the new values are the scene's, as checked


def test_with_checks_values_as_a_scene_does(system):
    with pytest.raises(si.ConfigError, match=r"\[coupling\] k_c: must be >= 0"):
        system.with_(k_c=-1.0)
    with pytest.raises(si.ConfigError, match="with_: q: not a parameter of this duffing "
                                             "system; one of c, k1, k2, F, w, d"):
        system.with_(q=1.0)
    assert system.with_(F=np.float64(0.5)).parameters["F"] == 0.5  # [system]
    with pytest.raises(si.ConfigError, match="u0: must be 4 finite numbers"):
        system.classify([1.0, 2.0])
    with pytest.raises(si.ConfigError, match="periods: must be a whole number"):
        system.trajectory(STATES[0], periods=0)


def test_trajectory_and_catalogue_are_the_kinds_results(system):
    u0 = STATES[0]
    mine = system.trajectory(u0, periods=30, samples_per_period=16)
    kind = si.run({**{k: v for k, v in PAIR.items() if k != "catalogue"},
                   "analysis": {"kind": "trajectory", "state": u0, "periods": 30,
                                "samples_per_period": 16}})
    np.testing.assert_array_equal(mine["state"].values, kind["state"].values)
    assert mine.attrs["outcome"] == kind.attrs["outcome"]
    assert mine.attrs["period"] == system.classify(u0).period
    catalogue = si.run({**{k: v for k, v in PAIR.items() if k != "catalogue"},
                        "analysis": {"kind": "catalogue", **PAIR["catalogue"]}})
    found = system.catalogue()
    assert found["attractor_name"].values.tolist() == \
        catalogue["attractor_name"].values.tolist()
    assert found["combination_name"].values.tolist() == \
        catalogue["combination_name"].values.tolist()


def test_a_scene_file_gives_its_base_values_and_search():
    system = si.System("configs/demo_basins.toml")
    scene = si.load_scene("configs/demo_basins.toml")
    assert {k: system.parameters[k] for k in scene.values} == dict(scene.values)
    assert system.state_names == ("x1", "v1", "x2", "v2")
    assert "duffing" in repr(system)
