# SPDX-License-Identifier: BSD-2-Clause
"""The Model Exchange fast loop (painleve.fmu.me_fast_loop: fmpy's CVode from event to event)
against fmpy's own simulate_fmu, its handling of an FMU that refuses a call, and the
fmpy internals it stands on (painleve.fmu.fmpy_internals), which an fmpy update may move."""
import ctypes

import numpy as np
import pytest

from painleve.theory import analytic as an
from painleve.fmu import fmpy_internals
from painleve.experiments.case import Case
from painleve.fmu.experiment import STATES, Experiment
from painleve.fmu.me_fast_loop import DirectCVode, event_iteration
from painleve.experiments.outcome import SimulationError, outcome_of_trajectory

VIDEO = dict(theta0=0.9463, phi0=1.6654, v0=1.0, delta=1.0)


def cases_at(eps):
    w1s = an.predict(Case(epsilon=eps, **VIDEO)).w1_star
    return [Case(epsilon=eps), Case(epsilon=eps, theta0=0.9, delta=0.0), Case(epsilon=eps, theta0=1.1, delta=0.5),
            Case(epsilon=eps, w10=1.2 * w1s, **VIDEO), Case(epsilon=eps, w10=0.8 * w1s, **VIDEO)]


@pytest.fixture(scope="module")
def experiment(fmu_path):
    with Experiment(fmu_path) as e:
        yield e


@pytest.mark.parametrize("eps", [1e-2, 1e-4, 1e-6])
def test_fast_loop_is_simulate_fmu_to_the_solver_tolerance(experiment, eps):
    # Both are fmpy's CVode at rtol = min(1e-6, eps/100); only the stops differ (events
    # only, or a 5 eps grid besides). The states (of order v0) agree to a few rtol; the
    # event times to rtol times the steps taken (~1000), in the fast time t/eps: the
    # compression grows from a seed exponentially, so its time sums every step's error.
    rtol = min(1e-6, eps / 100)
    for case in cases_at(eps):
        fast, grid = experiment.run(case), outcome_of_trajectory(case, experiment.simulate(case))
        assert (fast.iwc, fast.events) == (grid.iwc, grid.events)
        assert abs(fast.w - grid.w) <= 10 * rtol * case.v0
        assert abs(fast.phi - grid.phi) <= 10 * rtol * abs(grid.phi)
        assert abs(fast.t_return - grid.t_return) <= 1000 * rtol * eps
        for phase in ("compression", "stick", "lift_off", "flight_back"):
            assert np.isnan(getattr(fast, phase)) == np.isnan(getattr(grid, phase)), phase
            if not np.isnan(getattr(fast, phase)):
                assert abs(getattr(fast, phase) - getattr(grid, phase)) <= 1000 * rtol * eps, phase


def test_fast_loop_counts_the_solvers_work(experiment):
    o = experiment.run(Case(epsilon=1e-3))
    stats = experiment.solver_stats
    # BDF with a difference-quotient Jacobian: at least one right-hand side per step.
    assert 0 < stats["nsteps"] <= stats["nfev"] and o.solver_stats == stats


def test_a_call_the_fmu_refuses_fails_the_step_not_silently(fmu_path):
    # After initialization a Model Exchange FMU is in event mode, where setting the
    # states is not allowed: the solver's first right-hand side must stop CVode.
    with Experiment(fmu_path) as loaded:
        with pytest.raises(SimulationError, match="fmi2Set(Time|ContinuousStates): not allowed in state EventMode"):
            with loaded.fresh_run("a refused call") as instance:
                instance.setupExperiment(tolerance=1e-6, startTime=0.0)
                instance.enterInitializationMode()
                instance.exitInitializationMode()
                solver = DirectCVode(instance, loaded.model_description, relative_tolerance=1e-6, max_step=1e-3)
                solver.step(0.0, 1e-3)


def test_the_fmpy_internals_the_fast_loop_uses_are_where_it_expects(loaded):
    # If an fmpy update moves FMU2Model._functions or the serial N_Vector's content struct,
    # this fails here, naming which, rather than the fast loop failing somewhere inside CVode.
    from fmpy.sundials.nvector_serial import NV_DATA_S
    instance = loaded.instantiate()
    try:
        functions = fmpy_internals.c_functions(instance)
        assert [f.__name__ for f in functions] == list(fmpy_internals.FUNCTIONS)
        instance.setupExperiment(startTime=0.0)
        instance.enterInitializationMode()
        instance.exitInitializationMode()
        event_iteration(instance)
        instance.enterContinuousTimeMode()
        assert functions[0](instance.component, ctypes.c_double(0.5)) == 0     # fmi2SetTime, fmi2OK
        solver = DirectCVode(instance, loaded.model_description, relative_tolerance=1e-6, max_step=1e-3)
        data = fmpy_internals.vector_data(solver.x)
        assert ctypes.addressof(data.contents) == ctypes.addressof(NV_DATA_S(solver.x).contents)
        assert list(data[:6]) == list(instance.getReal([loaded.vr[k] for k in STATES]))
    finally:
        instance.freeInstance()


def test_a_run_past_its_event_budget_stops_with_a_message(experiment, monkeypatch):
    # An IWC from the consistent start has more than one event (contact, stick or slip changes,
    # lift-off, return): with a budget of one, the run must stop and say why, not go on.
    from painleve.fmu import me_fast_loop
    monkeypatch.setattr(me_fast_loop, "MAX_EVENTS", 1)
    with pytest.raises(SimulationError, match="1 events before t = .* the run chatters"):
        experiment.run(Case(epsilon=1e-3))
    monkeypatch.undo()
    assert experiment.run(Case(epsilon=1e-3)).iwc      # the instance runs on


def test_an_event_iteration_that_never_settles_stops():
    class Restless:            # an FMU that asks for another iteration every time
        calls = 0

        def newDiscreteStates(self):
            self.calls += 1
            return (True, False, False, False, False, 0.0)

    fmu = Restless()
    with pytest.raises(RuntimeError, match="did not settle"):
        event_iteration(fmu)
    from painleve.fmu.me_fast_loop import MAX_EVENT_ITERATIONS
    assert fmu.calls == MAX_EVENT_ITERATIONS
