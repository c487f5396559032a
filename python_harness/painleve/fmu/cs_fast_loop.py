"""Co-Simulation's fast loop: an IWC case through fmi2DoStep, the FMU integrating
itself with its embedded CVODE, the master seeing communication points only.

The phases come from the FMU's own record of its switches, variables it keeps
exact whatever the communication step (`switches`, `sticks`, and the times the
last stick and contact began and ended), so the master steps STEP_IN_EPSILONS *
eps at a time and reads them only at the end of each step, until the rod has
left the floor; the return to y = 0 is then the closed-form free flight run back
from the first point after it (outcome.flight_back_to_floor)."""
from ..experiments.outcome import (SLIP_BACKWARD, STATE_AT_RETURN, STICK, flight_back_to_floor, no_return,
                                   outcome_from_switches)

# The communication step in eps: well inside the flight after the return (O(1) long).
STEP_IN_EPSILONS = 4
RECORD = ("t_stick_begin", "t_stick_end", "t_contact_begin", "t_contact_end")


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
    return sorted(switches, key=lambda s: s[0])


def run_co_simulation(experiment, case):
    """One case through Co-Simulation, reduced to its Outcome (events: the FMU's switches)."""
    case.check()
    settings = experiment.settings(case)
    h, stop = STEP_IN_EPSILONS * case.epsilon, settings["stop_time"]
    vr = experiment.vr
    with experiment.fresh_run(case) as instance:
        experiment.start(case, settings["relative_tolerance"])
        start = (0.0, *experiment.contact_and_mode())
        t = 0.0
        while t < stop:
            instance.doStep(t, h)
            t += h
            record = experiment.read(RECORD)
            if record["t_contact_end"] > 0 and (state := experiment.read(STATE_AT_RETURN))["y"] >= 0:
                break                                 # left the floor, and back above it
        else:
            raise no_return(case, stop)
        switches, sticks = instance.getInteger([vr["switches"], vr["sticks"]])
    s, back = flight_back_to_floor(state) if state["y"] > 0 else (0.0, state)
    # The return's time from the closed form may fall a rounding error before the lift-off
    # (delta = 0: they are one instant), so no switch is put after it.
    history = [(min(ts, t + s), contact, mode) for ts, contact, mode in switches_from_record(start, record, sticks)]
    return outcome_from_switches(case, history, t + s, back, events=switches)
