"""A minimal FMI 2.0 Model Exchange driver over fmpy's low-level FMU2Model,
for tests that need each call in hand: interleaved instances, captured log
messages, calls in the wrong state."""
from ctypes import POINTER, c_double

import numpy as np
from fmpy import read_model_description

from painleve.instance import instantiate

_P = POINTER(c_double)


class Rod:
    """One instance of the FMU, with its log messages collected in .messages."""

    def __init__(self, unzipdir, name="rod", guid=None, logging_on=False):
        md = read_model_description(unzipdir)
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.nx, self.nz = len(md.derivatives), md.numberOfEventIndicators
        self.messages = []
        self.fmu = instantiate(unzipdir, md, lambda *m: self.messages.append(m), name=name, guid=guid,
                               logging_on=logging_on)

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

