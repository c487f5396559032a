# SPDX-License-Identifier: BSD-2-Clause
"""Importers other than fmpy run the FMI 3.0 FMU (build/fmi3/PainleveRod.fmu) through
its default experiment (an IWC at eps = 1e-3, t = 0 .. 0.1) and agree with fmpy as far
as their solvers allow.

Which of the project's importers read FMI 3.0 (docs/importers.md):
- fmi-sim 0.7.0 (crates.io): Model Exchange and Co-Simulation, given a copy of the FMU
  without the `unit` and `nominal` attributes its parser does not know (fmi_sim.py says why that
  changes nothing it runs);
- ecos (PyPI ecospy 0.7.2): Co-Simulation;
- FMI4j and JavaFMI (Maven Central) read FMI 2.0 model descriptions only: both refuse
  the FMU (tested below); libcosim (libcosimpy 0.0.6) imports FMI 1.0 and 2.0 only and
  crashes the process on an FMI 3.0 FMU, so it is not run.

Methods, and so how close each may come to fmpy:
- Co-Simulation (fmi-sim, ecos, fmpy): fmi3DoStep once per communication step on the
  grid stop/500, the FMU's own CVODE inside at the default experiment's tolerance; the
  masters' communication times differ by ulps (i*h or a sum of h), so they agree to
  O(rtol) = 1e-6, and with fmpy's CVode through Model Exchange to the same.
- fmi-sim's Model Exchange: forward Euler, step = output interval, events at step ends;
  fmpy's Euler is the same method, so the two agree to round-off, and both tend to
  CVode at first order in h/eps.
"""

import fmpy
import numpy as np
import pytest

from helpers.fmi_sim import fmi3_fmu_fmi_sim_can_read, run_fmi_sim
from helpers.other_importers import run_ecos, run_fmi4j_euler, run_jvm
from helpers.rod_sim import (OUTPUTS, assert_default_experiment_ends_in_flight_after_an_iwc, co_simulation_on_grid,
                             default_stop_time, phases, rod_energy)
from painleve.experiments.case import Case
from painleve.experiments.outcome import outcome_of_trajectory as outcome_of
from painleve.theory import analytic as an

DEFAULT = Case()                          # the modelDescription's start values
STATES = ["x", "v", "y", "w", "theta", "phi"]
STEPS = 500                               # the grid stop/500 (explicit: the DefaultExperiment has a stepSize)
RTOL = 1e-6                               # the default experiment's tolerance: the FMU's CVODE


@pytest.fixture(scope="module")
def stop_time(fmu3_path):
    return default_stop_time(fmu3_path)


@pytest.fixture(scope="module")
def fmi_sim_fmu(fmu3_path, tmp_path_factory):
    return fmi3_fmu_fmi_sim_can_read(fmu3_path, tmp_path_factory.mktemp("fmi-sim-fmu3"))


@pytest.fixture(scope="module")
def fmpy_cs(fmu3_path, stop_time):
    return co_simulation_on_grid(fmu3_path, stop_time, STEPS)


@pytest.fixture(scope="module")
def fmpy_cvode(fmu3_path):
    """fmpy's CVode through FMI 3.0 Model Exchange, tight: the IWC's w at the return."""
    r = fmpy.simulate_fmu(fmu3_path, fmi_type="ModelExchange", solver="CVode", relative_tolerance=1e-10,
                          output=list(OUTPUTS))
    return outcome_of(DEFAULT, r)


@pytest.fixture(scope="module", params=["fmi-sim", "ecos"])
def cs_run(request, fmi_sim_fmu, fmu3_path, stop_time, tmp_path_factory):
    """(importer, its Co-Simulation of the default experiment) on the grid stop/500."""
    if request.param == "fmi-sim":
        return request.param, run_fmi_sim(fmi_sim_fmu, tmp_path_factory.mktemp("fmi-sim-cs"), "CS",
                                          output_interval=stop_time / STEPS)
    return request.param, run_ecos(fmu3_path, stop_time, STEPS)


def test_fmi_sim_0_7_refuses_attributes_that_fmi_3_0_allows(fmu3_path, tmp_path):
    # Why fmi_sim_fmu leaves the units and nominals out; should a later fmi-sim read them,
    # this fails and the copy can go.
    with pytest.raises(RuntimeError, match='unknown field "(unit|nominal)" in element "FmiFloat64"'):
        run_fmi_sim(fmu3_path, tmp_path, "CS")


def test_co_simulation_ends_in_flight_after_an_iwc_with_w_positive(cs_run, stop_time):
    assert_default_experiment_ends_in_flight_after_an_iwc(*cs_run, stop_time)


def test_co_simulation_agrees_with_fmpy_to_the_solver_tolerance(cs_run, fmpy_cs, fmpy_cvode):
    name, theirs = cs_run
    assert len(theirs) == len(fmpy_cs)
    np.testing.assert_allclose(theirs["time"], fmpy_cs["time"], rtol=0, atol=1e-12)   # ulps of t
    for state in STATES:
        gap = np.max(np.abs(theirs[state] - fmpy_cs[state]))
        assert gap <= 10 * RTOL * (1 + np.max(np.abs(fmpy_cs[state]))), f"{name}: {state} differs by {gap:.3g}"
    assert abs(theirs["w"][-1] - fmpy_cs["w"][-1]) <= 10 * RTOL * (1 + abs(fmpy_cs["w"][-1]))
    # and fmpy's CVode (ME, rtol 1e-10) at the return to the floor, to the FMU's tolerance
    assert abs(outcome_of(DEFAULT, theirs, exact_events=False).w - fmpy_cvode.w) < 10 * RTOL * DEFAULT.v0


def test_co_simulation_energy_never_increases_beyond_the_solver_tolerance(cs_run):
    # The damper and friction only take energy; in flight it is conserved exactly, so a
    # rise is CVODE's error (rtol = RTOL). `energy` is the rod's of the states passed.
    name, r = cs_run
    E = r["energy"]
    np.testing.assert_allclose(E, rod_energy(r, alpha=DEFAULT.alpha, epsilon=DEFAULT.epsilon, contact=r["contact"]),
                               rtol=1e-12, atol=1e-12)
    assert np.max(np.diff(E)) <= RTOL * np.max(np.abs(E)), f"{name}: energy rises by {np.max(np.diff(E)):.3g}"
    assert E[-1] < E[0] - 0.1                                     # the contact took its share


def test_co_simulation_goes_through_fmpys_mode_sequence(cs_run, fmpy_cs):
    name, theirs = cs_run
    sequence = phases(theirs)
    assert sequence == phases(fmpy_cs), name
    assert sequence[0] == (True, 1) and (True, 0) in sequence and sequence[-1][0] is False


@pytest.mark.parametrize("steps_per_epsilon", [5, 100])     # 5: fmi-sim's default, stop/500
def test_fmi_sim_model_exchange_is_forward_euler_like_fmpys(fmi_sim_fmu, fmu3_path, tmp_path, steps_per_epsilon):
    h = DEFAULT.epsilon / steps_per_epsilon
    theirs = run_fmi_sim(fmi_sim_fmu, tmp_path, "ME", output_interval=h)
    ours = fmpy.simulate_fmu(fmu3_path, fmi_type="ModelExchange", solver="Euler", step_size=h, output_interval=h,
                             output=list(OUTPUTS))
    # fmi-sim records an event's state once, fmpy twice: the ends, and the mode sequence
    assert theirs["time"][-1] == pytest.approx(ours["time"][-1])
    for name in STATES + ["energy"]:
        assert theirs[name][-1] == pytest.approx(ours[name][-1], rel=1e-9, abs=1e-12), name
    assert phases(theirs) == phases(ours)
    assert outcome_of(DEFAULT, theirs, exact_events=False).w == \
        pytest.approx(outcome_of(DEFAULT, ours, exact_events=False).w, rel=1e-8)


def test_fmi_sim_model_exchange_converges_to_cvode_with_energy_error_of_first_order(fmi_sim_fmu, tmp_path,
                                                                                      fmpy_cvode):
    """Euler's error is first order in h/eps (events are located to a step): from eps/5 to
    eps/100 the error in w falls by more than 10, to a few % of e, and so does the energy
    Euler makes up in a step (the exact flow never gains any)."""
    w_error, rise = {}, {}
    for steps in (5, 100):
        r = run_fmi_sim(fmi_sim_fmu, tmp_path, "ME", output_interval=DEFAULT.epsilon / steps)
        outcome = outcome_of(DEFAULT, r, exact_events=False)
        assert outcome.iwc and r["w"][-1] > 0
        w_error[steps] = abs(outcome.w - fmpy_cvode.w)
        rise[steps] = np.max(np.diff(r["energy"]))
    assert w_error[100] < w_error[5] / 10
    e = an.e(DEFAULT.delta, DEFAULT.theta0, alpha=DEFAULT.alpha, mu=DEFAULT.mu)    # Theorem 1's restitution
    assert w_error[100] < 0.03 * e * DEFAULT.v0
    assert rise[100] < rise[5] / 10


def test_fmi_sim_refuses_what_the_fmu_refuses(fmi_sim_fmu, tmp_path):
    """epsilon = 5 is outside [1e-8, 1]: fmi3SetFloat64 returns fmi3Error, fmi-sim stops."""
    with pytest.raises(RuntimeError, match="failed"):
        run_fmi_sim(fmi_sim_fmu, tmp_path, "CS", start_values={"epsilon": 5.0})


@pytest.mark.parametrize("importer", ["fmi4j", "javafmi", "fmi4j-me"])
def test_the_jvm_importers_read_fmi_2_0_only(fmu3_path, stop_time, importer):
    # Their model-description readers know <ScalarVariable> only: no variable is found.
    with pytest.raises(RuntimeError, match="no variable x"):
        if importer == "fmi4j-me":
            run_fmi4j_euler(fmu3_path, stop_time, STEPS)
        else:
            run_jvm(importer, fmu3_path, stop_time, STEPS)
