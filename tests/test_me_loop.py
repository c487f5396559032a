"""The Model Exchange fast loop (painleve.me_loop: fmpy's CVode from event to event)
against fmpy's own simulate_fmu, and its handling of an FMU that refuses a call."""
import pytest

from painleve.experiment import Case, Experiment, outcome_of
from painleve.instance import LoadedFMU, SimulationError
from painleve.me_loop import DirectCVode

VIDEO = dict(theta0=0.9463, phi0=1.6654, v0=1.0, delta=1.0)


def cases_at(eps):
    w1s = Case(epsilon=eps, **VIDEO).w1_star
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
        fast, grid = experiment.run(case), outcome_of(case, experiment.simulate(case))
        assert (fast.iwc, fast.events) == (grid.iwc, grid.events)
        assert abs(fast.w - grid.w) <= 10 * rtol * case.v0
        assert abs(fast.phi - grid.phi) <= 10 * rtol * abs(grid.phi)
        assert abs(fast.t_return - grid.t_return) <= 1000 * rtol * eps
        if fast.iwc:
            assert abs(fast.stick - grid.stick) <= 1000 * rtol * eps


def test_fast_loop_counts_the_solvers_work(experiment):
    experiment.run(Case(epsilon=1e-3))
    stats = experiment.solver_stats
    # BDF with a difference-quotient Jacobian: at least one right-hand side per step.
    assert 0 < stats["nsteps"] <= stats["nfev"]


def test_a_call_the_fmu_refuses_fails_the_step_not_silently(fmu_path):
    # After initialization a Model Exchange FMU is in event mode, where setting the
    # states is not allowed: the solver's first right-hand side must stop CVode.
    loaded = LoadedFMU(fmu_path)
    try:
        with pytest.raises(SimulationError, match="fmi2Set(Time|ContinuousStates): not allowed in state EventMode"):
            with loaded.fresh_run("a refused call") as fmu:
                fmu.setupExperiment(tolerance=1e-6, startTime=0.0)
                fmu.enterInitializationMode()
                fmu.exitInitializationMode()
                solver = DirectCVode(fmu, loaded.model_description, tolerance=1e-6, max_step=1e-3)
                solver.step(0.0, 1e-3)
    finally:
        loaded.close()
