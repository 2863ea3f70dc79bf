"""Critical values per stop of a chain's non-impacting solutions (analysis/chain_dcrit).

A three-body hardening Duffing chain whose every body has two coexisting period-1
attractors (k2 = 0.05, w = 1.4, F = 1.5): its non-impacting solutions are the 2^3
products; each stop's critical value is checked by brute force on the chain itself (the
stop just beyond it: no contact and the product orbit returns; just inside: contact), and
against the maximum of the stop's compression on finely sampled joint orbits.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import body_catalogue, sample_states
from softimpact_cli.analysis.chain_dcrit import (
    TIGHT,
    body_problem,
    chain_critical_gaps,
    critical_values,
    products,
    stop_coefficients,
    uncoupled_values,
)
from softimpact_cli.analysis.engine import Problem, flow, record_trajectory
from softimpact_cli.systems.chain import ChainModel, Stop, chain_system, chain_values

MODEL = ChainModel(3, stops=(Stop(1, 2), Stop(2, 3), Stop(3, 0, "left")))
PHASES = [0.0, 5 * np.pi / 8, 5 * np.pi / 4]
STATES = sample_states({"x": (-4.0, 4.0), "v": (-4.0, 4.0)}, 4, 0, 0)


def chain_point(F=(1.5, 1.5, 1.5)):
    return chain_values(MODEL, 1.4, {"c": 0.05, "k1": 1.0, "k2": 0.05, "F": list(F),
                                     "phi": PHASES},
                        stop_values=[{"d": 2.0, "k_c": 8.0, "c_c": 10.0},
                                     {"d": 2.0, "k_c": 8.0, "c_c": 10.0},
                                     {"wall": -3.0, "k_c": 8.0, "c_c": 10.0}])


@pytest.fixture(scope="module")
def found():
    system = chain_system(MODEL)
    values = chain_point()
    per_body = [body_catalogue(body_problem(system, values, i, TIGHT), STATES)[0]
                for i in (1, 2, 3)]
    return system, values, per_body, products(per_body)


def with_one_stop(system, values, stop: int, value: float) -> dict:
    """The uncoupled chain with stop ``stop`` (1-based) set to ``value`` (gap or wall)."""
    out = uncoupled_values(system, values)
    s = MODEL.stops[stop - 1]
    out[f"stop.{stop}.{'wall' if s.wall else 'd'}"] = value
    return out


def test_products_are_the_chains_non_impacting_solutions(found):
    system, values, per_body, prods = found
    assert [len(a) for a in per_body] == [2, 2, 2]  # two P1 attractors per body
    assert len(prods) == 8 and len({p.name for p in prods}) == 8
    problem = Problem(system, uncoupled_values(system, values), TIGHT)
    for p in prods:  # a fixed point of the whole chain's stroboscopic map
        status, end, _ = flow(problem, p.orbit[0], 0.0, problem.period)
        assert np.max(np.abs(end - p.orbit[0])) < 1e-8


def test_each_stops_critical_value_decides_contact_by_brute_force(found):
    system, values, _, prods = found
    problem = Problem(system, uncoupled_values(system, values), TIGHT)
    eps = 1e-3
    for p in prods:
        crit = critical_values(problem, p)
        for s in (1, 2, 3):
            c, sign = stop_coefficients(system, s)
            # against dense samples of the compression (0.0006 T apart): never above it
            fine = record_trajectory(problem, p.orbit[0], 0.0, 1, 10_000)
            sampled = sign * np.max(fine.y @ c)
            assert abs(sampled - crit[s - 1]) < 1e-6
            assert sign * (crit[s - 1] - sampled) >= -1e-11
            # beyond it: the chain keeps the product, no contact
            safe = Problem(system, with_one_stop(system, values, s, crit[s - 1] + sign * eps),
                           TIGHT)
            run = record_trajectory(safe, p.orbit[0], 0.0, 3, 64)
            assert run.contacts.sum() == 0
            assert np.max(np.abs(run.section_y[-1] - p.orbit[0])) < 1e-8
            # inside it: contact in the first period, and the orbit is no longer the product
            touch = Problem(system, with_one_stop(system, values, s, crit[s - 1] - sign * eps),
                            TIGHT)
            run = record_trajectory(touch, p.orbit[0], 0.0, 3, 64)
            assert run.contacts[:2].sum() >= 1
            assert np.max(np.abs(run.section_y[-1] - p.orbit[0])) > 1e-7


def test_critical_values_follow_a_bodys_forcing(found):
    """Swept F.1: at each value the bodies are searched again and every product's values
    are those of that point's own products (NaN for a product the point does not have)."""
    system, _, _, _ = found
    base = chain_point()
    ds = chain_critical_gaps(system, base, STATES, "F.1", [0.3, 1.5])
    names = [str(n) for n in ds["combination_label"].values]
    for p_index, force in enumerate((0.3, 1.5)):
        values = {**base, "F.1": force}
        per_body = [body_catalogue(body_problem(system, values, i, TIGHT), STATES)[0]
                    for i in (1, 2, 3)]
        prods = products(per_body)
        problem = Problem(system, uncoupled_values(system, values), TIGHT)
        for p in prods:
            np.testing.assert_allclose(ds["d_crit"].values[:, names.index(p.name), p_index],
                                       critical_values(problem, p), atol=1e-9)
        assert np.isfinite(ds["d_crit"].values[0, :, p_index]).sum() == len(prods)
    assert len(per_body[0]) == 2  # at F.1 = 1.5 body 1 has its two attractors
