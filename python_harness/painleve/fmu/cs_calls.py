# SPDX-License-Identifier: BSD-2-Clause
"""The FMI calls of one Co-Simulation case, in the four steps cs_fast_loop takes: reset,
start (set-up, start values, initialization, the contact and mode there), a doStep and the
values read after it, and the FMU's counts at the end.

`WrapperCalls` makes them through fmpy's wrappers of the instance (any instance the harness
makes: FMI 2.0, or FMI 3.0 under fmi3_adapter). `DirectCalls` makes the same FMI 2.0 calls
with the same arguments straight into the FMU's C functions, as fmpy typed them
(fmpy_internals), with the value references' arrays made once per instance: fmpy's wrappers
build two ctypes arrays and check a status in Python for each call, 11 a case, which cost a
sweep's case about as much as the FMU's own integration. The values are the
same floats either way (tests/fmu/test_cs_calls.py); a status above fmi2Warning raises
fmpy's own FMICallException, so a failure reads the same."""
from ctypes import c_double, c_int, c_uint

from fmpy.fmi1 import FMICallException

from .fmpy_internals import fmi2_functions

FMI2_WARNING = 1
FMI2_TRUE = 1


def initialize(instance, vr, start_values, relative_tolerance):
    """fmpy's `instance` set up at t = 0 with the tolerance, `start_values` ({name: value}) set, and
    initialized (fmi2ExitInitializationMode done)."""
    instance.setupExperiment(tolerance=relative_tolerance, startTime=0.0)
    instance.setReal([vr[k] for k in start_values], list(start_values.values()))
    instance.enterInitializationMode()
    instance.exitInitializationMode()


def contact_and_mode(instance, vr):
    """(contact, mode) of fmpy's `instance` now."""
    return bool(instance.getBoolean([vr["contact"]])[0]), int(instance.getInteger([vr["mode"]])[0])


class WrapperCalls:
    """The case's FMI calls through fmpy's wrappers of `instance`; `read`: the Real variables read
    after each doStep."""

    def __init__(self, instance, vr, read):
        self.instance, self.vr = instance, vr
        self.read_vr = [vr[k] for k in read]

    def reset(self):
        self.instance.reset()

    def start(self, start_values, relative_tolerance):
        """Sets up and initializes the instance with `start_values` ({name: value}); (contact, mode) there."""
        initialize(self.instance, self.vr, start_values, relative_tolerance)
        return contact_and_mode(self.instance, self.vr)

    def step(self, t, h):
        """fmi2DoStep(t, h); the values of `read` after it, as a list."""
        self.instance.doStep(t, h)
        return self.instance.getReal(self.read_vr)

    def end(self):
        """(switches, sticks, contact) now."""
        switches, sticks = self.instance.getInteger([self.vr["switches"], self.vr["sticks"]])
        return switches, sticks, bool(self.instance.getBoolean([self.vr["contact"]])[0])


NAMES = ("fmi2Reset", "fmi2SetupExperiment", "fmi2SetReal", "fmi2EnterInitializationMode",
         "fmi2ExitInitializationMode", "fmi2GetBoolean", "fmi2GetInteger", "fmi2DoStep", "fmi2GetReal")


class DirectCalls:
    """The same calls on an instantiated fmpy FMU2Slave, straight into its C functions."""

    def __init__(self, instance, vr, read):
        self.component = instance.component
        (self._reset, self._setup, self._set_real, self._enter, self._exit, self._get_boolean, self._get_integer,
         self._do_step, self._get_real) = fmi2_functions(instance, NAMES)
        self.vr = vr
        self._start_vr = {}                     # the start values' names -> their value references' array
        self._read_vr, self._read = (c_uint * len(read))(*(vr[k] for k in read)), (c_double * len(read))()
        self._contact_vr, self._mode_vr = (c_uint * 1)(vr["contact"]), (c_uint * 1)(vr["mode"])
        self._counts_vr = (c_uint * 2)(vr["switches"], vr["sticks"])
        self._boolean, self._integers = (c_int * 1)(), (c_int * 2)()

    # Each call's status is checked where it returns, as fmpy's _call does: a status above fmi2Warning
    # raises before the next call (written out, not a helper: 11 calls a case).
    def reset(self):
        if (status := self._reset(self.component)) > FMI2_WARNING:
            raise FMICallException(function="fmi2Reset", status=status)

    def start(self, start_values, relative_tolerance):
        c = self.component
        names = tuple(start_values)
        vr = self._start_vr.get(names)
        if vr is None:
            vr = self._start_vr[names] = (c_uint * len(names))(*(self.vr[k] for k in names))
        if (status := self._setup(c, FMI2_TRUE, relative_tolerance, 0.0, 0, 0.0)) > FMI2_WARNING:
            raise FMICallException(function="fmi2SetupExperiment", status=status)
        values = (c_double * len(names))(*start_values.values())
        if (status := self._set_real(c, vr, len(names), values)) > FMI2_WARNING:
            raise FMICallException(function="fmi2SetReal", status=status)
        if (status := self._enter(c)) > FMI2_WARNING:
            raise FMICallException(function="fmi2EnterInitializationMode", status=status)
        if (status := self._exit(c)) > FMI2_WARNING:
            raise FMICallException(function="fmi2ExitInitializationMode", status=status)
        if (status := self._get_boolean(c, self._contact_vr, 1, self._boolean)) > FMI2_WARNING:
            raise FMICallException(function="fmi2GetBoolean", status=status)
        if (status := self._get_integer(c, self._mode_vr, 1, self._integers)) > FMI2_WARNING:
            raise FMICallException(function="fmi2GetInteger", status=status)
        return bool(self._boolean[0]), int(self._integers[0])

    def step(self, t, h):
        c = self.component
        if (status := self._do_step(c, t, h, FMI2_TRUE)) > FMI2_WARNING:
            raise FMICallException(function="fmi2DoStep", status=status)
        if (status := self._get_real(c, self._read_vr, len(self._read_vr), self._read)) > FMI2_WARNING:
            raise FMICallException(function="fmi2GetReal", status=status)
        return self._read[:]

    def end(self):
        c = self.component
        if (status := self._get_integer(c, self._counts_vr, 2, self._integers)) > FMI2_WARNING:
            raise FMICallException(function="fmi2GetInteger", status=status)
        if (status := self._get_boolean(c, self._contact_vr, 1, self._boolean)) > FMI2_WARNING:
            raise FMICallException(function="fmi2GetBoolean", status=status)
        return self._integers[0], self._integers[1], bool(self._boolean[0])
