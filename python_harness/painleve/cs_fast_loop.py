"""Co-Simulation's fast loop: an IWC case through fmi2DoStep, the FMU integrating
itself with its embedded CVODE, the master seeing communication points only.

The phases are read exactly from the FMU's event log (`mode_switches`, the one
place that knows its format), so the master steps STEP_IN_EPSILONS * eps at a
time and reads the state only at the end of each step, until the rod has left
the floor; the return to y = 0 is then the closed-form free flight run back
from the first point after it (outcome.flight_back_to_floor)."""
import re

from .outcome import STATE_AT_RETURN, flight_back_to_floor, no_return, outcome_from_switches

# The communication step in eps: well inside the flight after the return (O(1) long).
STEP_IN_EPSILONS = 4
# The FMU's logEvents message for a mode switch (fmi2_me.c, handle_event).
_SWITCH_MESSAGE = re.compile(r"t = (?P<t>\S+): indicator .*; contact \d -> (?P<contact>\d), "
                             r"mode \S+ -> (?P<mode>\S+?)(;|$)")


def mode_switches(messages):
    """[(t, contact, mode)] after each switch the FMU logged (category logEvents), in order."""
    switches = []
    for _, category, message in messages:
        if category == "logEvents" and (m := _SWITCH_MESSAGE.match(message)):
            switches.append((float(m["t"]), m["contact"] == "1", int(m["mode"])))
    return switches


def run_co_simulation(experiment, case):
    """One case through Co-Simulation, reduced to its Outcome (events: the logged switches)."""
    case.check()
    settings = experiment.settings(case)
    h, stop = STEP_IN_EPSILONS * case.epsilon, settings["stop_time"]
    with experiment.fresh_run(case) as instance:
        instance.setDebugLogging(True, ["logEvents"])
        experiment.start(case, settings["relative_tolerance"])
        switches = [(0.0, *experiment.contact_and_mode())]    # the start: a reference, not a switch
        t, read, left = 0.0, 0, False
        while t < stop:
            instance.doStep(t, h)
            t += h
            if len(experiment.messages) > read:      # only new messages are parsed
                for switch in mode_switches(experiment.messages[read:]):
                    if switch[1:] != switches[-1][1:]:   # the initial event iteration logs "1 -> 1"
                        switches.append(switch)
                        left = left or not switch[1]
                read = len(experiment.messages)
            if left and (state := experiment.read(STATE_AT_RETURN))["y"] >= 0:
                break
        else:
            raise no_return(case, stop)
    s, back = flight_back_to_floor(state) if state["y"] > 0 else (0.0, state)
    # The return's time from the closed form may fall a rounding error before the logged lift-off
    # (delta = 0: they are one instant), so no switch is put after it.
    switches = [(min(ts, t + s), contact, mode) for ts, contact, mode in switches]
    return outcome_from_switches(case, switches, t + s, back, events=len(switches) - 1)
