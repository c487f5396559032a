"""Model Exchange to the next event, with fmpy's own CVode and no simulate_fmu around it.

fmpy's CVodeSolver (BDF, dense difference-quotient Jacobian, atol = rtol *
nominal) calls the model through fmpy's Python wrappers: three FMI calls per
right-hand side and per root evaluation, each with a status check and a call
logger in Python, cost more than the model. `DirectCVode` is that solver with
the two callbacks calling the FMU's C functions directly; and `integrate` is
the FMI 2.0 Model Exchange master loop reduced to what an IWC case needs:
CVode runs from event to event (no output grid), each event gets the full
event iteration, and the caller decides at each event whether to stop.
Halves the time of an fmpy fast loop case; the solver is the same. It uses
two internals of fmpy, pinned in requirements.txt: FMU2Model._functions (the
FMU's C functions, typed) and the serial N_Vector's content struct.
"""
from ctypes import POINTER, byref, c_int, c_long, c_void_p

from fmpy.sundials import CVodeSolver
from fmpy.sundials.libraries import sundials_cvode
from fmpy.sundials.nvector_serial import _N_VectorContent_Serial

_get_num_steps = sundials_cvode.CVodeGetNumSteps     # fmpy binds it without types
_get_num_steps.argtypes, _get_num_steps.restype = [c_void_p, POINTER(c_long)], c_int


def _data(vector):
    """NV_DATA_S without fmpy's two casts (the callbacks' hottest line)."""
    return _N_VectorContent_Serial.from_address(vector.contents.content).data


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

    def __init__(self, fmu, model_description, *, tolerance, max_step):
        functions = fmu._functions
        self._component = fmu.component
        self._set_time = functions["fmi2SetTime"]
        self._set_states = functions["fmi2SetContinuousStates"]
        self._get_derivatives = functions["fmi2GetDerivatives"]
        self._get_indicators = functions["fmi2GetEventIndicators"]
        self.nfev, self._steps_before = 0, 0
        super().__init__(nx=model_description.numberOfContinuousStates, nz=model_description.numberOfEventIndicators,
                         get_x=fmu.getContinuousStates, set_x=fmu.setContinuousStates, get_dx=fmu.getDerivatives,
                         get_z=fmu.getEventIndicators, get_nominals=fmu.getNominalsOfContinuousStates,
                         set_time=fmu.setTime, input=_NoInput(), startTime=0.0, maxStep=max_step,
                         relativeTolerance=tolerance, maxNumSteps=100_000)

    def f(self, t, y, ydot, user_data):
        self.nfev += 1
        c = self._component
        failed = self._set_time(c, t) or self._set_states(c, _data(y), self.nx) or \
            self._get_derivatives(c, _data(ydot), self.nx)
        return -1 if failed else 0

    def g(self, t, y, gout, user_data):
        c = self._component
        failed = self._set_time(c, t) or self._set_states(c, _data(y), self.nx) or \
            self._get_indicators(c, gout, self.nz)
        return -1 if failed else 0

    @property
    def steps(self):
        """Steps taken since the start (CVode's own count restarts at each reset)."""
        n = c_long()
        _get_num_steps(self.cvode_mem, byref(n))
        return self._steps_before + n.value

    def reset(self, time):
        self._steps_before = self.steps
        super().reset(time)


def event_iteration(fmu):
    """fmi2NewDiscreteStates until the FMU needs no more; its last fmi2EventInfo
    as fmpy returns it: (needed, terminate, nominals changed, values changed,
    next event time defined, next event time)."""
    info = (True,)
    while info[0]:
        info = fmu.newDiscreteStates()
        if info[1]:
            break
    return info


def integrate(fmu, model_description, *, tolerance, stop_time, at_event):
    """Runs an instance that has left initialization mode (fmi2ExitInitializationMode)
    from t = 0: the initial event iteration, then CVode from event to event until
    at_event(t) is true (after the event's iteration, in continuous-time mode),
    the FMU asks to terminate, or t reaches stop_time. Returns (t, the solver's
    counters dict(nfev, nsteps)); raises RuntimeError if CVode fails."""
    me = model_description.modelExchange
    info = event_iteration(fmu)
    fmu.enterContinuousTimeMode()
    solver = DirectCVode(fmu, model_description, tolerance=tolerance, max_step=stop_time / 50)   # fmpy's max step
    t = 0.0
    while not info[1] and t < stop_time:
        t_next = min(stop_time, info[5]) if info[4] else stop_time
        root, _, t = solver.step(t, t_next)
        fmu.setTime(t)
        step_event = False
        if not me.completedIntegratorStepNotNeeded:
            step_event, terminate = fmu.completedIntegratorStep()
            if terminate:
                break
        if not (root or step_event or (info[4] and t >= info[5])):
            continue
        fmu.enterEventMode()
        info = event_iteration(fmu)
        fmu.enterContinuousTimeMode()
        if at_event(t):
            break
        solver.reset(t)
    return t, dict(nfev=solver.nfev, nsteps=solver.steps)
