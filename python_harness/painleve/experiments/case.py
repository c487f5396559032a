# SPDX-License-Identifier: BSD-2-Clause
"""An IWC experiment as an input record: start values plus the configuration they came from.

Every case is an `IWCCase`: the start values it fixes (`given`), the contact point's slip speed v0
(None: that of the FMU's own start) and normal speed w0, the compliance epsilon and damping delta,
and, for the start values it does not fix, what to solve for and where to start (`solve`, `guess`):
the FMU's states not given, and the parameters named in `solve`, are solved so that the contact
point is on the floor (fmu.body). Two kinds:

- `BodyCase`, any body FMU's: the start values the user gives by name;
- `Case`, the rod's: its parameters and its state on the floor at t = 0, every state given in
  closed form (`start_values()`), so nothing is solved. What the paper predicts for it is
  `analytic.predict(case)`, the closed forms the general theory (theory.general) reproduces."""
import math
from dataclasses import dataclass, fields

from ..theory.analytic import check_case, predict

# The parameters' ranges, the FMU's own (fmu_src/models/PainleveRod/config.h, the min/max of modelDescription.xml;
# tests/cli/test_cli_failures.py checks they agree): the CLI and sweeps refuse a value outside them before
# the FMU would. {name: (min, max)}, both ends included.
RANGES = {"alpha": (1e-6, 1e6), "mu": (0.0, 1e6), "delta": (0.0, 1e6), "epsilon": (1e-8, 1.0),
          "kappa": (0.0, 1e6), "beta": (0.0, 1e6)}


class IWCCase:
    """What every kind of case gives a runner (see the module's docstring): `given`, ((name, value), ...);
    `v0`, `w0`, `epsilon`, `delta`; `solve` and `guess`; `configuration()`, what it came from."""
    solve = ()
    guess = ()

    def configuration(self):
        """{name: value} of what the case was made from (its fields)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class BodyCase(IWCCase):
    """A start on the floor of any body FMU: the start values the user gives (parameters, some states),
    the contact point's slip speed v0 (None: that of the FMU's own start) and normal speed w0 (the FMU's
    units), the compliance eps, delta; `solve`: parameters solved for beside the states not given (the
    arm's pivot height H, to put the tip on the floor at given angles); `guess`: ((name, value), ...)
    where to start solving."""
    given: tuple          # ((name, value), ...)
    v0: float = None
    epsilon: float = 1e-3
    delta: float = 1.0
    w0: float = 0.0
    guess: tuple = ()
    solve: tuple = ()


@dataclass(frozen=True)
class Case(IWCCase):
    """The rod (alpha = m l^2/I, friction mu, damping delta, compliance epsilon) starting on
    the floor, y = 0, with slip velocity v0, angle theta0, angular velocity phi0 and vertical
    velocity w = epsilon * w10 (the inner scale of Theorem 2)."""
    theta0: float = 1.0
    phi0: float = 0.5
    v0: float = 1.0
    delta: float = 1.0
    epsilon: float = 1e-3
    w10: float = 0.0
    alpha: float = 3.0
    mu: float = 3.0
    kappa: float = 0.0    # the compliance law's stiffening (0: the paper's linear law, docs/nonlinear_compliance.md)
    beta: float = 0.0     # its damping growth with penetration

    def __hash__(self):
        """The dataclass's hash (of the fields' tuple), computed once: a sweep looks each case up in
        the predictions' caches several times, and hashing ten floats is a few us."""
        try:
            return self.__dict__["_hash"]
        except KeyError:
            value = hash((self.theta0, self.phi0, self.v0, self.delta, self.epsilon, self.w10, self.alpha, self.mu,
                          self.kappa, self.beta))
            object.__setattr__(self, "_hash", value)
            return value

    @property
    def given(self):
        """Every state and parameter in closed form (start_values): nothing is solved for."""
        return tuple(self.start_values().items())

    @property
    def w0(self):
        return self.epsilon * self.w10

    def check(self):
        """Raises analytic.HypothesisError, naming the hypothesis, if the paper's theorems do not cover this case."""
        check_case(self)

    def start_values(self):
        """The FMU's start values for this case (fmpy's start_values)."""
        law = {k: v for k, v in (("kappa", self.kappa), ("beta", self.beta)) if v}   # the FMU's default: linear
        return dict(alpha=self.alpha, mu=self.mu, delta=self.delta, epsilon=self.epsilon, **law,
                    x=0.0, v=self.v0, y=0.0, w=self.epsilon * self.w10, theta=self.theta0, phi=self.phi0)


def horizon(case, prediction=None):
    """Where a run of the case that has not returned to the floor is given up: in fast time
    tau = t/eps the IWC takes ln(1/eps)/lambda_+ to compress and O(1 + delta) to stick and
    lift off, so eps (10 ln(1/eps)/lambda_+ + 50 (1 + delta)). `prediction`: predict(case), if known."""
    lambda_plus = (prediction or predict(case)).lambda_plus
    return case.epsilon * (10 * math.log(1 / case.epsilon) / lambda_plus + 50 * (1 + case.delta))
