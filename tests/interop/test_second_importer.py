# SPDX-License-Identifier: BSD-2-Clause
"""A second FMI importer, fmi-sim (Rust, crates.io), loads PainleveRod.fmu, runs
the default experiment (an IWC) and agrees with fmpy as far as its solver allows.

- Co-Simulation: both masters call fmi2DoStep on the same communication grid
  (fmpy computes the points as i*h, fmi-sim sums h: they differ by ulps, and
  CVODE stops exactly at each and continues), so they agree to the solver
  tolerance, as both do with fmpy's own CVode through Model Exchange.
- Model Exchange: fmi-sim integrates with forward Euler, step = output interval,
  events at step ends. fmpy's Euler is the same method, so the two agree to
  round-off at every step size; against CVode the difference is Euler's first
  order error, O(h/eps) in the IWC's fast time: ~70 % of e at fmi-sim's default
  step stop/500 = eps/5, ~2 % at eps/100.
"""
import math

import fmpy
import numpy as np
import pytest

from painleve.theory import analytic as an
from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from painleve.experiments.outcome import outcome_of_trajectory
from helpers.fmi_sim import run_fmi_sim

DEFAULT = Case()                                 # the modelDescription's start values
OTHER = Case(epsilon=1e-4, delta=0.5, theta0=1.1)
STATES = ["x", "v", "y", "w", "theta", "phi"]


def start_values(case):
    return {} if case == DEFAULT else {k: v for k, v in case.start_values().items() if k not in ("x", "y")}


def stop_time(case, fmu_path):
    return float(fmpy.read_model_description(fmu_path).defaultExperiment.stopTime) if case == DEFAULT else 100 * case.epsilon


@pytest.fixture(scope="module")
def cvode(fmu_path):
    """fmpy's CVode through Model Exchange, tight: the reference."""
    with Experiment(fmu_path, relative_tolerance=1e-10) as experiment:
        yield {case: experiment.run(case) for case in (DEFAULT, OTHER)}


def theorem_bound(case):
    return 3 * case.epsilon * math.log(1 / case.epsilon)


def test_the_default_experiment_is_an_iwc_under_fmi_sim(fmu_path, tmp_path):
    r = run_fmi_sim(fmu_path, tmp_path, "CS")
    stop = float(fmpy.read_model_description(fmu_path).defaultExperiment.stopTime)
    assert r["time"][-1] == pytest.approx(stop)
    outcome = outcome_of_trajectory(DEFAULT, r, exact_events=False)
    assert outcome.iwc
    assert abs(outcome.w_error) < theorem_bound(DEFAULT)


@pytest.mark.parametrize("case", [DEFAULT, OTHER], ids=["default", "eps1e-4"])
def test_co_simulation_agrees_with_fmpy_to_solver_tolerance(fmu_path, tmp_path, cvode, case):
    stop = stop_time(case, fmu_path)
    interval = stop / 500       # one grid for both, explicit: each master's default is the DefaultExperiment's stepSize
    theirs = run_fmi_sim(fmu_path, tmp_path, "CS", start_values=start_values(case), stop_time=stop,
                         output_interval=interval)
    ours = fmpy.simulate_fmu(fmu_path, fmi_type="CoSimulation", start_values=start_values(case),
                             stop_time=stop, output_interval=interval, output=STATES + ["mode", "contact"])
    assert len(ours) == len(theirs)
    rtol = 1e-6             # the default experiment's, which both masters pass
    for name in STATES:     # the same fmi2DoStep calls on the same FMU, up to ulps of t
        assert np.max(np.abs(ours[name] - theirs[name])) <= 10 * rtol * (1 + np.max(np.abs(ours[name])))
    w_theirs = outcome_of_trajectory(case, theirs, exact_events=False).w
    w_ours = outcome_of_trajectory(case, ours, exact_events=False).w
    assert w_theirs == pytest.approx(w_ours, abs=10 * rtol)
    # fmpy's CVode (ME) at rtol 1e-10 against the FMU's CVODE at 1e-6
    assert abs(w_theirs - cvode[case].w) < 10 * rtol * case.v0
    assert abs(w_theirs / case.v0 - an.predict(case).e) < theorem_bound(case)


@pytest.mark.parametrize("steps_per_epsilon", [5, 100])     # 5: fmi-sim's default, stop/500
def test_model_exchange_is_forward_euler_like_fmpys(fmu_path, tmp_path, steps_per_epsilon):
    h = DEFAULT.epsilon / steps_per_epsilon
    theirs = run_fmi_sim(fmu_path, tmp_path, "ME", output_interval=h)
    ours = fmpy.simulate_fmu(fmu_path, fmi_type="ModelExchange", solver="Euler", step_size=h, output_interval=h,
                             output=STATES + ["mode", "contact"])
    # fmi-sim records an event's state once per event, fmpy twice: compare the ends
    assert theirs["time"][-1] == pytest.approx(ours["time"][-1])
    for name in STATES:
        assert theirs[name][-1] == pytest.approx(ours[name][-1], rel=1e-9, abs=1e-12)
    w_theirs = outcome_of_trajectory(DEFAULT, theirs, exact_events=False).w
    w_ours = outcome_of_trajectory(DEFAULT, ours, exact_events=False).w
    assert w_theirs == pytest.approx(w_ours, rel=1e-8)


def test_model_exchange_converges_to_cvode_as_eulers_step_shrinks(fmu_path, tmp_path, cvode):
    """Euler's error is first order in h/eps (events are located to a step):
    going from eps/5 to eps/100 it falls by more than 10, to a few % of e."""
    errors = {}
    for steps in (5, 100):
        r = run_fmi_sim(fmu_path, tmp_path, "ME", output_interval=DEFAULT.epsilon / steps)
        outcome = outcome_of_trajectory(DEFAULT, r, exact_events=False)
        assert outcome.iwc
        errors[steps] = abs(outcome.w - cvode[DEFAULT].w)
    assert errors[100] < errors[5] / 10
    assert errors[100] < 0.03 * an.predict(DEFAULT).e * DEFAULT.v0


def test_fmi_sim_refuses_what_the_fmu_refuses(fmu_path, tmp_path):
    """epsilon = 5 is outside [1e-8, 1]: the FMU returns fmi2Error, fmi-sim stops."""
    with pytest.raises(RuntimeError, match="failed"):
        run_fmi_sim(fmu_path, tmp_path, "CS", start_values={"epsilon": 5.0})
