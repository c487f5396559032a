# SPDX-License-Identifier: BSD-2-Clause
"""FMI4j (Maven Central, info.laht.fmi4j 0.38.0) runs PainleveRod.fmu's default experiment
through FMI 2.0 Model Exchange: FMI4j's instance (its JNI layer makes every FMI call)
under a fixed-step forward Euler master, tests/importers/jvm/.../ModelExchangeEuler.java,
since FMI4j ships no integrator on Maven Central.

The master is fmpy's solver="Euler" step for step (x += h der(x), indicators compared
with the previous step's, events handled at the step's end), so the two runs must be
equal to round-off: what differs is only the importer between the master and the FMU.
Against CVode the difference is Euler's first-order error in h/eps (the contact's time
scale is eps, events are located to a step): h = eps/100 brings w within 3 % of e v0,
as for fmi-sim's Euler (tests/interop/test_second_importer.py). Forward Euler does not keep
the energy from rising (it overshoots at the stick, located at a step's end), so the
energy is checked against fmpy's Euler and for the loss the contact must take.
"""
import fmpy
import numpy as np
import pytest

from helpers.other_importers import FIELDS, run_fmi4j_euler
from painleve.theory import analytic as an
from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from painleve.experiments.outcome import outcome_of_trajectory as outcome_of
from helpers.rod_sim import OUTPUTS, phases, rod_energy

DEFAULT = Case()
STEPS_PER_EPSILON = 100


@pytest.fixture(scope="module")
def stop_time(fmu_path):
    return float(fmpy.read_model_description(fmu_path).defaultExperiment.stopTime)


@pytest.fixture(scope="module")
def h(stop_time):
    return DEFAULT.epsilon / STEPS_PER_EPSILON


@pytest.fixture(scope="module")
def fmi4j(fmu_path, stop_time, h):
    return run_fmi4j_euler(fmu_path, stop_time, round(stop_time / h))


@pytest.fixture(scope="module")
def fmpy_euler(fmu_path, h):
    return fmpy.simulate_fmu(fmu_path, fmi_type="ModelExchange", solver="Euler", step_size=h, output_interval=h,
                             output=list(OUTPUTS), record_events=False)


@pytest.fixture(scope="module")
def fmpy_cvode(fmu_path):
    with Experiment(fmu_path, relative_tolerance=1e-10) as experiment:
        return experiment.run(DEFAULT)


def test_fmi4j_model_exchange_ends_in_flight_after_an_iwc_within_eulers_error(fmi4j, fmpy_cvode, stop_time):
    assert fmi4j["time"][-1] == pytest.approx(stop_time, rel=1e-12)
    for field in FIELDS:
        assert np.all(np.isfinite(fmi4j[field])), field
    outcome = outcome_of(DEFAULT, fmi4j, exact_events=False)
    assert outcome.iwc
    assert abs(outcome.w - fmpy_cvode.w) < 0.03 * an.predict(DEFAULT).e * DEFAULT.v0      # first order in h/eps = 1/100
    assert fmi4j["w"][-1] > 0 and not fmi4j["contact"][-1]


def test_fmi4j_model_exchange_is_fmpys_euler_step_for_step(fmi4j, fmpy_euler):
    assert len(fmi4j) == len(fmpy_euler)
    for field in FIELDS:     # the same arithmetic on the same FMU: round-off at most
        np.testing.assert_allclose(fmi4j[field], fmpy_euler[field], rtol=1e-12, atol=1e-15, err_msg=field)


def test_fmi4j_model_exchange_goes_through_fmpys_mode_sequence(fmi4j, fmpy_euler):
    sequence = phases(fmi4j)
    assert sequence == phases(fmpy_euler)
    assert sequence[0] == (True, 1) and (True, 0) in sequence and sequence[-1][0] is False


def test_fmi4j_model_exchange_energy_is_the_rods_and_the_contact_takes_its_share(fmi4j):
    E = fmi4j["energy"]
    np.testing.assert_allclose(E, rod_energy(fmi4j, alpha=DEFAULT.alpha, epsilon=DEFAULT.epsilon, contact=fmi4j["contact"]),
                               rtol=1e-12, atol=1e-12)
    assert E[-1] < E[0] - 0.1
    # what Euler adds back is its first-order error, a few % of what the contact takes
    rises = np.diff(E)
    assert np.sum(rises[rises > 0]) < 0.03 * (E[0] - E[-1])
