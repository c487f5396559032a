# SPDX-License-Identifier: BSD-2-Clause
"""Studies over many IWC cases: convergence to the paper's limits as eps -> 0,
and Theorem 2's separatrix located on the FMU by bisection."""
from dataclasses import dataclass, replace

import numpy as np

from ..theory.analytic import predict
from .acceptance import power_rate


@dataclass(frozen=True)
class Convergence:
    """One case at decreasing eps: the outcomes and the rates their errors fall at."""
    outcomes: tuple

    @property
    def epsilons(self):
        return np.array([o.case.epsilon for o in self.outcomes])

    def errors(self, name):
        """'w' (w/v0 - e), 'phi', 'theta' or 'v' (v -> 0) at each eps."""
        if name == "v":
            return np.array([o.v for o in self.outcomes])
        return np.array([getattr(o, f"{name}_error") for o in self.outcomes])

    def rate(self, name):
        return power_rate(self.epsilons, self.errors(name))

    @property
    def duration_slope(self):
        """d(t_return/eps)/d ln(1/eps): Theorem 1 says 1/lambda_+ (eq TT)."""
        t = np.array([o.t_return for o in self.outcomes])
        return float(np.polyfit(np.log(1 / self.epsilons), t / self.epsilons, 1)[0])

    @property
    def predicted_duration_slope(self):
        return 1 / predict(self.outcomes[0].case).lambda_plus

    def table(self):
        rows = [f"{'eps':>8} {'w/v0 - e':>11} {'phi err':>11} {'v':>11} {'t_return':>10} {'events':>6}"]
        for o in self.outcomes:
            rows.append(f"{o.case.epsilon:8.0e} {o.w_error:11.3e} {o.phi_error:11.3e} {o.v:11.3e} "
                        f"{o.t_return:10.3e} {o.events:6d}")
        rows.append(f"rates (slope of log|error| vs log eps): w {self.rate('w'):.2f}, "
                    f"phi {self.rate('phi'):.2f}, v {self.rate('v'):.2f}; duration slope "
                    f"{self.duration_slope:.3f} vs 1/lambda_+ = {self.predicted_duration_slope:.3f}")
        return "\n".join(rows)


def convergence(experiment, case, epsilons):
    """Runs `case` at each eps on one Experiment."""
    return Convergence(tuple(experiment.run(replace(case, epsilon=eps)) for eps in epsilons))


def separatrix(experiment, case, *, lower, upper, tolerance=1e-6):
    """The w10 at which the FMU's outcome switches from IWC (below) to lift-off (above),
    bisected between w10 = lower (must give IWC) and upper (must give lift-off); `experiment`:
    what runs a case (fmu.body.Body, or the rod's fmu.experiment.Experiment)."""
    def iwc(w10):
        return experiment.run(replace(case, w10=w10)).iwc
    if not iwc(lower) or iwc(upper):
        raise ValueError(f"w10 in [{lower}, {upper}] does not bracket the IWC / lift-off boundary")
    while upper - lower > tolerance * max(1.0, abs(lower)):
        middle = 0.5 * (lower + upper)
        lower, upper = (middle, upper) if iwc(middle) else (lower, middle)
    return 0.5 * (lower + upper)

