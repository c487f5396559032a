# SPDX-License-Identifier: BSD-2-Clause
"""The SI rod's Co-Simulation table, as the rod's: the
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
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from bench_runners import EPSILONS, ROOT, cases_at                   # noqa: E402
from one_step_table import header, row, timed_run                     # noqa: E402
from painleve.coupling import si                                     # noqa: E402
from painleve.experiments import reference                           # noqa: E402
from painleve.experiments.case import horizon                        # noqa: E402
from painleve.experiments.outcome import flight_back_to_floor         # noqa: E402
from painleve.fmu.experiment import Experiment                       # noqa: E402

SI_FMU = ROOT / "build" / "PainleveRodSI.fmu"
STATES = ("x", "v", "y", "w", "theta", "phi")


def run_once(ex, case, rtol, step=True):
    """One run of the case; (seconds, state at the horizon in the paper's units, switches)."""
    rod, state = si.si_of(case)
    V = rod.speed_scale

    def read(fmu, vr):
        x = dict(zip(STATES, fmu.getReal([vr[k] for k in STATES])))
        return dict(v=x["v"] / V, w=x["w"] / V, y=x["y"] / rod.l, theta=x["theta"], phi=x["phi"] * rod.time_scale)

    return timed_run(ex, {**rod.parameters(), **state.start_values()}, rtol, horizon(case) * rod.time_scale, read,
                     step)


def w_at_return(paper_state):
    return flight_back_to_floor(paper_state)[1]["w"] if paper_state["y"] > 0 else paper_state["w"]


def si_row(ex, eps, rtol, label, refs):
    return row(eps, rtol, label, [(lambda step, case=case: run_once(ex, case, rtol, step),
                                   lambda state, w_ref=w_ref: abs(w_at_return(state) - w_ref))
                                  for case, w_ref in zip(cases_at(eps), refs)])


def si_markdown(epsilons=EPSILONS):
    lines = ["## The SI rod (PainleveRodSI): one fmi2DoStep per case from Python", "",
             __doc__.split("\n\n", 2)[2].replace("\n", " "), "", *header("abs(w-w_ref)")]
    with Experiment(SI_FMU, fmi_type="CoSimulation") as ex:
        for eps in epsilons:
            refs = [reference.run_reference(case, method="DOP853", relative_tolerance=1e-12).w
                    for case in cases_at(eps)]
            lines.append(si_row(ex, eps, 1e-6, "default", refs))
            if eps / 100 < 1e-6:
                lines.append(si_row(ex, eps, eps / 100, "harness", refs))
    return lines


if __name__ == "__main__":
    print("\n".join(si_markdown()))
