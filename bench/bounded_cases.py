# SPDX-License-Identifier: BSD-2-Clause
"""Random legal cases of every built FMU (model x FMI version x interface), each run
in a worker child process under a wall limit: the machinery of
tests/fmu/test_bounded_calls.py (every call returns) and bench/bounded_calls.py (its
table over a few thousand cases).

A case is a dict of plain values (JSON), made from (seed, index) alone, so any
case can be replayed by its index: `python bench/bounded_calls.py --seed S --only K`.
It draws, within each model description's min/max:
  - each Real parameter (not the calculated ones): its start value, a value within
    a factor 10 of it, or anywhere in its range (log-uniform, or an end);
  - each state and input: its start value or start + scale * U(-1, 1) * 10^U(-6, 0)
    (states near a switching surface as often as far from it);
  - the relative tolerance: an edge of any plausible range (1e-14 ... 48.125) or
    log-uniform in [1e-10, 1e-1]; the start time: 0, U(-100, 100) or a large one;
  - Co-Simulation: 1 to 8 steps, each log-uniform over five decades below the
    model's horizon (twice its DefaultExperiment's stop time);
    Model Exchange: fmpy's simulate_fmu with CVode or Euler over up to the horizon.

The cases are run by bench/bounded_runs.py (a worker process each, under a wall limit).
"""
import math
import pathlib
import random

ROOT = pathlib.Path(__file__).resolve().parents[1]

# (model, FMI version) -> the built FMU.
FMUS = {("PainleveRod", 2): "build/PainleveRod.fmu", ("PainleveRod", 3): "build/fmi3/PainleveRod.fmu",
        ("PainleveRodSI", 2): "build/PainleveRodSI.fmu", ("ShakerTable", 2): "build/ShakerTable.fmu",
        ("TwoLinkArm", 2): "build/TwoLinkArm.fmu", ("TwoLinkArm", 3): "build/fmi3/TwoLinkArm.fmu"}
# Every run: (model, FMI version, interface, ME solver).
COMBOS = [(model, fmi, *run) for (model, fmi) in FMUS
          for run in (("CS", None), ("ME", "CVode"), ("ME", "Euler"))]

# The scale of a state's or input's excursion from its start (model units).
SCALES = {"x": 1, "v": 2, "y": 0.1, "w": 1, "theta": 3.2, "phi": 3, "position": 1e-3, "velocity": 0.1,
          "theta1": 3.2, "theta2": 3.2, "omega1": 3, "omega2": 3, "y_floor": 0.05, "w_floor": 1, "v_floor": 1, "F_x": 10, "F_y": 10, "tau": 1, "F_N": 100, "F_T": 100}
# The documented range is 1e-12 to 1e-3 (docs/bounded_calls.md): its ends, just outside them, and far outside.
TOLERANCE_EDGES = [1e-14, 1e-13, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3, 2e-3, 1e-2, 0.1, 0.5, 1.0, 10.0, 48.125]
START_EDGES = [48.125, 1e4, -1e4, 1e6]


def read_models(fmus=None):
    """For each (model, FMI version) whose FMU is built: its path, parameters (name: (min, max, start)),
    states and inputs (name: start) and horizon, from its model description."""
    from fmpy import read_model_description
    models = {}
    for key, rel in (fmus or FMUS).items():
        path = ROOT / rel
        if not path.exists():
            continue
        md = read_model_description(str(path))
        real = [v for v in md.modelVariables if v.type in ("Real", "Float64")]

        def start(v):
            return float(v.start) if v.start is not None else 0.0

        # the states a start sets (a state the FMU calculates at initialization, the arm's y, is not one)
        states = {d.variable.derivative.name for d in md.derivatives if d.variable.derivative.initial != "calculated"}
        models[key] = dict(
            path=str(path),
            parameters={v.name: (float(v.min) if v.min is not None else -math.inf,
                                 float(v.max) if v.max is not None else math.inf, start(v))
                        for v in real if v.causality == "parameter"},
            states={v.name: start(v) for v in real if v.name in states},
            inputs={v.name: start(v) for v in real if v.causality == "input"},
            horizon=2 * float(md.defaultExperiment.stopTime))
    return models


def _parameter(rng, lo, hi, start):
    r = rng.random()
    if r < 0.5:
        return start
    if r < 0.9:                     # within a factor 10 of the start (of 1 where it starts at 0)
        x = (start or 1.0) * 10 ** rng.uniform(-1, 1)
    elif r < 0.93:
        x = rng.choice([e for e in (lo, hi) if math.isfinite(e)] or [start])
    else:                           # anywhere in the range, log-uniform
        a, b = max(lo, 1e-12 * hi if lo <= 0 else lo), hi
        x = 10 ** rng.uniform(math.log10(a), math.log10(b)) if 0 < a < b < math.inf else start
    return min(max(x, lo), hi)


def _excursion(rng, name, start):
    if rng.random() < 0.5:
        return start
    return start + SCALES.get(name, 1.0) * rng.uniform(-1, 1) * 10 ** rng.uniform(-6, 0)


def make_case(models, seed, index):
    """Case `index` of the run with `seed`: the same whatever the number of cases."""
    rng = random.Random(f"{seed}:{index}")
    combos = [c for c in COMBOS if (c[0], c[1]) in models]
    model, fmi, interface, solver = combos[index % len(combos)]
    m = models[(model, fmi)]
    values = {name: _parameter(rng, *spec) for name, spec in m["parameters"].items()}
    values.update({name: _excursion(rng, name, s) for name, s in {**m["states"], **m["inputs"]}.items()})
    r = rng.random()
    start = 0.0 if r < 0.6 else rng.uniform(-100, 100) if r < 0.8 else rng.choice(START_EDGES)
    tolerance = rng.choice(TOLERANCE_EDGES) if rng.random() < 0.4 else 10 ** rng.uniform(-10, -1)
    horizon = m["horizon"]
    case = dict(index=index, seed=seed, model=model, fmi=fmi, interface=interface, tolerance=tolerance,
                start=start, values=values)
    if interface == "CS":
        case["steps"] = [10 ** rng.uniform(math.log10(horizon) - 5, math.log10(horizon))
                         for _ in range(rng.randint(1, 8))]
    else:
        span = horizon * 10 ** rng.uniform(-2, 0)
        case.update(solver=solver, stop=start + span, step=span / 10 ** rng.uniform(1, 3))
    return case


def regression_cases(models):
    """The calls that once hung, as cases (negative indices), where their FMUs are built: tolerance = start time =
    48.125 then steps of 0.02 and 0.069 (each model, each FMI version); PainleveRod at tolerance 1.56e-6
    from a deep, stiff start; PainleveRodSI at tolerance 0.157 (a step across t = 2.12 never returned)."""
    rod = dict(alpha=19.93, epsilon=4.87e-6, kappa=3.19, y=-0.1138, w=0.863, phi=1.220)
    si = dict(m=1.30, l=4.30, J=0.0662, c=2801, w_floor=0.918, F_x=0.184, F_y=0.0925, w=0.731, phi=2.64)
    cases = [dict(model=model, fmi=fmi, tolerance=48.125, start=48.125, values={}, steps=[0.02, 0.069])
             for (model, fmi) in FMUS]
    cases += [dict(model="PainleveRod", fmi=fmi, tolerance=1.56e-6, start=0.0, values=rod, steps=[0.257, 0.257])
              for fmi in (2, 3)]
    cases.append(dict(model="PainleveRodSI", fmi=2, tolerance=0.157, start=0.0, values=si, steps=[0.25] * 10))
    return [dict(case, index=-k - 1, seed="regression", interface="CS") for k, case in enumerate(cases)
            if (case["model"], case["fmi"]) in models]


def describe(case):
    """A case as one line of its values (to replay it by hand, or by index)."""
    head = (f"case {case['index']} (seed {case['seed']}): {case['model']} FMI {case['fmi']}.0 {case['interface']}"
            + (f" {case['solver']} step {case['step']:.6g} to {case['stop']:.17g}" if case["interface"] == "ME"
               else f" steps {[float(f'{h:.6g}') for h in case['steps']]}"))
    return (f"{head}; tolerance {case['tolerance']:.17g}, start time {case['start']:.17g}; "
            + ", ".join(f"{k} = {v:.17g}" for k, v in case["values"].items()))
