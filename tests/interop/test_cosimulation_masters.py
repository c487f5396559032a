# SPDX-License-Identifier: BSD-2-Clause
"""Four more FMI 2.0 importers, installed by `bash run.sh test` from PyPI and Maven
Central, run the default experiment (an IWC at eps = 1e-3, t = 0 .. 0.1, no start value
changed) through Co-Simulation: libcosim, ecos, FMI4j, JavaFMI (tests/helpers/other_importers.py;
docs/importers.md says why no Model Exchange).

Each calls fmi2DoStep on fmpy's default grid, h = stop/500 = eps/5, and the FMU's own
CVODE integrates inside each step at the FMU's tolerance, 1e-6 here (fmpy passes the
default experiment's 1e-6; the masters that pass none get the FMU's own min(1e-6, eps/1000)).
The masters differ only in how they form the communication times (i*h, a sum of h, integer
nanoseconds), by ulps: CVODE stops at each point and carries on, so two masters follow
step sequences that differ by round-off and agree to O(rtol), as fmpy's CVode through
Model Exchange does with them.
"""
import numpy as np
import pytest

from helpers.other_importers import MASTERS
from helpers.rod_sim import (assert_default_experiment_ends_in_flight_after_an_iwc, co_simulation_on_grid,
                             default_stop_time, phases, rod_energy)
from painleve.experiments.case import Case
from painleve.experiments.outcome import outcome_of_trajectory as outcome_of
from painleve.fmu.experiment import Experiment

DEFAULT = Case()                          # the modelDescription's start values
STATES = ["x", "v", "y", "w", "theta", "phi"]
STEPS = 500                               # fmpy's default grid: stop/500
RTOL = 1e-6                               # the FMU's CVODE tolerance in the default experiment


@pytest.fixture(scope="module")
def stop_time(fmu_path):
    return default_stop_time(fmu_path)


@pytest.fixture(scope="module")
def fmpy_cs(fmu_path, stop_time):
    """fmpy's Co-Simulation of the default experiment on the same grid."""
    return co_simulation_on_grid(fmu_path, stop_time, STEPS)


@pytest.fixture(scope="module")
def fmpy_cvode(fmu_path):
    """fmpy's CVode through Model Exchange, tight: the IWC's w at the return to the floor."""
    with Experiment(fmu_path, relative_tolerance=1e-10) as experiment:
        return experiment.run(DEFAULT)


@pytest.fixture(scope="module", params=sorted(MASTERS))
def run(request, fmu_path, stop_time):
    """(master name, its run of the default experiment, the matching rows of fmpy's grid)."""
    return request.param, MASTERS[request.param](fmu_path, stop_time, STEPS)


def aligned(theirs, ours):
    """fmpy's rows at the master's communication points (libcosim has no t = 0 row)."""
    ours = ours[len(ours) - len(theirs):]
    np.testing.assert_allclose(theirs["time"], ours["time"], rtol=0, atol=1e-12)   # ulps of t
    return ours


def test_the_default_experiment_ends_in_flight_after_an_iwc_with_w_positive(run, stop_time):
    assert_default_experiment_ends_in_flight_after_an_iwc(*run, stop_time)


def test_w_at_the_end_agrees_with_fmpys_co_simulation_to_the_solver_tolerance(run, fmpy_cs, fmpy_cvode):
    name, theirs = run
    ours = aligned(theirs, fmpy_cs)
    assert abs(theirs["w"][-1] - ours["w"][-1]) <= 10 * RTOL * (1 + abs(ours["w"][-1]))
    for state in STATES:      # every communication point, every state
        gap = np.max(np.abs(theirs[state] - ours[state]))
        assert gap <= 10 * RTOL * (1 + np.max(np.abs(ours[state]))), f"{name}: {state} differs by {gap:.3g}"
    # and with fmpy's CVode (ME, rtol 1e-10) at the return to the floor, to the FMU's tolerance
    w_return = outcome_of(DEFAULT, theirs, exact_events=False).w
    assert abs(w_return - fmpy_cvode.w) < 10 * RTOL * DEFAULT.v0


def test_energy_never_increases_beyond_the_solver_tolerance(run):
    """The damper and sliding friction only take energy (docs/fmu.md, Sticking and energy); in
    flight it is conserved. The importer passes the FMU's `energy` output, which is the
    rod's energy of the states it passes (rod_sim.rod_energy, derived from the states)."""
    name, r = run
    E = r["energy"]
    np.testing.assert_allclose(E, rod_energy(r, alpha=DEFAULT.alpha, epsilon=DEFAULT.epsilon, contact=r["contact"]), rtol=1e-12, atol=1e-12)
    # In flight E is conserved exactly, so what remains is CVODE's error (rtol = RTOL), not round-off.
    bound = RTOL * np.max(np.abs(E))
    assert np.max(np.diff(E)) <= bound, f"{name}: energy rises by {np.max(np.diff(E)):.3g} in one step"
    assert E[-1] < E[0] - 0.1                      # the contact took its share


def test_mode_and_contact_go_through_fmpys_sequence(run, fmpy_cs):
    name, theirs = run
    ours = aligned(theirs, fmpy_cs)
    assert phases(theirs) == phases(ours), name
    # an IWC: slipping forward in contact, a stick, lift-off into flight
    sequence = phases(theirs)
    assert sequence[0] == (True, 1) and (True, 0) in sequence and sequence[-1][0] is False
