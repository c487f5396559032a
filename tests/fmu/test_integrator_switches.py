# SPDX-License-Identifier: BSD-2-Clause
"""Every switch of Co-Simulation's integrator completes wherever the master's communication points
fall (fmu_src/fmi/instance_step.c): the explicit pair's hand-over to CVODE in a sustained stiff
phase, the closed-form flight's landing where the pair takes over, and the restarts at events
(the pair's and CVODE's); at a step's end, at a step's start, within a few units in the last place
(ulps) of either, and after an FMU state restore; in FMI 2.0 and 3.0.

Each switch's time is first read from the FMU's event log in one uninterrupted step; the runs that
put a communication point on it, or a few ulps either side, must return OK at every step and end
where the uninterrupted run ends, to the tolerance: the solution does not depend on where the
master samples it. Where the physics fixes the switch's time (a rod dropped with no spin and no
vertical velocity lands after sqrt(2 y0 / g)), the FMU must put it there. Last, the recorded runs
that ended in CVode (-22) replay with OK at every step."""
import json
import math
import pathlib

import numpy as np
import pytest

from conftest import built_fmu
from helpers.cs_slave import Slave, Unpacked, ulps_from

TOLERANCE = 1e-6    # every scenario's (the FMUs' default too)

# Two runs that each hold every step's local error to rtol (|x| + nominal) (CVODE's and the pair's
# error test), through a damped contact that does not amplify differences, end within a small
# multiple of that of each other, and of the true solution.
AGREE = 50

# The issue's SI rod: stepped by stopTime / 60 from 0, its 42nd step (0.034167 to 0.035) ended in
# CVode (-22) where the pair handed a sustained stiff phase to CVODE at the step's end.
SI_ISSUE = dict(m=0.11075540715862829, l=0.06608815254978619, J=0.18743874722537796, g=82.84764506376017,
                k=6357327.019697341, c=4303.3608954933425, mu=3.3706875026659566)

# Sustained stiff phases, each handed from the pair to CVODE once: (FMU, start time, start values,
# horizon after the start).
#   rod       the rod at rest standing on the floor at theta = 1 with mu = 3, eps = 1e-5: it sticks
#             and tips over in a contact of O(1) time, whose spring holds the pair's steps; CVODE
#             then meets the backward fold and a new stick (events under CVODE).
#   rod_late  the same rod at eps = 1e-6 started at t = 1000, where the time's resolution is
#             10^4 times coarser (the rod is autonomous: the same physics).
#   rod_si    the issue's SI rod.
#   arm       the two-link arm at rest with its tip on the floor, the contact overdamped (c = 3e4).
#   table     the shaker table on a stiff, overdamped mount (K = 4e10 N/m, C = 1e7 N s/m, M = 10 kg):
#             modes at -K/C = -4e3 and -C/M = -1e6 per second, the fast one stiff from the start.
HAND_OVERS = {
    "rod": ("PainleveRod.fmu", 0.0, dict(epsilon=1e-5, v=0.0, w=0.0, theta=1.0, phi=0.0), 2.5),
    "rod_late": ("PainleveRod.fmu", 1000.0, dict(epsilon=1e-6, v=0.0, w=0.0, theta=1.0, phi=0.0), 0.005),
    "rod_si": ("PainleveRodSI.fmu", 0.0, SI_ISSUE, 0.05),
    "arm": ("TwoLinkArm.fmu", 0.0, dict(omega1=0.0, omega2=0.0, mu=3.0, c=3e4), 0.15),
    "table": ("ShakerTable.fmu", 0.0, dict(K=4e10, C=1e7), 0.003),
}

# Flights that land (closed form to the pair) and the impacts that follow: the rod dropped from
# y0 with theta = 1, no spin and no vertical velocity lands after sqrt(2 y0 / g) (its lower end
# falls with the centre), g = 1 in the dimensionless rod, 9.81 m/s^2 in the SI rod.
LANDINGS = {
    "rod": ("PainleveRod.fmu", 0.0, dict(y=0.5, w=0.0, theta=1.0, phi=0.0, v=0.5), 1.1, 1.0),
    "rod_late": ("PainleveRod.fmu", 1000.0, dict(y=0.5, w=0.0, theta=1.0, phi=0.0, v=0.5), 1.1, 1.0),
    "rod_si": ("PainleveRodSI.fmu", 0.0, dict(y=0.02, w=0.0, theta=1.0, phi=0.0, v=0.5), 0.08,
               math.sqrt(2 * 0.02 / 9.81)),
}

# Events under the pair alone: the arm's default experiment (stick, folds 2e-11 s apart, lift-offs,
# landings: 24 events in 0.05 s).
ARM_EVENTS = ("TwoLinkArm.fmu", 0.0, {}, 0.05)

VERSIONS = [2, 3]
NEAR = (-3, -1, 0, 1, 3)    # ulps from a switch


@pytest.fixture(scope="module")
def unpacked():
    u = Unpacked()
    yield u
    u.close()


def fmu_file(name, fmi):
    return built_fmu(name) if fmi == 2 else built_fmu("fmi3", name)


def slave(unpacked, scenario, fmi, early_return=False, tolerance=TOLERANCE):
    name, t0, start, *_ = scenario
    return Slave(unpacked, fmu_file(name, fmi), tolerance, t0, early_return=early_return, **start)


def run(unpacked, scenario, fmi, points, early_return=False):
    """A run through the communication points given to the scenario's horizon: its final state and
    the instance (freed)."""
    s = slave(unpacked, scenario, fmi, early_return)
    for t in list(points) + [scenario[1] + scenario[3]]:
        s.step_to(t)
    x = np.array(s.state())
    s.free()
    return x, s


def assert_agree(x, ref, s, what):
    for name, a, b, nominal in zip(s.states, x, ref, s.nominals):
        assert abs(a - b) <= AGREE * TOLERANCE * (max(abs(a), abs(b)) + nominal), (what, name, a, b)


_references = {}


def reference(unpacked, scenario, fmi):
    """The uninterrupted run: one step to the horizon."""
    key = (repr(scenario), fmi)
    if key not in _references:
        _references[key] = run(unpacked, scenario, fmi, [])
    return _references[key]


def hand_over(unpacked, scenario, fmi):
    ref, s = reference(unpacked, scenario, fmi)
    assert len(s.hand_overs()) == 1, s.hand_overs()
    return s.hand_overs()[0], ref


@pytest.mark.parametrize("k", NEAR)
@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("name", HAND_OVERS)
def test_a_hand_over_to_cvode_at_a_steps_end_completes(unpacked, name, fmi, k):
    scenario = HAND_OVERS[name]
    T, ref = hand_over(unpacked, scenario, fmi)
    x, s = run(unpacked, scenario, fmi, [ulps_from(T, k)])
    # at the switch, or at the step's end a few ulps from it (the same instant to the time's resolution)
    assert len(s.hand_overs()) == 1 and abs(s.hand_overs()[0] - T) <= abs(ulps_from(T, k) - T)
    assert_agree(x, ref, s, f"a step's end {k} ulps from the hand-over at {T!r}")


@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("name", HAND_OVERS)
def test_steps_that_start_at_a_hand_over_complete(unpacked, name, fmi):
    # Steps of 1 to 300 ulps from the hand-over (those within the time's resolution reach their end
    # as they are), then a master whose own arithmetic put its communication point 100 ulps behind
    # the instance's time (within the 1e-12 it forgives) and whose step ends before CVODE's time.
    scenario = HAND_OVERS[name]
    T, ref = hand_over(unpacked, scenario, fmi)
    s = slave(unpacked, scenario, fmi)
    s.step_to(T)
    assert s.hand_overs() == [T]
    for k in (1, 3, 8, 40, 300):
        s.step_to(ulps_from(s.t, k))
    behind = ulps_from(s.t, -100)
    s.do_step(behind, ulps_from(behind, 60) - behind)
    s.t = ulps_from(behind, 60)
    s.step_to(scenario[1] + scenario[3])
    assert len(s.hand_overs()) == 1
    assert_agree(np.array(s.state()), ref, s, "steps starting at the hand-over")
    s.free()


@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("name", HAND_OVERS)
def test_a_masters_even_grid_through_a_hand_over_agrees_with_one_step(unpacked, name, fmi):
    scenario = HAND_OVERS[name]
    _, ref = hand_over(unpacked, scenario, fmi)
    t0, horizon = scenario[1], scenario[3]
    x, s = run(unpacked, scenario, fmi, [t0 + horizon * i / 60 for i in range(1, 60)])
    assert len(s.hand_overs()) == 1
    assert_agree(x, ref, s, "60 even steps")


@pytest.mark.parametrize("fmi", VERSIONS)
def test_the_issues_si_rod_stepped_by_stop_time_over_60_completes(unpacked, fmi):
    # Its own default tolerance, steps t += h as a master adds them (stopTime = 0.05).
    s = Slave(unpacked, fmu_file("PainleveRodSI.fmu", fmi), None, **SI_ISSUE)
    h, t = 0.05 / 60, 0.0
    for _ in range(60):
        s.do_step(t, h)
        t += h
    s.t = t
    _, ref = hand_over(unpacked, HAND_OVERS["rod_si"], fmi)
    assert_agree(np.array(s.state()), ref, s, "the issue's 60 steps")
    s.free()


@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("name", HAND_OVERS)
def test_a_hand_over_at_a_steps_end_after_an_fmu_state_restore(unpacked, name, fmi):
    # States taken at the start (where the integrator starts anyway: the hand-over stays where the
    # uninterrupted run has it) and at the hand-over, at a step's end; each restored, the run
    # repeats bit for bit, and a restore at the hand-over restarts CVODE at a step's start.
    scenario = HAND_OVERS[name]
    T, ref = hand_over(unpacked, scenario, fmi)
    t0, end = scenario[1], scenario[1] + scenario[3]
    s = slave(unpacked, scenario, fmi)
    saved = s.get_fmu_state()
    runs = []
    for _ in range(2):                 # the run, then the same run from the restored start
        s.step_to(T)                   # the hand-over at the step's end
        at_switch = s.get_fmu_state()  # taken with CVODE integrating on
        s.step_to(end)
        first = np.array(s.state())
        s.set_fmu_state(at_switch, T)
        s.step_to(end)
        runs.append((first, np.array(s.state())))
        s.free_fmu_state(at_switch)
        s.set_fmu_state(saved, t0)
    s.free_fmu_state(saved)
    assert s.hand_overs() == [T, T]
    assert np.array_equal(runs[0][0], runs[1][0]) and np.array_equal(runs[0][1], runs[1][1])
    for x in runs[0]:
        assert_agree(x, ref, s, "after a restore")
    s.free()


def switch_times(s, t0):
    return [t for t, text in s.events() if t > t0]


@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("name", LANDINGS)
def test_a_landing_at_a_steps_end_hands_the_flight_to_the_pair(unpacked, name, fmi):
    # The closed-form flight ends at the landing, where the pair takes over; a step's end on it,
    # or up to 300 ulps (the root finder's resolution and more) either side of it.
    scenario = LANDINGS[name]
    t0, fall = scenario[1], scenario[4]
    ref, r = reference(unpacked, scenario, fmi)
    T = switch_times(r, t0)[0]
    assert abs(T - (t0 + fall)) <= 256 * np.finfo(float).eps * abs(T), (T, t0 + fall)
    for k in (-300, -100, -16, -5, -1, 0, 1, 5, 16, 100, 300):
        x, s = run(unpacked, scenario, fmi, [ulps_from(T, k)])
        assert abs(switch_times(s, t0)[0] - T) <= 256 * np.finfo(float).eps * abs(T), k
        assert s.hand_overs() == r.hand_overs(), k
        assert_agree(x, ref, s, f"a step's end {k} ulps from the landing at {T!r}")


EVENT_RUNS = {
    "rod_under_cvode": HAND_OVERS["rod"],
    "rod_landing": LANDINGS["rod"],
    "rod_si_landing": LANDINGS["rod_si"],
    "arm_under_the_pair": ARM_EVENTS,
}


@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("name", EVENT_RUNS)
def test_every_event_at_a_steps_end_completes(unpacked, name, fmi):
    # Each event of the uninterrupted run (the integrator restarts there: the pair, the flight or
    # CVODE), with a step's end on it and 3 ulps either side.
    scenario = EVENT_RUNS[name]
    ref, r = reference(unpacked, scenario, fmi)
    events = [t for t in switch_times(r, scenario[1]) if t not in r.hand_overs()]
    assert events
    for T in events:
        for k in (-3, 0, 3):
            x, s = run(unpacked, scenario, fmi, [ulps_from(T, k)])
            assert_agree(x, ref, s, f"a step's end {k} ulps from the event at {T!r}")


@pytest.mark.parametrize("name", EVENT_RUNS)
def test_every_event_at_a_steps_start_completes_under_early_return(unpacked, name):
    # FMI 3.0 with early return: each step ends right after an event's update and the next starts
    # there, so every restart, and the hand-over's steps, are at a step's start.
    scenario = EVENT_RUNS[name]
    ref, r = reference(unpacked, scenario, 3)
    x, s = run(unpacked, scenario, 3, [], early_return=True)
    assert s.hand_overs() == r.hand_overs()
    assert_agree(x, ref, s, "early return at every event")


@pytest.mark.parametrize("fmi", VERSIONS)
def test_a_restart_then_steps_of_a_few_ulps_stay_with_the_pair(unpacked, fmi):
    # The arm's default experiment started at t = 1000 (it is autonomous), where an ulp is 1.1e-13:
    # at each of its first events, a state is taken (the integrator restarts there, at the next
    # step's start) and steps of 1 to 60 ulps follow. Each tiny step is the pair's last step, however
    # small: it reaches its end, and hands nothing to CVODE, as the uninterrupted run hands nothing.
    # An event within the 121 ulps of tiny steps after the one before (a stick's fold touched, then
    # crossed 100 ulps later) is passed by them: the run restarts there within the tiny steps.
    t0, end = 1000.0, 1000.0 + ARM_EVENTS[3]
    scenario = ("TwoLinkArm.fmu", t0, {}, ARM_EVENTS[3])
    ref, r = reference(unpacked, scenario, fmi)
    assert r.hand_overs() == []
    events = switch_times(r, t0)[:4]
    s = slave(unpacked, scenario, fmi)
    for T in events:
        if T <= s.t:
            continue
        s.step_to(T)
        s.free_fmu_state(s.get_fmu_state())
        for k in (1, 5, 9, 16, 30, 60):
            s.step_to(ulps_from(s.t, k))
    s.step_to(end)
    assert s.hand_overs() == []
    assert_agree(np.array(s.state()), ref, s, "steps of a few ulps after restarts")
    s.free()


REPLAYS = json.loads((pathlib.Path(__file__).parent / "data" / "switch_cases.json").read_text())["cases"]


@pytest.mark.parametrize("fmi", VERSIONS)
@pytest.mark.parametrize("case", REPLAYS, ids=[f"{c['model']}-fmi{c['fmi_version']}" for c in REPLAYS])
def test_the_recorded_runs_that_ended_in_cvode_errors_return_ok_at_every_step(unpacked, case, fmi):
    """Random legal Co-Simulation runs with irregular communication steps that ended in CVode (-22)
    at a step's end (PainleveRod FMI 2.0, TwoLinkArm FMI 3.0, PainleveRodSI FMI 3.0): the three
    "solver_error" cases of the workplace's shared reproduction file (the repro folder's cases.json,
    beside the repository), copied as they were into data/switch_cases.json. Each case
    runs in the FMI version it was recorded in and in the other (both share the integrators): its
    start values, tolerance and start time, then its steps as a master adds them up."""
    s = Slave(unpacked, fmu_file(case["model"] + ".fmu", fmi), case["tolerance"], case["start_time"],
              **case["start_values"])
    t = case["start_time"]
    for h in case["steps"]:
        s.do_step(t, h)
        t += h
    assert all(np.isfinite(s.state()))
    s.free()
