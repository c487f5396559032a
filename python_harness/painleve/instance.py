"""Instantiating the FMU with a logger of its own.

fmpy's native logger proxy keeps one logger for the whole process, so with it
the last instance created would receive every instance's messages. The
PainleveRod FMU formats its messages itself (a literal '%' arrives as '%%'),
so each instance gets its Python logger directly."""
import contextlib
import shutil
import tempfile

from fmpy import calloc, extract, free, read_model_description, simulate_fmu
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


class SimulationError(RuntimeError):
    """The FMU or its solver gave up on a run; the message carries the FMU's own words."""


class LoadedFMU:
    """One extracted FMU and one instance, reset between runs (fmpy's fast loop),
    so a study of thousands of runs pays the unzip and the load once."""

    def __init__(self, fmu_path, *, interface="ME"):
        self.interface = interface
        self.model_description = read_model_description(fmu_path)
        self._tmp = tempfile.mkdtemp(prefix="painleve-")
        self.unzipdir = extract(fmu_path, self._tmp)
        self._errors = []
        self.fmu = instantiate(self.unzipdir, self.model_description, self._log, interface=interface)
        self.vr = {v.name: v.valueReference for v in self.model_description.modelVariables}
        self._used = False

    def _log(self, status, category, message):
        if status >= FMI2_ERROR:
            self._errors.append(message)

    def close(self):
        self.fmu.freeInstance()
        shutil.rmtree(self._tmp, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @contextlib.contextmanager
    def fresh_run(self, what):
        """The instance reset for a new run (after the first); a failure inside raises
        SimulationError naming `what` and quoting the FMU's first error message (the
        cause: after it the instance is in its Error state and refuses what follows)."""
        if self._used:
            self.fmu.reset()
        self._used = True
        self._errors.clear()
        try:
            yield self.fmu
        except Exception as err:
            said = self._errors[0] if self._errors else str(err)
            raise SimulationError(f"{what}: the FMU stopped: {said}") from err

    def simulate(self, what, **kwargs):
        """fmpy.simulate_fmu on the loaded instance, events recorded."""
        with self.fresh_run(what):
            return simulate_fmu(self.unzipdir, model_description=self.model_description, fmu_instance=self.fmu,
                                fmi_type="CoSimulation" if self.interface == "CS" else "ModelExchange",
                                record_events=True, validate=False, **kwargs)
