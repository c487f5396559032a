# SPDX-License-Identifier: BSD-2-Clause
"""Raw FMI 2.0 instances for tests that need each call in hand (interleaved
instances, captured log messages, calls in the wrong state): the instance
comes from the harness's Experiment.instantiate, the calls are fmpy's."""
from ctypes import POINTER, c_double

import numpy as np

_P = POINTER(c_double)


class Rod:
    """One Model Exchange instance of the FMU, with its log messages collected in .messages,
    and a forward Euler driver."""

    def __init__(self, loaded, name="rod", guid=None, logging_on=False):
        md = loaded.model_description
        self.vr = loaded.vr
        self.nx, self.nz = len(md.derivatives), md.numberOfEventIndicators
        self.messages = []
        self.fmu = loaded.instantiate(instance_name=name, guid=guid, logging_on=logging_on,
                                      on_message=lambda *m: self.messages.append(m))

    def set(self, **values):
        self.fmu.setReal([self.vr[k] for k in values], list(values.values()))

    def get(self, *names):
        return self.fmu.getReal([self.vr[k] for k in names])

    def initialize(self, start_time=0.0, **values):
        self.fmu.setupExperiment(startTime=start_time)
        self.set(**values)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.t = start_time
        self._event()

    def _event(self):
        while self.fmu.newDiscreteStates()[0]:
            pass
        self.fmu.enterContinuousTimeMode()
        self.x = np.zeros(self.nx)
        self.z = np.zeros(self.nz)
        self.fmu.getContinuousStates(self.x.ctypes.data_as(_P), self.nx)
        self.fmu.getEventIndicators(self.z.ctypes.data_as(_P), self.nz)

    def euler_step(self, h):
        """One explicit Euler step, then the event iteration if an indicator changed sign."""
        dx = np.zeros(self.nx)
        self.fmu.getDerivatives(dx.ctypes.data_as(_P), self.nx)
        self.t += h
        self.x = self.x + h * dx
        self.fmu.setTime(self.t)
        self.fmu.setContinuousStates(self.x.ctypes.data_as(_P), self.nx)
        z = np.zeros(self.nz)
        self.fmu.getEventIndicators(z.ctypes.data_as(_P), self.nz)
        crossed = np.any(np.sign(z) != np.sign(self.z))
        self.z = z
        if crossed:
            self.fmu.enterEventMode()
            self._event()

    def free(self):
        self.fmu.freeInstance()


class Slave:
    """One Co-Simulation instance, initialized with the start values given, with its log messages."""

    def __init__(self, loaded, tolerance=None, **start):
        from painleve.fmu.experiment import STATES
        self.vr, self._states = loaded.vr, list(STATES)
        self.messages = []
        self.fmu = loaded.instantiate(fmi_type="CoSimulation", on_message=lambda *m: self.messages.append(m))
        self.fmu.setupExperiment(tolerance=tolerance, startTime=0.0)
        self.fmu.setReal([self.vr[k] for k in start], list(start.values()))
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.t = 0.0

    def step(self, h):
        self.fmu.doStep(self.t, h)
        self.t += h

    def states(self):
        return np.array(self.fmu.getReal([self.vr[k] for k in self._states]))
