# SPDX-License-Identifier: BSD-2-Clause
"""The benchmark's cases and its runners (bench/bench.py measures and compares them):
every way we have of running an IWC case, as name -> f(case, rtol), instances made
once; see bench.py's docstring for what each runner is.
"""
import os
import pathlib
import sys
import time

# The systems are 6x6: BLAS threads would only spin on the other core.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

import fmpy                                              # noqa: E402
from native_driver import run_native, run_native_cs      # noqa: E402
from painleve.experiments import reference                      # noqa: E402
from painleve.experiments.case import Case                      # noqa: E402
from painleve.experiments.outcome import outcome_of_trajectory  # noqa: E402
from painleve.fmu.experiment import OUTPUTS, Experiment         # noqa: E402
from painleve.theory import analytic as an                      # noqa: E402

FMU = ROOT / "build" / "PainleveRod.fmu"
NATIVE = ROOT / "build" / "bench" / "native" / "painleve_native_me"
NATIVE_CS = ROOT / "build" / "bench" / "native" / "painleve_native_cs"
# Co-Simulation under CVODE alone, without the explicit pair: a build of a commit
# before the pair (e.g. main's build/PainleveRod.fmu at 7cee6fa), if given; the runner is left out if not.
CVODE_CS_FMU = os.environ.get("PAINLEVE_BENCH_CVODE_CS_FMU")
NATIVE_CS_FMUS = {"native CS": FMU, **({"native CS (CVODE only)": CVODE_CS_FMU} if CVODE_CS_FMU else {})}
EPSILONS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
SCIPY = ("LSODA", "DOP853", "Radau", "BDF")
VIDEO = dict(theta0=0.9463, phi0=1.6654, v0=1.0, delta=1.0)


def cases_at(eps):
    """Theorem 1 at three theta0 and delta, Theorem 2 on both sides of w1*."""
    t1 = [Case(epsilon=eps), Case(epsilon=eps, theta0=0.9, delta=0.0), Case(epsilon=eps, theta0=1.1, delta=0.5)]
    w1s = an.predict(Case(epsilon=eps, **VIDEO)).w1_star
    return t1 + [Case(epsilon=eps, w10=1.2 * w1s, **VIDEO), Case(epsilon=eps, w10=0.8 * w1s, **VIDEO)]


def w_error(case, w):
    """w/v0 - e: the model's O(eps ln 1/eps) error (Theorem 1)."""
    return w / case.v0 - an.predict(case).e


class Counting:
    """Counts an fmpy instance's fmi2GetDerivatives calls (one per CVode RHS evaluation)."""

    def __init__(self, fmu):
        self.calls, self._get = 0, fmu.getDerivatives

        def counted(*args, **kwargs):
            self.calls += 1
            return self._get(*args, **kwargs)
        fmu.getDerivatives = counted


# The runners with a tolerance: those compared at equal accuracy.
TUNABLE = ["fmpy ME fast loop", "fmpy CS fast loop"] + [f"scipy {m}" for m in SCIPY] + ["native"] + list(NATIVE_CS_FMUS)


class Runners:
    """Every runner as name -> f(case, rtol) -> dict(w, nfev, nsteps, nevents); instances made once.
    rtol None: the harness's, min(1e-6, eps/100)."""

    def __init__(self):
        self.me, self.cs = Experiment(FMU), Experiment(FMU, fmi_type="CoSimulation")
        self.euler = Experiment(FMU, solver="Euler")
        self.euler_count = Counting(self.euler.instance)

    def names(self):
        return (["fmpy ME simulate_fmu", "fmpy ME fast loop", "fmpy ME Euler", "fmpy CS simulate_fmu",
                 "fmpy CS fast loop"] + [f"scipy {m}" for m in SCIPY] + ["native"] + list(NATIVE_CS_FMUS))

    def run(self, name, case, rtol=None):
        self.me.relative_tolerance = self.cs.relative_tolerance = rtol    # simulate_fmu's settings too
        if name.endswith("simulate_fmu"):
            return dict(w=self.simulate_fmu(case, "CoSimulation" if " CS " in name else "ModelExchange").w)
        if name == "fmpy ME fast loop":
            o = self.me.run(case)
            return dict(w=o.w, nevents=o.events, **self.me.solver_stats)
        if name == "fmpy ME Euler":
            before = self.euler_count.calls
            o = self.euler.run(case)
            return dict(w=o.w, nfev=self.euler_count.calls - before, nevents=o.events)
        if name == "fmpy CS fast loop":
            return dict(w=self.cs.run(case).w)
        if name.startswith("scipy "):
            o = reference.run_reference(case, method=name.split()[1], relative_tolerance=rtol)
            return dict(w=o.w, **{k: o.solver_stats[k] for k in ("nfev", "nsteps", "nevents")})
        raise KeyError(name)

    def run_block(self, name, cases, rtol=None):
        """The cases one after the other: [(seconds, dict)] (the native driver times itself)."""
        if name == "native":
            return [(n["wall_seconds"], dict(w=n["w"], nfev=n["nfev"], nsteps=n["nsteps"], nevents=n["nevents"]))
                    for n in run_native(NATIVE, FMU, cases, rtol=rtol)]
        if name in NATIVE_CS_FMUS:
            return [(n["wall_seconds"], dict(w=n["w"], fixed_seconds=n["fixed_seconds"], **cs_counts(n)))
                    for n in run_native_cs(NATIVE_CS, NATIVE_CS_FMUS[name], cases, rtol=rtol, repeat=5)]
        return [timed(self.run, name, case, rtol) for case in cases]

    def simulate_fmu(self, case, fmi_type):
        """fmpy.simulate_fmu from the .fmu file (unzip, load, run, free), with the harness's settings."""
        experiment = self.cs if fmi_type == "CoSimulation" else self.me
        r = fmpy.simulate_fmu(str(FMU), fmi_type=fmi_type,
                              start_values=case.start_values(), output=list(OUTPUTS), record_events=True,
                              **experiment.settings(case))
        return outcome_of_trajectory(case, r, exact_events=fmi_type == "ModelExchange")

    def close(self):
        for e in (self.me, self.cs, self.euler):
            e.close()


def cs_counts(row):
    """A native CS row's work as the FMU's logStatistics gives it (both integrators' steps and
    right-hand sides, events); a build without that category (-1) gives its switches only."""
    if row["steps"] < 0:
        return dict(nevents=row["switches"])
    return dict(nsteps=row["steps"] + row["cvode_steps"], nfev=row["rhs"] + row["cvode_rhs"],
                nflight=row["flight_evaluations"], nevents=row["events"])


def timed(f, *args):
    t = time.perf_counter()
    out = f(*args)
    return time.perf_counter() - t, out


def load_line(before, after):
    """The machine's load averages (1, 5, 15 min) before and after a timed table, for its heading."""
    return (f"load average (1, 5, 15 min) before {', '.join(f'{x:.2f}' for x in before)}, after "
            f"{', '.join(f'{x:.2f}' for x in after)}")
