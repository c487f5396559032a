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

Each case's result: its outcome and the slowest single call. Outcomes:
  ok, discard (a doStep returned Discard, and the instance then answered its getters),
  error (a call returned Error; its log does not say Zeno), solver (Model Exchange: fmpy's
  CVode gave up, e.g. too much work: the importer's limit, not the FMU's), and the failures:
  zeno (an error whose log or message says "Zeno"), illegal (Discard from a call
  other than doStep, or the getters failing after a Discard, or a non-finite
  output after one), harness (this file's own exception), and, recorded by the
  parent, hang (the case ran past the wall limit: the worker is killed) and crash
  (the worker died). A call's time is the time between the ends of two successive
  FMI calls (fmpy's call logger): the call itself plus the importer's own work before it.
"""
import json
import math
import os
import pathlib
import random
import select
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
FAILURES = ("hang", "crash", "zeno", "illegal", "harness")

# (model, FMI version) -> the built FMU.
FMUS = {("PainleveRod", 2): "build/PainleveRod.fmu", ("PainleveRod", 3): "build/fmi3/PainleveRod.fmu",
        ("PainleveRodSI", 2): "build/PainleveRodSI.fmu", ("ShakerTable", 2): "build/ShakerTable.fmu"}
# Every run: (model, FMI version, interface, ME solver).
COMBOS = [(model, fmi, *run) for (model, fmi) in FMUS
          for run in (("CS", None), ("ME", "CVode"), ("ME", "Euler"))]

# The scale of a state's or input's excursion from its start (model units).
SCALES = {"x": 1, "v": 2, "y": 0.1, "w": 1, "theta": 3.2, "phi": 3, "position": 1e-3, "velocity": 0.1,
          "y_floor": 0.05, "w_floor": 1, "v_floor": 1, "F_x": 10, "F_y": 10, "tau": 1, "F_N": 100, "F_T": 100}
# The documented range is 1e-12 to 1e-3 (docs/bounded_calls.md): its ends, just outside them, and far outside.
TOLERANCE_EDGES = [1e-14, 1e-13, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3, 2e-3, 1e-2, 0.1, 0.5, 1.0, 10.0, 48.125]
START_EDGES = [48.125, 1e4, -1e4, 1e6]
ME_TIMEOUT = 2.0  # fmpy's own limit on a Model Exchange run's real time (it stops the loop between calls)


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

        states = {d.variable.derivative.name for d in md.derivatives}
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


def issue_cases(models):
    """Issue 23's hangs as cases (negative indices), where their FMUs are built: tolerance = start time =
    48.125 then steps of 0.02 and 0.069 (each model, each FMI version); PainleveRod at tolerance 1.56e-6
    from a deep, stiff start; PainleveRodSI at tolerance 0.157 (a step across t = 2.12 never returned)."""
    rod = dict(alpha=19.93, epsilon=4.87e-6, kappa=3.19, y=-0.1138, w=0.863, phi=1.220)
    si = dict(m=1.30, l=4.30, J=0.0662, c=2801, w_floor=0.918, F_x=0.184, F_y=0.0925, w=0.731, phi=2.64)
    cases = [dict(model=model, fmi=fmi, tolerance=48.125, start=48.125, values={}, steps=[0.02, 0.069])
             for (model, fmi) in FMUS]
    cases += [dict(model="PainleveRod", fmi=fmi, tolerance=1.56e-6, start=0.0, values=rod, steps=[0.257, 0.257])
              for fmi in (2, 3)]
    cases.append(dict(model="PainleveRodSI", fmi=2, tolerance=0.157, start=0.0, values=si, steps=[0.25] * 10))
    return [dict(case, index=-k - 1, seed="issue23", interface="CS") for k, case in enumerate(cases)
            if (case["model"], case["fmi"]) in models]


def describe(case):
    """A case as one line of its values (to replay it by hand, or by index)."""
    head = (f"case {case['index']} (seed {case['seed']}): {case['model']} FMI {case['fmi']}.0 {case['interface']}"
            + (f" {case['solver']} step {case['step']:.6g} to {case['stop']:.17g}" if case["interface"] == "ME"
               else f" steps {[float(f'{h:.6g}') for h in case['steps']]}"))
    return (f"{head}; tolerance {case['tolerance']:.17g}, start time {case['start']:.17g}; "
            + ", ".join(f"{k} = {v:.17g}" for k, v in case["values"].items()))


# ------------------------------------------------------------------ the worker (child process)

class _Calls:
    """fmpy's call logger: the slowest call, and the FMU's log messages."""

    def __init__(self):
        self.last = time.perf_counter()
        self.slowest = (0.0, "")
        self.messages = []

    def call(self, text):
        now = time.perf_counter()
        if now - self.last > self.slowest[0]:
            self.slowest = (now - self.last, text[:200])
        self.last = now

    def log(self, *args):
        message = args[-1]
        self.messages.append(message.decode(errors="replace") if isinstance(message, bytes) else str(message))


def _co_simulation(case, md, unzipdir, calls):
    from fmpy.fmi1 import FMICallException
    from fmpy.simulation import instantiate_fmu
    fmu = instantiate_fmu(unzipdir, md, "CoSimulation", logger=calls.log, fmi_call_logger=calls.call)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    names = list(case["values"])
    outputs = [v.valueReference for v in md.modelVariables
               if v.type in ("Real", "Float64") and v.causality == "output"]
    fmi3 = case["fmi"] == 3
    failed = True                   # an Error leaves the instance in a state where only freeing it is allowed
    set_real, get_real = (fmu.setFloat64, fmu.getFloat64) if fmi3 else (fmu.setReal, fmu.getReal)
    try:
        t = case["start"]
        if fmi3:
            set_real([vr[n] for n in names], [case["values"][n] for n in names])
            fmu.enterInitializationMode(tolerance=case["tolerance"], startTime=t)
        else:
            fmu.setupExperiment(tolerance=case["tolerance"], startTime=t)
            set_real([vr[n] for n in names], [case["values"][n] for n in names])
            fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        for h in case["steps"]:
            try:
                answer = fmu.doStep(t, h)
                # FMI 3.0 §4.2.1: without an early return, the step ends at t + h
                if fmi3 and not answer[2] and answer[3] != t + h:
                    failed = False
                    return "illegal", f"doStep({t!r}, {h!r}) returned lastSuccessfulTime {answer[3]!r}"
            except FMICallException as e:
                if e.status != 2:
                    raise
                try:                # Discard: the instance still answers its getters
                    values = get_real(outputs)
                except FMICallException as e2:
                    return "illegal", f"after a Discard of doStep({t!r}, {h!r}): {e2}"
                failed = False
                if not all(math.isfinite(x) for x in values):
                    return "illegal", f"after a Discard of doStep({t!r}, {h!r}): outputs {values}"
                return "discard", f"doStep({t!r}, {h!r})"
            t += h
        values = get_real(outputs)
        failed = False
        if not all(math.isfinite(x) for x in values):
            return "illegal", f"outputs {values}"
        return "ok", ""
    finally:
        if not failed:
            fmu.terminate()
        fmu.freeInstance()


def _model_exchange(case, md, unzipdir, calls):
    from fmpy import simulate_fmu
    span, step = case["stop"] - case["start"], case["step"]
    # fmpy's fixed-step Euler wants output points on its grid
    interval = step * max(1, round(span / 50 / step)) if case["solver"] == "Euler" else span / 50
    simulate_fmu(unzipdir, validate=False, model_description=md, fmi_type="ModelExchange",
                 solver=case["solver"], start_time=case["start"], stop_time=case["stop"], step_size=case["step"],
                 output_interval=interval, relative_tolerance=case["tolerance"],
                 start_values=case["values"], timeout=ME_TIMEOUT, logger=calls.log, fmi_call_logger=calls.call)
    return "ok", ""


def run_one(case, md, unzipdir):
    """One case in this process: (outcome, detail, slowest call)."""
    from fmpy.fmi1 import FMICallException
    calls = _Calls()
    try:
        run = _co_simulation if case["interface"] == "CS" else _model_exchange
        outcome, detail = run(case, md, unzipdir, calls)
    except FMICallException as e:
        outcome = "illegal" if e.status == 2 else "error"
        detail = str(e)
    except RuntimeError as e:       # fmpy's CVode gave up (too much work, error test failures)
        outcome, detail = ("solver" if str(e).startswith("CVode error") else "harness"), str(e)[:300]
    except Exception as e:
        outcome, detail = "harness", f"{type(e).__name__}: {e}"
    text = " | ".join(calls.messages[-3:])
    if outcome == "error" and ("zeno" in text.lower() or "zeno" in detail.lower()):
        outcome = "zeno"
    if outcome not in ("ok", "discard"):
        detail = f"{detail}; log: {text}"[:1000]
    return outcome, detail, calls.slowest


def worker(cases_file, first, fd):
    """Runs the cases from `first` on, reporting "start K" and "end K {json}" lines on fd."""
    from fmpy import read_model_description
    spec = json.loads(pathlib.Path(cases_file).read_text())
    mds = {}
    out = os.fdopen(int(fd), "w", buffering=1)
    for case in spec["cases"][int(first):]:
        key = f"{case['model']}/{case['fmi']}"
        if key not in mds:
            mds[key] = read_model_description(spec["unzipdirs"][key])
        out.write(f"start {case['index']}\n")
        started = time.perf_counter()
        outcome, detail, slowest = run_one(case, mds[key], spec["unzipdirs"][key])
        out.write("end " + json.dumps(dict(index=case["index"], outcome=outcome, detail=detail,
                                           slowest=slowest, seconds=time.perf_counter() - started)) + "\n")


# ------------------------------------------------------------------ the parent

def run_cases(models, cases, wall, progress=None):
    """Runs `cases` in sequence in worker processes; a case past `wall` seconds is a hang (its worker
    is killed, a fresh one goes on from the next case), a worker's death a crash. Returns
    {index: result}; each result has outcome, detail, slowest (seconds, call), seconds."""
    from fmpy import extract
    results = {}
    with tempfile.TemporaryDirectory(prefix="bounded-cases-") as tmp:
        unzipdirs = {f"{model}/{fmi}": str(extract(m["path"], os.path.join(tmp, f"{model}-{fmi}")))
                     for (model, fmi), m in models.items()}
        cases_file = os.path.join(tmp, "cases.json")
        pathlib.Path(cases_file).write_text(json.dumps(dict(cases=cases, unzipdirs=unzipdirs)))
        position = {case["index"]: k for k, case in enumerate(cases)}
        k = 0
        while k < len(cases):
            k = _one_worker(cases, k, cases_file, wall, results, position, tmp, progress)
    return results


def _one_worker(cases, first, cases_file, wall, results, position, tmp, progress):
    """One worker from case position `first`; returns the position to go on from."""
    read_fd, write_fd = os.pipe()
    stderr_path = os.path.join(tmp, "worker-stderr")
    with open(stderr_path, "w") as stderr:
        proc = subprocess.Popen([sys.executable, __file__, "--worker", cases_file, str(first), str(write_fd)],
                                pass_fds=(write_fd,), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=stderr)
    os.close(write_fd)
    current, deadline, buffer = None, math.inf, ""
    try:
        while True:
            ready, _, _ = select.select([read_fd], [], [], max(0.0, min(deadline - time.monotonic(), 1.0)))
            if not ready:
                if time.monotonic() < deadline:
                    continue
                proc.kill()
                proc.wait()
                results[current] = dict(outcome="hang", detail=f"still running after {wall:g} s",
                                        slowest=(wall, "a call that did not return"), seconds=wall)
                _report(progress, cases[position[current]], results[current])
                return position[current] + 1
            chunk = os.read(read_fd, 65536).decode()
            if not chunk:           # the worker ended: all done, or it died in `current`
                proc.wait()
                if current is None:
                    if first < len(cases) and proc.returncode != 0:
                        raise RuntimeError(f"the worker failed to start:\n{pathlib.Path(stderr_path).read_text()}")
                    return len(cases)
                text = pathlib.Path(stderr_path).read_text()[-1500:]
                results[current] = dict(outcome="crash", detail=f"worker exit {proc.returncode}: {text}",
                                        slowest=(0.0, ""), seconds=0.0)
                _report(progress, cases[position[current]], results[current])
                return position[current] + 1
            buffer += chunk
            *lines, buffer = buffer.split("\n")
            for line in lines:
                word, rest = line.split(" ", 1)
                if word == "start":
                    current, deadline = int(rest), time.monotonic() + wall
                else:
                    result = json.loads(rest)
                    results[result["index"]] = result
                    _report(progress, cases[position[result["index"]]], result)
                    current, deadline = None, math.inf
    finally:
        os.close(read_fd)
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def _report(progress, case, result):
    if progress:
        progress(case, result)


if __name__ == "__main__" and sys.argv[1:2] == ["--worker"]:
    worker(*sys.argv[2:5])
