# SPDX-License-Identifier: BSD-2-Clause
"""Drives the FMU through the harness for the tests, and reads trajectories the way a physicist would."""
import math

import fmpy
import numpy as np
import pytest

from painleve.experiments.case import Case
from painleve.experiments.outcome import outcome_of_trajectory
from painleve.fmu.experiment import Experiment

OUTPUTS = ("x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy", "mode", "contact")


def simulate(fmu, stop_time, *, solver="CVode", rtol=1e-6, step_size=None, output_interval=None, **start):
    """One Model Exchange run with every output recorded, events included; fails on any NaN or infinity."""
    with Experiment(fmu) as experiment:
        result = experiment.simulate_from(start, stop_time=stop_time, output_interval=output_interval,
                                          relative_tolerance=rtol, output=OUTPUTS, solver=solver, step_size=step_size)
    assert np.all(np.isfinite(result["time"])), "time is not finite"
    return result


def default_stop_time(fmu):
    """The stop time of the FMU's DefaultExperiment."""
    return float(fmpy.read_model_description(fmu).defaultExperiment.stopTime)


def co_simulation_on_grid(fmu, stop_time, steps):
    """fmpy's Co-Simulation of the default experiment, every output on the grid stop_time/steps."""
    return fmpy.simulate_fmu(fmu, fmi_type="CoSimulation", output_interval=stop_time / steps, output=list(OUTPUTS))


def mode_changes(result):
    """Indices i where (contact, mode) differs from row i-1."""
    key = result["contact"].astype(int) * 10 + result["mode"]
    return np.flatnonzero(np.diff(key) != 0) + 1


def phases(result):
    """The sequence of (contact, mode) the run went through."""
    starts = np.concatenate(([0], mode_changes(result)))
    return [(bool(result["contact"][i]), int(result["mode"][i])) for i in starts]


def event_count(result):
    """fmpy records each event twice, at the same time."""
    return int(np.sum(np.diff(result["time"]) == 0))


def rod_energy(r, alpha, epsilon, contact):
    """Energy of the rod and the contact spring, derived here from the states alone:
    the centre of mass is (x - cos theta, y + sin theta) (eq coord), the moment of inertia 1/alpha.
    The spring holds (y/eps)^2/2 only where `contact` (its force acts): after a damped
    lift-off at y < 0 it is let go, so the energy is constant in free flight."""
    s, c, phi, y = np.sin(r["theta"]), np.cos(r["theta"]), r["phi"], r["y"]
    kinetic = 0.5 * ((r["v"] + phi * s) ** 2 + (r["w"] + phi * c) ** 2) + 0.5 * phi**2 / alpha
    spring = np.where(contact, 0.5 * (y / epsilon) ** 2, 0.0)
    return kinetic + (y + s) + spring


def energy_gradient(x, alpha, epsilon, contact):
    """d rod_energy / d (x, v, y, w, theta, phi) at one state x."""
    _, v, y, w, th, ph = x
    s, c = np.sin(th), np.cos(th)
    Xd, Yd = v + ph * s, w + ph * c
    return np.array([0.0, Xd, 1 + (y / epsilon**2 if contact else 0.0), Yd, Xd * ph * c - Yd * ph * s + c,
                     Xd * s + Yd * c + ph / alpha])


def theorem_bound(case):
    """Theorem 1's error, O(eps ln 1/eps), with the constant the importers' runs keep to."""
    return 3 * case.epsilon * math.log(1 / case.epsilon)


def assert_default_experiment_ends_in_flight_after_an_iwc(name, r, stop_time):
    """An importer's run of the default experiment (the modelDescription's start values, Case()): to the
    stop time, finite, an IWC whose w is e(delta, theta0) v0 within Theorem 1's bound, then lift-off."""
    case = Case()
    assert r["time"][-1] == pytest.approx(stop_time, rel=1e-12)
    for field in r.dtype.names:
        assert np.all(np.isfinite(r[field])), f"{name}: {field} is not finite"
    outcome = outcome_of_trajectory(case, r, exact_events=False)
    assert outcome.iwc, f"{name}: no stick before lift-off"
    assert abs(outcome.w_error) < theorem_bound(case)             # Theorem 1: w -> e(delta, theta0) v0
    assert r["w"][-1] > 0 and not r["contact"][-1]                # lifted off, still rising at the stop time
