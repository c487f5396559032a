# SPDX-License-Identifier: BSD-2-Clause
"""The Zeno guard's instant against the time's resolution (fmu_src/contact/contact_record.h):
an autonomous body's contact gives the same outcome whenever it starts, as long as the time
can place its events; a contact faster than the time resolves ends in the guard, which says
so; a true run of events at one instant still ends as a Zeno run, far from t = 0 too."""
import math
import sys

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.simulation import instantiate_fmu

from conftest import built_fmu

# Events are placed to 100 ulps of |t| + |h| (CVODE's root finding, the explicit pair's):
# at t the guard cannot tell apart events closer than 256 ulps of t.
RESOLUTION_ULPS = 256


def resolution(t):
    return RESOLUTION_ULPS * sys.float_info.epsilon * abs(t)


class Arm:
    """TwoLinkArm through Co-Simulation, FMI 2.0 or 3.0, step by step, with its log."""

    def _log(self, *args):
        # the last line of a refused step is its reason, not the step's statistics that follow it
        if args[-2] != b"logStatistics":
            self.messages.append(str(args[-1]))

    def __init__(self, fmi, start, tolerance, values):
        path = built_fmu("TwoLinkArm.fmu") if fmi == 2 else built_fmu("fmi3", "TwoLinkArm.fmu")
        md = read_model_description(path)
        self.fmi3, self.vr, self.t, self.messages = fmi == 3, {v.name: v.valueReference for v in md.modelVariables}, \
            start, []
        self.fmu = instantiate_fmu(extract(path), md, "CoSimulation", debug_logging=True,
                                   logger=self._log)
        names = list(values)
        if self.fmi3:
            self.fmu.setFloat64([self.vr[n] for n in names], [values[n] for n in names])
            self.fmu.enterInitializationMode(tolerance=tolerance, startTime=start)
        else:
            self.fmu.setupExperiment(tolerance=tolerance, startTime=start)
            self.fmu.setReal([self.vr[n] for n in names], [values[n] for n in names])
            self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def step(self, h):
        self.fmu.doStep(self.t, h)
        self.t += h

    def get(self, *names):
        get = self.fmu.getFloat64 if self.fmi3 else self.fmu.getReal
        return dict(zip(names, get([self.vr[n] for n in names])))

    def free(self):
        self.fmu.freeInstance()


# The arm's own start (its model description's): the tip on the floor in the paradox region,
# an IWC with a stick. A floor of k = 1e15 N/m damped at delta = c/sqrt(M k) = 1 makes the
# contact last about 3e-7 s: at t = 1e6 s, 5 event resolutions.
M, K = 0.8, 1e15
STIFF = dict(k=K, c=math.sqrt(M * K))
ANGLES = ("omega1", "omega2")
TIMES = ("t_contact_begin", "t_stick_begin", "t_contact_end")


def stiff_arm(fmi, start):
    arm = Arm(fmi, start, 1e-8, STIFF)
    before = arm.get(*ANGLES)
    for _ in range(4):
        arm.step(5e-4)
    after = arm.get(*ANGLES, *TIMES)
    arm.free()
    return before, {k: v - start if k in TIMES else v for k, v in after.items()}


@pytest.mark.parametrize("fmi", [2, 3])
def test_a_stiff_contact_far_from_t_0_lifts_off_as_near_it(fmi):
    # The arm is autonomous: started at t = 1e6 s it must do what it does at t = 0, up to where
    # the time places its events there (resolution(1e6) = 5.7e-8 s). A switch placed late by
    # that acts for that long with a force of the contact's size, so the velocities after the
    # contact may move by at most resolution / contact time of their change over it.
    before, near = stiff_arm(fmi, 0.0)
    _, far = stiff_arm(fmi, 1e6)
    contact = near["t_contact_end"] - near["t_contact_begin"]
    assert near["t_contact_begin"] == far["t_contact_begin"] == 0 and 1e-7 < contact < 1e-6
    for k in ("t_stick_begin", "t_contact_end"):
        assert abs(far[k] - near[k]) <= resolution(1e6), k
    for k in ANGLES:
        change = abs(near[k] - before[k])
        assert abs(far[k] - near[k]) <= resolution(1e6) / contact * change, k


# bench/bounded_calls.py's case 1272 (seed 1): the tip starts 0.74 m deep in a floor of
# k = 1e15 N/m, stiffened (kappa) and damped (beta) with depth: a violent release, events
# 2e-11 s apart at first.
DEEP = dict(m1=0.5, l1=0.71356548827629784, J1=0, m2=0.3, l2=0.2, J2=0.001, H=0.056230491755616813, k=1e15,
            c=912.41174536129006, mu=0.27453618664048834, kappa=0.1170319172750601, beta=3.1837581430779633,
            theta1=-1, theta2=-1.3, omega1=-0.6035, omega2=1.9333763913726258)
DEEP_STEPS = (5.149773021661734e-06, 0.0013939157684175298, 0.0005972754465849777)


def test_a_contact_faster_than_the_time_resolves_ends_in_the_guard_saying_so():
    # Even the undamped contact's time scale sqrt(M/k) = 2.9e-8 s is below the time to which events
    # are placed at t = 1e6 s: the run cannot go on there, and the guard says why, not "Zeno".
    tip = DEEP["H"] + DEEP["l1"] * math.sin(DEEP["theta1"]) + DEEP["l2"] * math.sin(DEEP["theta2"])
    assert tip < -0.7 and math.sqrt((DEEP["m1"] + DEEP["m2"]) / DEEP["k"]) < resolution(1e6)
    arm = Arm(2, 1e6, 1e-3, DEEP)
    with pytest.raises(FMICallException) as refused:
        for h in DEEP_STEPS:
            arm.step(h)
    assert refused.value.status == 3
    line = arm.messages[-1]
    assert "t cannot resolve the contact at this time" in line and "Zeno" not in line, line
    assert f"below the {resolution(arm.t):.3g} to which events" in line and "the boundary '" in line, line
    scale = float(line.split("its time scale ")[1].split()[0])
    assert 0 < scale < resolution(arm.t)
    arm.free()


def test_the_same_deep_start_near_t_0_runs_to_its_end():
    # Where the time resolves the contact the same motion goes on: every step is taken.
    arm = Arm(2, 0.0, 1e-3, DEEP)
    for h in DEEP_STEPS:
        arm.step(h)
    assert arm.t == pytest.approx(sum(DEEP_STEPS))
    assert all(math.isfinite(v) for v in arm.get(*ANGLES).values())
    assert not any("Zeno" in m or "cannot resolve" in m for m in arm.messages)
    arm.free()
