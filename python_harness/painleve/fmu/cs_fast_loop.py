# SPDX-License-Identifier: BSD-2-Clause
"""Co-Simulation's fast loop: an IWC case through fmi2DoStep, the FMU integrating
itself (its explicit pair, CVODE where the contact is stiff), the master seeing
communication points only.

The phases come from the FMU's own record of its switches, variables it keeps
exact whatever the communication step (`switches`, `sticks`, and the times the
last stick and contact began and ended). A case first runs through one doStep
to its horizon: if the rod is then in the air above the floor and the record
accounts for every switch the FMU counted (one contact, at most one stick), the
record is the whole history and the return to y = 0 is the closed-form free
flight run back from the horizon (outcome.flight_back_to_floor). Otherwise (a
second contact, a switch the record does not keep, the rod still below the
floor) the case runs again stepped: a doStep STEP_IN_EPSILONS * eps at a time,
the record read after each, until the rod has left the floor and is back above it."""
import math
from operator import itemgetter

from ..experiments.outcome import (SLIP_BACKWARD, STATE_AT_RETURN, STICK, back_on_floor, flight_back_to_floor,
                                   no_return, outcome_from_switches)
from ..theory.analytic import predict
from .cs_calls import contact_and_mode, initialize

# The communication step in eps: well inside the flight after the return (O(1) long).
STEP_IN_EPSILONS = 4
# How far (in eps) a return run back in closed form may fall before the lift-off: at delta = 0 they are one
# instant, apart by rounding (up to 1e-6 eps seen at eps = 1e-2); a wrong root would be O(eps) away.
ROUNDING_SLACK = 1e-4
RECORD = ("t_stick_begin", "t_stick_end", "t_contact_begin", "t_contact_end")
READ = RECORD + STATE_AT_RETURN      # what the loop reads after each doStep (cs_calls)
_CONTACT_END, _Y = READ.index("t_contact_end"), READ.index("y")
# How closely a body's return is bisected on the Co-Simulation steps: this fraction of its time.
RETURN_TIME_RESOLUTION = 1e-13


def switches_from_record(start, record, sticks):
    """The switches [(t, contact, mode)] (the start first) that the FMU's record implies for a run
    with one contact and at most one stick (an IWC or a lift-off): the contact's start if after
    the run's, the stick's start and end, the contact's end. Out of a stick the rod slips at the
    fold (its direction does not enter the phases)."""
    (t0, contact, mode) = start
    switches = [start]
    if record["t_contact_begin"] > t0:
        switches.append((record["t_contact_begin"], True, mode))
    if sticks:
        switches.append((record["t_stick_begin"], True, STICK))
        if record["t_stick_end"] > record["t_stick_begin"]:
            switches.append((record["t_stick_end"], True, SLIP_BACKWARD))
    if record["t_contact_end"] > t0:
        switches.append((record["t_contact_end"], False, SLIP_BACKWARD))
    return sorted(switches, key=itemgetter(0))


def _outcome(case, t, implied, back, switches):
    """The Outcome of a run seen at t with the switches `implied` by its record, back on the floor at
    t + s in state back (s, back: run_back)."""
    s, state = back
    # The return's time from the closed form may fall a rounding error before the lift-off
    # (delta = 0: they are one instant), so no switch is put after it.
    history = [(min(ts, t + s), contact, mode) for ts, contact, mode in implied]
    return outcome_from_switches(case, history, t + s, state, events=switches)


def run_back(state):
    """(s, state at the return): the flight run back in closed form from a state above the floor."""
    return flight_back_to_floor(state) if state["y"] > 0 else (0.0, state)


def record_tells(start, record, state, contact, switches, sticks, implied=None):
    """Whether a run seen in this state is one whose outcome the record gives: out of contact, above
    the floor and rising (so the closed form run back finds the last return) after its contact,
    and every switch the FMU counted in the history the record implies (a second contact, or a
    switch the record keeps no time of, would make the count exceed it). `implied`:
    switches_from_record(start, record, sticks), if made."""
    if contact or state["y"] < 0 or state["w"] <= 0 or record["t_contact_end"] <= start[0] or sticks > 1:
        return False
    return switches == len(implied or switches_from_record(start, record, sticks)) - 1


def first_step(case, prediction=None):
    """The first communication step: past the end of contact, before the rod can land again. The
    contact lasts at most 1.43 eps (ln(1/eps)/lambda_+ + 1 + delta) on the validation's and the
    benchmark's cases (the compression's ln(1/eps)/lambda_+ in fast time, then O(1 + delta) to
    stick and lift off); twice that, within the horizon. `prediction`: predict(case), if known."""
    lambda_plus = (prediction or predict(case)).lambda_plus
    estimate = case.epsilon * (math.log(1 / case.epsilon) / lambda_plus + 1 + case.delta)
    return 2 * estimate if math.isfinite(estimate) else STEP_IN_EPSILONS * case.epsilon


def run_stepped(experiment, case, first=None, prediction=None):
    """The case through a first doStep of `first` (default STEP_IN_EPSILONS * eps), then
    STEP_IN_EPSILONS * eps at a time, the record read after each, to the first communication
    point after the rod has left the floor and is back above it. With `first`: its Outcome if
    the record tells it there (record_tells), else None. `prediction`: predict(case), if known."""
    settings = experiment.settings(case, prediction)
    h, stop = STEP_IN_EPSILONS * case.epsilon, settings["stop_time"]
    calls = experiment.cs_calls
    with experiment.fresh_run(case, calls):
        start = (0.0, *calls.start(case.start_values(), settings["relative_tolerance"]))
        t, step = 0.0, min(first or h, stop)
        while t < stop:
            values = calls.step(t, step)
            t, step = t + step, h
            # Touched: the record says a contact has ended. Contact is not read each step: there is
            # none above the floor (y > 0), and the record's check (record_tells) reads it at the end.
            if back_on_floor(values[_CONTACT_END] > 0, False, values[_Y]):
                break
        else:
            raise no_return(case, stop)
        switches, sticks, contact = calls.end()
    record, state = dict(zip(RECORD, values)), dict(zip(STATE_AT_RETURN, values[len(RECORD):]))
    implied = switches_from_record(start, record, sticks)
    if first is not None and not record_tells(start, record, state, contact, switches, sticks, implied):
        return None
    back = run_back(state)
    # With `first`, the return must follow the lift-off (delta = 0: be one instant with it, within
    # the closed form's rounding): a root of the run back before it would be in the contact.
    if first is not None and t + back[0] < record["t_contact_end"] - ROUNDING_SLACK * case.epsilon:
        return None
    return _outcome(case, t, implied, back, switches)


def run_co_simulation(experiment, case, prediction=None):
    """One case through Co-Simulation, reduced to its Outcome (events: the FMU's switches): one long
    first step where the record tells the outcome after it, else the case again, stepped.
    `prediction`: predict(case), if known."""
    case.check()
    return (run_stepped(experiment, case, first_step(case, prediction), prediction)
            or run_stepped(experiment, case, prediction=prediction))


def run_to_return(experiment, case, start_values, *, relative_tolerance, stop_time, step, read):
    """One run of any body through Co-Simulation from `start_values`: doSteps of `step` until a
    communication point at which it is back_on_floor (touched: in contact at a communication point,
    or a contact the FMU's record says has ended), then that last step bisected, from the FMU state
    saved before it, down to RETURN_TIME_RESOLUTION of the time: the return as closely as Model
    Exchange's event locates it. Its Outcome (the Real variables `read`, y among them, at the
    return; the phases from the FMU's record, switches_from_record; events: the FMU's switches),
    or None if it is not back by stop_time. The FMU must be able to get and set its state."""
    instance, vr = experiment.instance, experiment.vr
    names = list(RECORD) + [n for n in read if n not in RECORD]

    def advance(t, h, touched):
        instance.doStep(currentCommunicationPoint=t, communicationStepSize=h, noSetFMUStatePriorToCurrentPoint=False)
        values = experiment.read(names)
        contact = contact_and_mode(instance, vr)[0]
        touched = touched or contact or values["t_contact_end"] > 0
        counts = instance.getInteger([vr["switches"], vr["sticks"]])
        return values, back_on_floor(touched, contact, values["y"]), touched, counts

    with experiment.fresh_run(f"{case}") as instance:
        initialize(instance, vr, dict(start_values), relative_tolerance)
        start = (0.0, *contact_and_mode(instance, vr))
        t, touched = 0.0, start[1]
        while t < stop_time:
            before = instance.getFMUState()
            try:
                values, back, now_touched, counts = advance(t, step, touched)
                if back:
                    t, values, counts = _bisect_return(instance, advance, before, t, step, touched, (values, counts))
                    break
            finally:
                instance.freeFMUState(before)
            t, touched = t + step, now_touched
        else:
            return None
    record = {k: values[k] for k in RECORD}
    switches, sticks = (int(n) for n in counts)
    implied = [(min(ts, t), contact, mode) for ts, contact, mode in switches_from_record(start, record, sticks)]
    return outcome_from_switches(case, implied, t, {k: values[k] for k in read}, events=switches)


def _bisect_return(instance, advance, before, t, step, touched, at_step_end):
    """(time, values, counts) at the return within the step from t (state `before`) to t + step, at whose
    end the run is back on the floor: bisected on the step's length."""
    lo, hi, at_hi, state_lo = 0.0, step, at_step_end, before
    try:
        while hi - lo > RETURN_TIME_RESOLUTION * (t + hi):
            mid = 0.5 * (lo + hi)
            instance.setFMUState(state_lo)
            values, back, now_touched, counts = advance(t + lo, mid - lo, touched)
            if back:
                hi, at_hi = mid, (values, counts)
            else:
                lo, touched = mid, now_touched
                if state_lo is not before:
                    instance.freeFMUState(state_lo)
                state_lo = instance.getFMUState()
    finally:
        if state_lo is not before:
            instance.freeFMUState(state_lo)
    return t + hi, at_hi[0], at_hi[1]
