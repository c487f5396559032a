# SPDX-License-Identifier: BSD-2-Clause
"""The Co-Simulation fast loop's FMI calls straight into the FMU's C functions (cs_calls.DirectCalls,
the harness's default on an FMI 2.0 FMU) are fmpy's calls: the same outcome of every case, to the
last bit, as through fmpy's wrappers (WrapperCalls), whether the record tells it after the first
step or the case runs stepped; a value the FMU refuses stops both runs with the FMU's own words.
And the outcome is the physics': w at the return on Theorem 1's e where eps is small."""
import math
import struct
from dataclasses import fields, replace

import pytest

from painleve.experiments.case import Case
from painleve.experiments.outcome import SimulationError
from painleve.fmu import cs_fast_loop
from painleve.fmu.cs_calls import DirectCalls, WrapperCalls
from painleve.fmu.experiment import Experiment
from painleve.theory import analytic as an


def bits(outcome):
    """The outcome's fields, floats as their bytes (so -0.0 and 0.0, or two NaNs' payloads, differ)."""
    return [struct.pack("<d", v) if isinstance(v, float) else v
            for v in (getattr(outcome, f.name) for f in fields(outcome))]


def cases():
    wide, video = Case(theta0=1.0, phi0=0.5, delta=1.0), Case(theta0=0.9463, phi0=1.6654, delta=1.0)
    w1 = an.predict(video).w1_star
    return [replace(wide, epsilon=eps) for eps in (1e-2, 1e-4, 1e-6)] + [replace(wide, delta=0.0, epsilon=1e-3),
                                                                         replace(wide, kappa=2.0, beta=1.0)] + \
        [replace(video, w10=f * w1, epsilon=eps) for f in (1.5, 0.5) for eps in (1e-3, 1e-5)]


@pytest.fixture(scope="module")
def both(fmu_path):
    with Experiment(fmu_path, fmi_type="CoSimulation") as direct, \
            Experiment(fmu_path, fmi_type="CoSimulation", direct_calls=False) as wrapped:
        assert isinstance(direct.cs_calls, DirectCalls) and isinstance(wrapped.cs_calls, WrapperCalls)
        yield direct, wrapped


@pytest.mark.parametrize("case", cases(), ids=lambda c: f"th{c.theta0}-d{c.delta}-w{c.w10:.3g}-eps{c.epsilon:g}"
                                                         f"-k{c.kappa}")
def test_direct_calls_give_the_outcome_of_fmpys_wrappers_bit_for_bit(both, case):
    direct, wrapped = both
    for first in (cs_fast_loop.first_step(case), None):     # the long first step, and stepped
        a, b = (cs_fast_loop.run_stepped(e, case, first=first) for e in (direct, wrapped))
        assert a is not None and bits(a) == bits(b)
    a, b = direct.run(case), wrapped.run(case)
    assert bits(a) == bits(b)
    if case.epsilon <= 1e-4 and an.theorem_of(case) == 1:   # Theorem 1: w -> e v0, error O(eps ln 1/eps)
        assert abs(a.w / case.v0 - an.predict(case).e) <= 0.01 * an.predict(case).e


@pytest.mark.parametrize("bad, name", [(dict(mu=-1.0), "mu = -1"), (dict(epsilon=2.0), "epsilon = 2")])
def test_a_value_the_fmu_refuses_stops_both_with_its_own_words(both, bad, name):
    said = []
    for experiment in both:
        with pytest.raises(SimulationError) as err:
            cs_fast_loop.run_stepped(experiment, Case(**bad))
        said.append(str(err.value))
    assert said[0] == said[1] and f"fmi2SetReal: {name} is out of range" in said[0]
    assert math.isfinite(both[0].run(Case()).w)      # and the instance runs the next case
