# SPDX-License-Identifier: BSD-2-Clause
"""Cases of bench/bounded_cases.py run in sequence in worker child processes under a
wall limit: the parent (run_cases) starts a worker, hears "start K" and "end K {json}"
from it on a pipe, and kills it past the wall limit; the worker (`python
bench/bounded_runs.py --worker CASES_FILE FIRST FD`) runs each case through fmpy.

Each case's result: its outcome and the slowest single call. Outcomes:
  ok, discard (a doStep returned Discard, and the instance then answered its getters),
  error (a call returned Error; its log does not say Zeno), solver (Model Exchange: fmpy's
  CVode gave up, e.g. too much work: the importer's limit, not the FMU's),
  t-limit (an error whose log says t cannot resolve the contact at that time: its time scale
  is below what events at that t can be placed to, contact_record.h; the double's limit, said
  as such), and the failures:
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
import select
import subprocess
import sys
import tempfile
import time

# The outcomes that are failures (the docstring above).
FAILURES = ("hang", "crash", "zeno", "illegal", "harness")
ME_TIMEOUT = 2.0  # fmpy's own limit on a Model Exchange run's real time (it stops the loop between calls)


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
    elif outcome == "error" and "t cannot resolve the contact" in text:
        outcome = "t-limit"
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
