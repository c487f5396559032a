# SPDX-License-Identifier: BSD-2-Clause
"""The compliant Painleve rod: analytic results of Hogan & Kristiansen and IWC experiments on the FMU.

    from painleve import Case, Experiment, analytic
    with Experiment("build/PainleveRod.fmu") as ex:
        outcome = ex.run(Case(theta0=1.0, phi0=0.5, epsilon=1e-5))
    analytic.predict(Case(theta0=1.0, phi0=0.5, epsilon=1e-5)).e

Any body FMU (the rod, TwoLinkArm.fmu, ...), through its own variables and either interface; a case is
start values plus the configuration they came from (IWCCase): a BodyCase, or the rod's Case:

    from painleve import Body, BodyCase, run_body
    with Body("build/TwoLinkArm.fmu", fmi_type="CoSimulation") as body:
        predicted, outcome = run_body(body, BodyCase(given=(), epsilon=1e-4))   # its own start, on the floor
    outcome.w_error         # w/v0 - e, e from the FMU's coefficients (predicted.e); outcome.as_row(): a flat dict
    with Body("build/PainleveRod.fmu") as body:      # the rod's Case takes the same path
        predicted, outcome = run_body(body, Case(theta0=1.0, phi0=0.5, epsilon=1e-5))

and many of them, the paradox map from simulation beside the theory's p_plus < 0:

    from painleve import run_body_sweep, sweep_axes, sweep_map_figure
    rows = run_body_sweep("build/TwoLinkArm.fmu", sweep_axes({"theta1": "-1.6:-0.5", "theta2": "-1.6:-0.5",
                          "mu": "0.3:2"}, {"epsilon": "1e-5", "v0": "0.2"}, random=True), samples=20, seed=1,
                          solve=("H",))

or, written as they finish and resumable, here or on dask (sweep.run, as the rod's sweep runs):

    from painleve import BodySweep, run_sweep
    run_sweep(BodySweep(axes=sweep_axes({"theta1": "-1.2:-0.8:9"}, {"epsilon": "1e-5", "v0": "0.2"}),
                        guess=(("theta2", -1.3),)), "build/TwoLinkArm.fmu", "out/arm.csv")

The names below are the package's public face; each is imported on first use, so that
`import painleve` (and the theory alone) loads no fmpy. The layers behind them:
theory < experiments < fmu < coupling, validation, sweep < figures < cli (docs/architecture.md).
"""
import importlib

# {public name: (module, its name there)}; a module's own name (analytic, general, ...) is the module.
_PUBLIC = {
    "analytic": ("theory.analytic", None), "rigid_limit": ("theory.rigid_limit", None),
    "general": ("theory.general", None), "HypothesisError": ("theory.hypotheses", "HypothesisError"),
    "IWCCase": ("experiments.case", "IWCCase"), "Case": ("experiments.case", "Case"),
    "BodyCase": ("experiments.case", "BodyCase"), "Outcome": ("experiments.outcome", "Outcome"),
    "SimulationError": ("experiments.outcome", "SimulationError"), "NoReturn": ("experiments.outcome", "NoReturn"),
    "w_error": ("experiments.outcome", "w_error"), "run_reference": ("experiments.reference", "run_reference"),
    "Experiment": ("fmu.experiment", "Experiment"), "FmuLoadError": ("fmu.experiment", "FmuLoadError"),
    "run_iwc": ("fmu.experiment", "run_iwc"),
    "Body": ("fmu.body", "Body"), "BodyError": ("fmu.body", "BodyError"),
    "BodyPrediction": ("fmu.body_case", "BodyPrediction"), "predict_body": ("fmu.body_case", "predict"),
    "run_body": ("fmu.body_case", "run_body"),
    "si": ("coupling.si", None), "SIExperiment": ("coupling.si_experiment", "SIExperiment"),
    "validate": ("validation.suite", "validate"), "validate_body": ("validation.body", "validate_body"),
    "validate_fmu": ("validation.body", "validate_fmu"),
    "SweepSpec": ("sweep.spec", "SweepSpec"), "run_sweep": ("sweep.run", "run_sweep"),
    "run_body_sweep": ("sweep.body", "run_body_sweep"), "sweep_axes": ("sweep.body", "axes_of"),
    "BodySweep": ("sweep.body", "BodySweep"),
    "make_figures": ("figures.paper", "make_figures"), "paradox_figure": ("figures.body", "paradox_figure"),
    "sweep_map_figure": ("figures.body", "sweep_map_figure"),
}
__all__ = sorted(_PUBLIC)


def __getattr__(name):
    if name not in _PUBLIC:
        raise AttributeError(f"module 'painleve' has no attribute {name!r}")
    where, attribute = _PUBLIC[name]
    module = importlib.import_module(f".{where}", __name__)
    value = module if attribute is None else getattr(module, attribute)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_PUBLIC))
