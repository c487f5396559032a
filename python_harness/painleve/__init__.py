# SPDX-License-Identifier: BSD-2-Clause
"""The compliant Painleve rod: analytic results of Hogan & Kristiansen and IWC experiments on the FMU.

    from painleve import Case, Experiment, analytic
    with Experiment("build/PainleveRod.fmu") as ex:
        outcome = ex.run(Case(theta0=1.0, phi0=0.5, epsilon=1e-5))
    analytic.predict(Case(theta0=1.0, phi0=0.5, epsilon=1e-5)).e

Any body FMU (the rod, TwoLinkArm.fmu, ...), through its own variables and either interface:

    from painleve import Body, BodyCase, run_body
    with Body("build/TwoLinkArm.fmu", fmi_type="CoSimulation") as body:
        predicted, outcome = run_body(body, BodyCase(given=(), epsilon=1e-4))   # its own start, on the floor
    outcome.w / predicted.start_v0, predicted.e     # an Outcome as ex.run's; e from the FMU's coefficients

The names below are the package's public face; each is imported on first use, so that
`import painleve` (and the theory alone) loads no fmpy. The layers behind them:
theory < experiments < fmu < coupling, validation, sweep < figures < cli (docs/architecture.md).
"""
import importlib

_PUBLIC = {
    "analytic": "theory.analytic", "rigid_limit": "theory.rigid_limit", "HypothesisError": "theory.hypotheses",
    "Case": "experiments.case", "Outcome": "experiments.outcome", "SimulationError": "experiments.outcome",
    "run_reference": "experiments.reference",
    "Experiment": "fmu.experiment", "FmuLoadError": "fmu.experiment", "run_iwc": "fmu.experiment",
    "Body": "fmu.body", "BodyError": "fmu.body", "BodyCase": "fmu.body_case",
    "run_body": "fmu.body_case", "general": "theory.general",
    "si": "coupling.si", "SIExperiment": "coupling.si_experiment",
    "validate": "validation.suite", "SweepSpec": "sweep.spec", "run_sweep": "sweep.run",
    "make_figures": "figures.paper",
}
__all__ = sorted(_PUBLIC)


def __getattr__(name):
    if name not in _PUBLIC:
        raise AttributeError(f"module 'painleve' has no attribute {name!r}")
    module = importlib.import_module(f".{_PUBLIC[name]}", __name__)
    value = module if _PUBLIC[name].endswith("." + name) else getattr(module, name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_PUBLIC))
