# SPDX-License-Identifier: BSD-2-Clause
"""One Co-Simulation instance of a built FMU, FMI 2.0 or 3.0, for tests that must see every
step's status and the FMU's event log: fmpy's calls, the doStep status taken from the FMI
function itself (fmpy's doStep drops it), each log message kept with its status and category."""
import math
import re
import shutil
from ctypes import byref

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave, fmi2True
from fmpy.fmi3 import FMU3Slave, fmi3Boolean, fmi3Float64
from fmpy.simulation import instantiate_fmu

OK = 0

_EVENT = re.compile(r"t = (\S+): (.*)")


class Unpacked:
    """Built FMUs extracted once each (read_model_description and extract), removed by close()."""

    def __init__(self):
        self._fmus = {}

    def __call__(self, path):
        if path not in self._fmus:
            self._fmus[path] = (read_model_description(path), extract(path))
        return self._fmus[path]

    def close(self):
        for _, folder in self._fmus.values():
            shutil.rmtree(folder, ignore_errors=True)
        self._fmus.clear()


class StepFailed(AssertionError):
    pass


class Slave:
    """A Co-Simulation instance initialized at start_time with the start values given; FMI 3.0 with
    early return allowed if asked (the step then ends right after an event's update)."""

    def __init__(self, unpacked, path, tolerance=None, start_time=0.0, early_return=False, **start):
        md, folder = unpacked(path)
        self.md, self.fmi3 = md, md.fmiVersion.startswith("3")
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.states = [v.name[4:-1] for v in md.modelVariables if v.name.startswith("der(")]
        self.nominals = [_nominal(md, name) for name in self.states]
        self.log = []           # (status, category, message)
        if self.fmi3:
            self.fmu = FMU3Slave(guid=md.guid, unzipDirectory=folder, modelIdentifier=md.coSimulation.modelIdentifier,
                                 instanceName="switch")
            self.fmu.instantiate(loggingOn=True, earlyReturnAllowed=early_return, logMessage=self._log3)
            self.fmu.setFloat64([self.vr[k] for k in start], list(start.values()))
            self.fmu.enterInitializationMode(tolerance=tolerance, startTime=start_time)
        else:
            self.fmu = instantiate_fmu(folder, md, "CoSimulation", debug_logging=True, logger=self._log2)
            self.fmu.setupExperiment(tolerance=tolerance, startTime=start_time)
            self.fmu.setReal([self.vr[k] for k in start], list(start.values()))
            self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.t = start_time

    def _log2(self, env, name, status, category, message):
        self.log.append((status, category.decode(), message.decode()))

    def _log3(self, env, status, category, message):
        self.log.append((status, category.decode(), message.decode()))

    def do_step(self, t, h):
        """doStep(t, h) as given; fails, with the FMU's last message, unless it returns OK. Returns
        FMI 3.0's (earlyReturn, lastSuccessfulTime), FMI 2.0's (False, t + h)."""
        try:
            if self.fmi3:
                flags = [fmi3Boolean(), fmi3Boolean(), fmi3Boolean()]
                last = fmi3Float64()
                status = self.fmu.fmi3DoStep(self.fmu.component, t, h, fmi3Boolean(True), *map(byref, flags),
                                             byref(last))
                result = flags[2].value, last.value
            else:
                status = self.fmu.fmi2DoStep(self.fmu.component, t, h, fmi2True)
                result = False, t + h
        except Exception as error:
            status, result = error, None
        if status != OK:
            said = [m for s, c, m in self.log if s != OK]
            raise StepFailed(f"doStep({t!r}, {h!r}) returned {status}: {said[-1] if said else 'nothing logged'}")
        return result

    def step_to(self, t_end):
        """One doStep from the instance's time to t_end, which it must reach with OK (an early
        return at an event goes on from the time it reached)."""
        for _ in range(100000):
            early, reached = self.do_step(self.t, t_end - self.t)
            self.t = reached if early else t_end
            if not early:
                return
        raise AssertionError("more than 100000 early returns in one step")

    def get(self, *names):
        return (self.fmu.getFloat64 if self.fmi3 else self.fmu.getReal)([self.vr[k] for k in names])

    def state(self):
        return self.get(*self.states)

    def get_fmu_state(self):
        return self.fmu.getFMUState() if self.fmi3 else self.fmu.getFMUstate()

    def set_fmu_state(self, state, t):
        (self.fmu.setFMUState if self.fmi3 else self.fmu.setFMUstate)(state)
        self.t = t

    def free_fmu_state(self, state):
        (self.fmu.freeFMUState if self.fmi3 else self.fmu.freeFMUstate)(state)

    def events(self):
        """The event log's lines after the start as (t, text)."""
        out = []
        for status, category, message in self.log:
            m = _EVENT.match(message)
            if category == "logEvents" and m:
                out.append((float(m.group(1)), m.group(2)))
        return out

    def hand_overs(self):
        """The times at which the explicit pair handed the trajectory to CVODE (the event log's)."""
        return [t for t, text in self.events() if text.endswith("CVODE integrates on")]

    def free(self):
        self.fmu.freeInstance()


def _nominal(md, name):
    v = next(v for v in md.modelVariables if v.name == name)
    return float(v.nominal) if v.nominal is not None else 1.0


def ulps_from(t, k):
    """t moved by k units in the last place (k < 0: down)."""
    for _ in range(abs(k)):
        t = math.nextafter(t, math.inf if k > 0 else -math.inf)
    return t
