"""Instantiating the FMU with a logger of its own.

fmpy's native logger proxy keeps one logger for the whole process, so with it
the last instance created would receive every instance's messages. The
PainleveRod FMU formats its messages itself (a literal '%' arrives as '%%'),
so each instance gets its Python logger directly."""
from fmpy import calloc, free
from fmpy.fmi2 import (FMU2Model, FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

FMI2_ERROR = 3


def instantiate(unzipdir, model_description, on_message, *, interface="ME", name="PainleveRod", guid=None,
                logging_on=False):
    """An instantiated FMU2Model (interface "ME") or FMU2Slave ("CS") that calls
    on_message(status, category, message) for each log message."""
    def logger(env, instance_name, status, category, message):
        on_message(status, category.decode(), message.decode(errors="replace").replace("%%", "%"))

    callbacks = fmi2CallbackFunctions()
    callbacks.logger = fmi2CallbackLoggerTYPE(logger)
    callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    if interface not in ("ME", "CS"):
        raise ValueError(f"interface must be 'ME' (Model Exchange) or 'CS' (Co-Simulation), not {interface!r}")
    kind = model_description.modelExchange if interface == "ME" else model_description.coSimulation
    if kind is None:
        raise ValueError(f"this FMU does not declare {'Model Exchange' if interface == 'ME' else 'Co-Simulation'}")
    cls = FMU2Model if interface == "ME" else FMU2Slave
    fmu = cls(guid=guid or model_description.guid, unzipDirectory=unzipdir,
              modelIdentifier=kind.modelIdentifier, instanceName=name)
    fmu.instantiate(callbacks=callbacks, loggingOn=logging_on)
    return fmu
