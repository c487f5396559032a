# SPDX-License-Identifier: BSD-2-Clause
"""Model Exchange's fast loop: an IWC case from event to event with fmpy's own
CVode solver and no simulate_fmu around it.

`integrate` is the FMI 2.0 Model Exchange master loop reduced to what an IWC
case needs: CVode runs from event to event (no output grid), each event gets
the full event iteration, and the caller decides at each event whether to stop.
`DirectCVode` is fmpy's CVodeSolver (BDF, dense difference-quotient Jacobian,
atol = rtol * nominal) with its two callbacks calling the FMU's C functions
directly (fmpy_internals): half the time of an fmpy fast-loop case, same solver.
"""
from ctypes import byref, c_long

from fmpy.sundials import CVodeSolver

from ..experiments.outcome import STATE_AT_RETURN, back_on_floor, no_return, outcome_from_switches
from .cs_calls import initialize
from .fmpy_internals import c_functions, cvode_get_num_steps, vector_data


class _NoInput:
    def apply(self, t):
        pass


class DirectCVode(CVodeSolver):
    """fmpy's CVodeSolver calling fmi2SetTime, fmi2SetContinuousStates,
    fmi2GetDerivatives and fmi2GetEventIndicators directly. A status other than
    fmi2OK fails the step (CVode then reports it, and the FMU has logged why)
    where fmpy's wrappers would raise inside a ctypes callback, which is ignored.
    Counts right-hand sides (Jacobian columns included) and steps. Starts at t = 0
    from the instance's states (it must be in continuous-time mode)."""

    def __init__(self, instance, model_description, *, relative_tolerance, max_step):
        self._component = instance.component
        self._set_time, self._set_states, self._get_derivatives, self._get_indicators = c_functions(instance)
        self.nfev, self._steps_before = 0, 0
        super().__init__(nx=model_description.numberOfContinuousStates, nz=model_description.numberOfEventIndicators,
                         get_x=instance.getContinuousStates, set_x=instance.setContinuousStates,
                         get_dx=instance.getDerivatives, get_z=instance.getEventIndicators,
                         get_nominals=instance.getNominalsOfContinuousStates, set_time=instance.setTime,
                         input=_NoInput(), startTime=0.0, maxStep=max_step, relativeTolerance=relative_tolerance,
                         maxNumSteps=100_000)

    def f(self, t, y, ydot, user_data):
        self.nfev += 1
        c = self._component
        failed = self._set_time(c, t) or self._set_states(c, vector_data(y), self.nx) or \
            self._get_derivatives(c, vector_data(ydot), self.nx)
        return -1 if failed else 0

    def g(self, t, y, gout, user_data):
        c = self._component
        failed = self._set_time(c, t) or self._set_states(c, vector_data(y), self.nx) or \
            self._get_indicators(c, gout, self.nz)
        return -1 if failed else 0

    @property
    def steps(self):
        """Steps taken since the start (CVode's own count restarts at each reset)."""
        n = c_long()
        cvode_get_num_steps(self.cvode_mem, byref(n))
        return self._steps_before + n.value

    def reset(self, time):
        self._steps_before = self.steps
        super().reset(time)


# A run's events and an event's iterations: an IWC has a handful of events and a rod that ends
# lying on the floor about a hundred; far beyond both, the run is chattering, not moving on.
MAX_EVENTS = 100_000
MAX_EVENT_ITERATIONS = 1_000


def event_iteration(instance):
    """fmi2NewDiscreteStates until the FMU needs no more; its last fmi2EventInfo
    as fmpy returns it: (needed, terminate, nominals changed, values changed,
    next event time defined, next event time). Raises RuntimeError if it never settles."""
    info = (True,)
    for _ in range(MAX_EVENT_ITERATIONS):
        info = instance.newDiscreteStates()
        if not info[0] or info[1]:
            return info
    raise RuntimeError(f"the event iteration did not settle in {MAX_EVENT_ITERATIONS} calls of fmi2NewDiscreteStates")


def integrate(instance, model_description, *, relative_tolerance, stop_time, at_event):
    """Runs an instance that has left initialization mode (fmi2ExitInitializationMode)
    from t = 0: the initial event iteration, then CVode from event to event until
    at_event(t) is true (after the event's iteration, in continuous-time mode),
    the FMU asks to terminate, or t reaches stop_time. Returns (t, the solver's
    counters dict(nfev, nsteps)); raises RuntimeError if CVode fails or the events
    exceed MAX_EVENTS."""
    me = model_description.modelExchange
    info = event_iteration(instance)
    instance.enterContinuousTimeMode()
    solver = DirectCVode(instance, model_description, relative_tolerance=relative_tolerance,
                         max_step=stop_time / 50)   # fmpy's max step
    t, events = 0.0, 0
    while not info[1] and t < stop_time:
        t_next = min(stop_time, info[5]) if info[4] else stop_time
        root, _, t = solver.step(t, t_next)
        instance.setTime(t)
        step_event = False
        if not me.completedIntegratorStepNotNeeded:
            step_event, terminate = instance.completedIntegratorStep()
            if terminate:
                break
        if not (root or step_event or (info[4] and t >= info[5])):
            continue
        events += 1
        if events > MAX_EVENTS:
            raise RuntimeError(f"{MAX_EVENTS} events before t = {t:.17g} without reaching t = {stop_time:g}: "
                               f"the run chatters at a switching surface")
        instance.enterEventMode()
        info = event_iteration(instance)
        instance.enterContinuousTimeMode()
        if at_event(t):
            break
        solver.reset(t)
    return t, dict(nfev=solver.nfev, nsteps=solver.steps)


def run_to_return(experiment, what, start_values, *, relative_tolerance, stop_time, read):
    """One run of any body through Model Exchange from `start_values`, the (contact, mode) switches
    read at each event, stopped at the first event after which it is back_on_floor. Returns the
    switches [(t, contact, mode)] (the start first), the time it stopped, the Real variables `read`
    (y among them) there, whether it returned, and the solver's counters."""
    switches, back, returned = [], {}, False

    def at_event(t):
        nonlocal returned
        contact, mode = experiment.contact_and_mode()
        if switches[-1][1:] != (contact, mode):
            switches.append((t, contact, mode))
        touched = any(c for _, c, _ in switches)
        if touched and not contact:
            back.update(experiment.read(read))
            returned = back_on_floor(touched, contact, back["y"])
        return returned

    with experiment.fresh_run(what) as instance:
        initialize(instance, experiment.vr, start_values, relative_tolerance)
        switches.append((0.0, *experiment.contact_and_mode()))     # the start: a reference, not a switch
        t, stats = integrate(instance, experiment.model_description, relative_tolerance=relative_tolerance,
                             stop_time=stop_time, at_event=at_event)
    return switches, t, back, returned, stats


def run_model_exchange(experiment, case):
    """One case of the rod through Model Exchange (run_to_return), reduced to its Outcome."""
    case.check()
    settings = experiment.settings(case)
    switches, t, back, returned, experiment.solver_stats = run_to_return(
        experiment, case, case.start_values(), relative_tolerance=settings["relative_tolerance"],
        stop_time=settings["stop_time"], read=STATE_AT_RETURN)
    if not returned:
        raise no_return(case, t)
    return outcome_from_switches(case, switches, t, back, events=len(switches) - 1,
                                 solver_stats=dict(experiment.solver_stats))
