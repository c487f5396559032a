# SPDX-License-Identifier: BSD-2-Clause
"""The one definition of an IWC's phases (painleve.experiments.outcome.phases), on switch lists whose
durations follow from the definition by hand, and the same phases read off the FMU and
off the independent scipy reference."""
import math

import pytest

from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from painleve.experiments.outcome import SLIP_BACKWARD, SLIP_FORWARD, STICK, phases
from painleve.experiments.reference import run_reference


def test_compression_stick_lift_off_flight_back_by_the_definition():
    # touch-down at 0, stick 2..5, a slip at the fold, contact ends at 5.1, back on the floor at 6
    switches = [(0.0, True, SLIP_FORWARD), (2.0, True, STICK), (5.0, True, SLIP_BACKWARD),
                (5.1, False, SLIP_BACKWARD)]
    p = phases(switches, 6.0)
    assert p["iwc"]
    assert (p["compression"], p["stick"]) == (2.0, 3.0)
    assert p["lift_off"] == pytest.approx(0.1) and p["flight_back"] == pytest.approx(0.9)


def test_phases_count_from_touch_down_not_from_the_start():
    switches = [(0.0, False, SLIP_FORWARD), (1.0, True, SLIP_FORWARD), (3.0, True, STICK), (4.0, False, STICK)]
    p = phases(switches, 4.0)
    assert (p["compression"], p["stick"], p["lift_off"], p["flight_back"]) == (2.0, 1.0, 0.0, 0.0)


def test_without_a_stick_only_lift_off_and_flight_back():
    p = phases([(0.0, True, SLIP_FORWARD), (3.0, False, SLIP_FORWARD)], 4.0)
    assert not p["iwc"] and math.isnan(p["compression"]) and math.isnan(p["stick"])
    assert (p["lift_off"], p["flight_back"]) == (3.0, 1.0)


def test_switches_after_the_return_are_not_this_iwcs():
    switches = [(0.0, True, SLIP_FORWARD), (1.0, True, STICK), (2.0, False, STICK), (9.0, True, STICK)]
    p = phases(switches, 3.0)
    assert (p["compression"], p["stick"], p["lift_off"], p["flight_back"]) == (1.0, 1.0, 0.0, 1.0)


@pytest.mark.parametrize("delta", [0.0, 1.0])
def test_the_fmu_and_the_reference_have_the_same_phases(fmu_path, delta):
    # Two implementations at rtol 1e-10: event times agree to rtol times the steps, amplified
    # along the unstable manifold of the compression (test_me_fast_loop.py): 1e-6 of the run.
    case = Case(epsilon=1e-4, delta=delta)
    with Experiment(fmu_path, relative_tolerance=1e-10) as ex:
        fmu = ex.run(case)
    ref = run_reference(case, "Radau", relative_tolerance=1e-10)
    assert fmu.iwc and ref.iwc
    for name in ("compression", "stick", "lift_off", "flight_back"):
        assert abs(getattr(fmu, name) - getattr(ref, name)) <= 1e-6 * fmu.t_return, name
