# SPDX-License-Identifier: BSD-2-Clause
"""An FMI 3.0 instance of PainleveRod (fmpy's FMU3Model or FMU3Slave) under the
FMI 2.0 calls the harness makes, so that Experiment, the Co-Simulation fast loop
and the raw-instance helpers drive either FMU alike. fmpy's simulate_fmu takes
the wrapped instance itself (`.fmu`): it knows FMI 3.0."""
from fmpy.fmi3 import FMU3Model, FMU3Slave


class Fmi3AsFmi2:
    """The FMI 2.0 names the harness uses, over an instantiated FMI 3.0 instance; every
    other attribute is the FMI 3.0 instance's."""

    def __init__(self, fmu):
        self.fmu = fmu
        self._tolerance, self._start = None, 0.0

    def __getattr__(self, name):
        return getattr(self.fmu, name)

    def setupExperiment(self, tolerance=None, startTime=0.0):
        # FMI 3.0 takes the experiment with fmi3EnterInitializationMode.
        self._tolerance, self._start = tolerance, startTime

    def enterInitializationMode(self):
        self.fmu.enterInitializationMode(tolerance=self._tolerance, startTime=self._start)

    def setReal(self, vr, values):
        self.fmu.setFloat64(vr, values)

    def getReal(self, vr):
        return self.fmu.getFloat64(vr)

    def getInteger(self, vr):
        return self.fmu.getInt32(vr)

    def doStep(self, currentCommunicationPoint, communicationStepSize, noSetFMUStatePriorToCurrentPoint=True):
        self.fmu.doStep(currentCommunicationPoint, communicationStepSize, noSetFMUStatePriorToCurrentPoint)


def instantiate(unzipdir, model_description, fmi_type, *, guid, instance_name, logging_on, on_message):
    """An instantiated FMI 3.0 instance, wrapped; on_message(status, category, message) per log message."""
    kind = model_description.modelExchange if fmi_type == "ModelExchange" else model_description.coSimulation
    cls = FMU3Model if fmi_type == "ModelExchange" else FMU3Slave

    def log_message(env, status, category, message):
        if on_message:
            on_message(status, category.decode(), message.decode(errors="replace").replace("%%", "%"))

    fmu = cls(guid=guid or model_description.guid, unzipDirectory=unzipdir, modelIdentifier=kind.modelIdentifier,
              instanceName=instance_name)
    fmu.instantiate(loggingOn=logging_on, logMessage=log_message)
    return Fmi3AsFmi2(fmu)
