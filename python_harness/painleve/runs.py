"""Free runs of the PainleveRod FMU from any state, for what the IWC cases of
`experiment` do not cover: the quadrants of figure fig:GB (states outside the
theorems' hypotheses) and the two rods of figure video (a flight, then a graze).

One `Rig` extracts the FMU and instantiates it once for Model Exchange, then
resets it between runs (fmpy's fast loop), as `experiment.Experiment` does."""
import numpy as np

from .instance import LoadedFMU, SimulationError

STATES = ["x", "v", "y", "w", "theta", "phi"]
OUTPUTS = STATES + ["mode", "contact"]


class Rig(LoadedFMU):
    """Runs the FMU through Model Exchange from arbitrary start values, events recorded."""

    def __init__(self, fmu_path):
        super().__init__(fmu_path, interface="ME")

    def run(self, start_values, *, stop_time, output_interval, relative_tolerance=1e-8, outputs=OUTPUTS):
        """fmpy's structured array of one run; the FMU's own words in a SimulationError if it stops."""
        r = self.simulate(f"run from {dict(start_values)}", start_values=dict(start_values), output=list(outputs),
                          stop_time=stop_time, output_interval=output_interval,
                          relative_tolerance=relative_tolerance)
        for name in outputs:
            if r[name].dtype.kind == "f" and not np.all(np.isfinite(r[name])):
                raise SimulationError(f"run from {dict(start_values)}: the FMU returned a non-finite {name}")
        return r
