"""Free runs of the PainleveRod FMU from any state, for what the IWC cases of
`experiment` do not cover: the quadrants of figure fig:GB (states outside the
theorems' hypotheses) and the two rods of figure video (a flight, then a graze).

One `Rig` extracts the FMU and instantiates it once for Model Exchange, then
resets it between runs (fmpy's fast loop), as `experiment.Experiment` does."""
import shutil
import tempfile

import numpy as np
from fmpy import extract, read_model_description, simulate_fmu

from .experiment import SimulationError
from .instance import FMI2_ERROR, instantiate

STATES = ["x", "v", "y", "w", "theta", "phi"]
OUTPUTS = STATES + ["mode", "contact"]


class Rig:
    """Runs the FMU through Model Exchange from arbitrary start values, events recorded."""

    def __init__(self, fmu_path):
        self.model_description = read_model_description(fmu_path)
        self._tmp = tempfile.mkdtemp(prefix="painleve-rig-")
        self.unzipdir = extract(fmu_path, self._tmp)
        self._errors = []
        self.fmu = instantiate(self.unzipdir, self.model_description, self._log, interface="ME")
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

    def run(self, start_values, *, stop_time, output_interval, relative_tolerance=1e-8, outputs=OUTPUTS):
        """fmpy's structured array of one run; the FMU's own words in a SimulationError if it stops."""
        if self._used:
            self.fmu.reset()
        self._used = True
        self._errors.clear()
        try:
            r = simulate_fmu(self.unzipdir, model_description=self.model_description, fmu_instance=self.fmu,
                             fmi_type="ModelExchange", start_values=dict(start_values), output=list(outputs),
                             stop_time=stop_time, output_interval=output_interval,
                             relative_tolerance=relative_tolerance, record_events=True, validate=False)
        except Exception as err:
            said = self._errors[-1] if self._errors else str(err)
            raise SimulationError(f"run from {dict(start_values)}: the FMU stopped: {said}") from err
        for name in outputs:
            if r[name].dtype.kind == "f" and not np.all(np.isfinite(r[name])):
                raise SimulationError(f"run from {dict(start_values)}: the FMU returned a non-finite {name}")
        return r
