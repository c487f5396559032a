"""The SI rod's Co-Simulation table (issue #28: "the SI rod gets the same table"): the
benchmark's cases (bench_runners.cases_at) as PainleveRodSI starts (a rod of 1 kg and
half-length 0.5 m, coupling.si.si_of), each through one fmi2DoStep from 0 to the case's
horizon (in seconds), from Python through fmpy on one instance: fmi2Reset, setup with the
tolerance, the parameters and states set, initialization, the step, the state read.

    .venv/bin/python bench/si_table.py          # prints the markdown table

Per eps, at the FMU's default tolerance (1e-6) and at the harness's min(1e-6, eps/100): the
largest |w - w_ref| at the return to the floor (the state at the horizon in the paper's
units, run back in closed form as the harness's fast loop does; w_ref: scipy DOP853 at
1e-12 on the scaled model, an independent code; v0 = 1), us per case (median over cases of
the median over repeats; fmpy's calls included, about 50 us), the fixed cost (the same run
without its fmi2DoStep) and the FMU's switches."""
import pathlib
import statistics
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from bench_runners import EPSILONS, ROOT, cases_at                   # noqa: E402
from painleve.coupling import si                                     # noqa: E402
from painleve.experiments import reference                           # noqa: E402
from painleve.experiments.case import horizon                        # noqa: E402
from painleve.experiments.outcome import flight_back_to_floor         # noqa: E402
from painleve.fmu.experiment import Experiment                       # noqa: E402

SI_FMU = ROOT / "build" / "PainleveRodSI.fmu"
STATES = ("x", "v", "y", "w", "theta", "phi")
REPEATS = 11


def run_once(ex, case, rtol, step=True):
    """One run of the case; (seconds, state at the horizon in the paper's units, switches)."""
    rod, state = si.si_of(case)
    values = {**rod.parameters(), **state.start_values()}
    vr, fmu = ex.vr, ex.instance
    t0 = time.perf_counter()
    fmu.reset()
    fmu.setupExperiment(tolerance=rtol, startTime=0.0)
    fmu.setReal([vr[k] for k in values], list(values.values()))
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    if step:
        fmu.doStep(0.0, horizon(case) * rod.time_scale)
    x = dict(zip(STATES, fmu.getReal([vr[k] for k in STATES])))
    switches = fmu.getInteger([vr["switches"]])[0]
    seconds = time.perf_counter() - t0
    V = rod.speed_scale
    return seconds, dict(v=x["v"] / V, w=x["w"] / V, y=x["y"] / rod.l, theta=x["theta"],
                         phi=x["phi"] * rod.time_scale), switches


def w_at_return(paper_state):
    return flight_back_to_floor(paper_state)[1]["w"] if paper_state["y"] > 0 else paper_state["w"]


def row(ex, eps, rtol, label, refs):
    walls, fixed, errs, switches = [], [], [], []
    for case, w_ref in zip(cases_at(eps), refs):
        runs = [run_once(ex, case, rtol) for _ in range(REPEATS)]
        walls.append(statistics.median(s for s, _, _ in runs))
        fixed.append(statistics.median(run_once(ex, case, rtol, step=False)[0] for _ in range(REPEATS)))
        errs.append(abs(w_at_return(runs[0][1]) - w_ref))
        switches.append(runs[0][2])
    return (f"| {eps:.0e} | {rtol:.0e} ({label}) | {max(errs):.1e} | {1e6 * statistics.median(walls):.0f} "
            f"({1e6 * max(walls):.0f}) | {1e6 * statistics.median(fixed):.0f} | {statistics.median(switches):.0f} |")


def si_markdown(epsilons=EPSILONS):
    lines = ["## The SI rod (PainleveRodSI): one fmi2DoStep per case from Python", "",
             __doc__.split("\n\n", 2)[2].replace("\n", " "), "",
             "| eps | rtol | abs(w-w_ref) | us/case (slowest case) | fixed us/run | switches |",
             "|---|---|---|---|---|---|"]
    with Experiment(SI_FMU, fmi_type="CoSimulation") as ex:
        for eps in epsilons:
            refs = [reference.run_reference(case, method="DOP853", relative_tolerance=1e-12).w
                    for case in cases_at(eps)]
            lines.append(row(ex, eps, 1e-6, "default", refs))
            if eps / 100 < 1e-6:
                lines.append(row(ex, eps, eps / 100, "harness", refs))
    return lines


if __name__ == "__main__":
    print("\n".join(si_markdown()))
