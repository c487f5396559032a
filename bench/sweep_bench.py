# SPDX-License-Identifier: BSD-2-Clause
"""The harness's sweep, timed side by side: N random Theorem 1 cases through
Co-Simulation (the harness's fastest path), by main's path before
sweep.plan (main's own code, MAIN_COMMIT's python_harness, with the FMU built here: a local
dask cluster of 2 worker processes, tasks of 200 cases, through fmpy's wrappers) and by
today's (sweep.plan: the first chunk in this process, the rest here unless a
cluster finishes it sooner; on a cluster, a few large chunks per worker; a case's
FMI calls straight into the FMU, its row a tuple).

    .venv/bin/python bench/sweep_bench.py               # prints the markdown table
    .venv/bin/python bench/sweep_bench.py 10000 auto    # one run: one JSON line
    .venv/bin/python bench/sweep_bench.py profile       # where a serial sweep's time goes (cProfile)
    .venv/bin/python bench/sweep_bench.py same 3000     # main's code and today's rows, bit for bit

Main's rows run in a Python started with -S and main's code first on PYTHONPATH (the
editable install's import hook would otherwise load today's), which its cluster's
workers inherit. Each run is a fresh process, so that its imports, its cluster and its peak memory
(the driver's high-water mark, VmHWM) are its own; the paths alternate, REPEATS
times each, and the table gives the median. The clock runs from the call of
run_sweep to its return, as `painleve sweep` spends it: the import of
dask.distributed, the cluster's start and close included, except in the first
row, which starts the cluster before the clock as the reference figures of 7.7 s
(REFERENCE_SECONDS) and 13.3 -> 4.7 s were measured (docs/benchmarks.md)."""
import json
import os
import pathlib
import statistics
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import time

SPEC = {"theta0": "0.9:1.2", "epsilon": "1e-5:1e-3:log", "delta": "0:2"}
REPEATS = 3
PATHS = {   # name: (what the row says, run_sweep's options)
    "main-started": ("main's code: 2 workers, tasks of 200, cluster started before the clock", dict(batch=200)),
    "main": ("main's code: 2 workers, tasks of 200 (`painleve sweep` on main)", dict(workers=2, batch=200)),
    "cluster": ("today's on a cluster (`--workers 2`): 8 tasks", dict(workers=2)),
    "auto": ("today's default (sweep.plan)", dict()),
}
REFERENCE_SECONDS = 7.7     # the 10,000-case sweep the plan was set against (docs/benchmarks.md)
MAIN_COMMIT = "cdca957^"    # main before sweep.plan: its sweep, its fast loop
ROOT = pathlib.Path(__file__).resolve().parents[1]


def peak_rss_mib():
    for line in pathlib.Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def run(fmu, n, path):
    from painleve.sweep.run import run_sweep
    from painleve.sweep.spec import SweepSpec
    spec = SweepSpec.from_texts(SPEC, samples=n, seed=7)
    said = []
    how = dict(PATHS[path][1])
    cluster = None
    if path == "main-started":
        import logging

        from dask.distributed import LocalCluster
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                               silence_logs=logging.ERROR)
        how["scheduler"] = cluster.scheduler_address
    with tempfile.TemporaryDirectory() as tmp:
        t = time.monotonic()
        result = run_sweep(spec, fmu, pathlib.Path(tmp) / "sweep.parquet", fmi_type="CoSimulation", progress=False,
                           say=said.append, **how)
        seconds = time.monotonic() - t
    if cluster is not None:
        cluster.close()
    return dict(cases=result.ran, seconds=seconds, path=path, dask=any("dask" in s for s in said),
                driver_peak_mib=peak_rss_mib())


def main_code(into):
    """MAIN_COMMIT's python_harness extracted into `into`; its directory."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", MAIN_COMMIT, "python_harness"], capture_output=True,
                             check=True).stdout
    with tarfile.open(fileobj=__import__("io").BytesIO(archive)) as tar:
        tar.extractall(into, filter="data")
    return str(pathlib.Path(into) / "python_harness")


def fresh(fmu, n, path, main=None):
    """One run in a fresh process; with `main` (main_code's directory) main's rows run main's code."""
    env, flags = None, []
    if path.startswith("main") and main:
        site = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]}
        env, flags = {**os.environ, "PYTHONPATH": os.pathsep.join([main, *sorted(site)])}, ["-S"]
    out = subprocess.run([sys.executable, *flags, __file__, str(n), path, str(fmu)], capture_output=True, text=True,
                         check=True, env=env)
    return json.loads(out.stdout.strip().splitlines()[-1])


def sweep_table(fmu, n=10_000, large=100_000):
    """Markdown lines: every path at n cases (alternating, REPEATS each), today's default at n/4 and
    at `large` (where the cluster pays), each run in a fresh process."""
    load = os.getloadavg()[0]
    runs = {p: [] for p in PATHS}
    with tempfile.TemporaryDirectory() as tmp:
        main = main_code(tmp)
        for _ in range(REPEATS):
            for p in PATHS:
                runs[p].append(fresh(fmu, n, p, main))
    rows = [(runs[p], p) for p in PATHS] + [([fresh(fmu, size, "auto")], "auto") for size in (n // 4, large)]
    main = statistics.median(r["seconds"] for r in runs["main"])
    started = statistics.median(r["seconds"] for r in runs["main-started"])
    lines = [f"`painleve.sweep.run.run_sweep`, random Theorem 1 cases {SPEC}, Co-Simulation fast loop, on this 2-core "
             f"machine (load average {load:.1f} at the start); each run a fresh process, the paths "
             f"alternating, the median of {REPEATS} at {n:,} cases (one run at the other sizes).", "",
             "| cases | path | where it ran | seconds | cases/s | vs main's, started before | vs main's | vs 7.7 s "
             "| driver peak MiB |", "|---|---|---|---|---|---|---|---|---|"]
    for results, p in rows:
        seconds = statistics.median(r["seconds"] for r in results)
        cases = results[0]["cases"]
        where = "local cluster" if results[0]["dask"] else "this process"
        ratios = " | ".join(f"{ref / seconds:.1f}x" if cases == n else "" for ref in (started, main, REFERENCE_SECONDS))
        lines.append(f"| {cases:,} | {PATHS[p][0]} | {where} | {seconds:.2f} | {cases / seconds:,.0f} | {ratios} | "
                     f"{max(r['driver_peak_mib'] for r in results):.0f} |")
    out = subprocess.run([sys.executable, __file__, "profile", str(fmu)], capture_output=True, text=True, check=True)
    parts, total, plain = json.loads(out.stdout.strip().splitlines()[-1])
    shares = "; ".join(f"{part} {100 * seconds / total:.0f} %" for part, seconds in parts)
    return lines + ["", WHERE_THE_TIME_GOES.format(plain=plain, total=total, shares=shares)]


WHERE_THE_TIME_GOES = (
    "Where the time goes. Today's default runs 10,000 cases in this process: a local dask cluster "
    "of 2 workers costs about 4 s before it returns results (the driver's import of dask.distributed about 1 s, "
    "the cluster 0.8-1.6 s, each worker importing the harness and extracting the FMU 1.3 s, closing 0.5 s; "
    "longer on a loaded machine, compare the first two rows), more than the whole sweep takes here, and 2 "
    "workers on 2 cores shared with other jobs rarely halve the rest (sweep.plan counts the cores the load "
    "average leaves free). So the time is the cases themselves, and their Python was cut by half: a case's 11 "
    "FMI calls go straight into the FMU's C functions with arrays made once per instance (fmu/cs_calls.py; "
    "fmpy's wrappers made two ctypes arrays and a status check in Python per call), the batch's predictions "
    "over arrays go to each run and row (no cache look-ups per case; a row is a tuple, not a dict and an "
    "Outcome.as_row), a random batch's draws are numpy's generators over arrays (sweep/draws.py, 0.02 s for "
    "10,000 cases where a generator per case took 0.15 s), Case hashes once; every row bitwise as before "
    "(tests/sweep/test_sweep_rows.py). A serial sweep of the same 10,000 cases took {plain:.2f} s in the same "
    "run; under cProfile ({total:.2f} s, which inflates Python's share and not C's): {shares}. The FMU's C is "
    "now about half of it (the explicit integrator cuts its doStep further); the rest is the "
    "fast loop's Python per case (the Outcome's phases from the FMU's record, the closed-form flight run back, "
    "the run's reset and error context: about 30 us) and the batch's (predictions, DataFrames, Parquet). What "
    "would go further: the phases and the run back from the record in C (an output of the FMU), or a pool "
    "forked from the driver, which gains only on free cores (at load 4.6, 2 forked processes ran the 10,000 "
    "cases no faster than this process).")


def profile(fmu, n):
    """cProfile of today's path run serially on n cases: [(part, profiled seconds)], the profiled total
    and the same run's seconds unprofiled (cProfile inflates Python's share, not C's)."""
    import cProfile
    import pstats

    from painleve.sweep.run import run_sweep
    from painleve.sweep.spec import SweepSpec
    spec = SweepSpec.from_texts(SPEC, samples=n, seed=7)
    with tempfile.TemporaryDirectory() as tmp:
        t = time.monotonic()
        run_sweep(spec, fmu, pathlib.Path(tmp) / "plain.parquet", fmi_type="CoSimulation", serial=True,
                  progress=False)
        plain = time.monotonic() - t
        pr = cProfile.Profile()
        pr.runcall(run_sweep, spec, fmu, pathlib.Path(tmp) / "profiled.parquet", fmi_type="CoSimulation",
                   serial=True, progress=False)
    stats = pstats.Stats(pr).stats        # {(file, line, name): (cc, nc, tottime, cumtime, callers)}

    def cum(file, name):
        return sum(v[3] for (f, _, fn), v in stats.items() if f.endswith(file) and fn == name)
    step = cum("cs_calls.py", "step")
    calls = step + sum(cum("cs_calls.py", name) for name in ("reset", "start", "end"))
    loop, row = cum("cs_fast_loop.py", "run_co_simulation"), cum("run.py", "case_row")
    parts = [("the FMU's fmi2DoStep and the values read after it (its integration, in C)", step),
             ("the 10 other FMI calls a case (reset, set-up, start values, initialization, reads)", calls - step),
             ("the fast loop's Python (the Outcome from the FMU's record, the flight run back)", loop - calls),
             ("the row (its check, its tuple)", row - loop),
             ("the cases rebuilt from (seed, id)", cum("spec.py", "cases")),
             ("the predictions over arrays", cum("predict_many.py", "predict_many")),
             ("the chunks' DataFrames", cum("store.py", "as_frame")),
             ("writing the Parquet parts", cum("store.py", "append"))]
    total = cum("run.py", "run_sweep")
    return parts + [("the rest (opening the store, the probe's extraction of the FMU, ...)",
                     total - sum(s for _, s in parts))], total, plain


# `same`: cases inside and outside the theorems, and some that fail (no return within the horizon).
WIDE = {"theta0": "0.3:1.5", "phi0": "0:2", "w10": "-2:1", "epsilon": "1e-5:1e-2:log", "delta": "0:2"}


def rows(fmu, n, out):
    """The rows of n random WIDE cases, run serially in chunks of 1,000, written to the Parquet file `out`."""
    from painleve.sweep.run import run_sweep
    from painleve.sweep.spec import SweepSpec
    from painleve.sweep.store import ResultStore
    with tempfile.TemporaryDirectory() as tmp:
        run_sweep(SweepSpec.from_texts(WIDE, samples=n, seed=11), fmu, pathlib.Path(tmp) / "rows.parquet",
                  fmi_type="CoSimulation", serial=True, progress=False, batch=1000)
        ResultStore(pathlib.Path(tmp) / "rows.parquet").read().to_parquet(out)


def same(fmu, n):
    """Whether main's code and today's give the same rows, every float to the bit, on n WIDE cases."""
    import numpy as np
    import pandas as pd
    with tempfile.TemporaryDirectory() as tmp:
        main = main_code(tmp)
        site = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]}
        for name, flags, env in (("main", ["-S"], {**os.environ, "PYTHONPATH": os.pathsep.join([main, *sorted(site)])}),
                                 ("today", [], None)):
            subprocess.run([sys.executable, *flags, __file__, "rows", str(n), str(fmu), f"{tmp}/{name}.parquet"],
                           check=True, env=env)
        a, b = (pd.read_parquet(f"{tmp}/{name}.parquet") for name in ("main", "today"))
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    for name, column in a.items():
        if column.dtype == "float64":
            assert np.array_equal(column.to_numpy().view(np.int64), b[name].to_numpy().view(np.int64)), name
    return f"{n:,} cases ({a['status'].value_counts().to_dict()}): main's code and today's rows bitwise equal"


if __name__ == "__main__":
    root = pathlib.Path(__file__).resolve().parents[1]
    built = str(root / "build" / "PainleveRod.fmu")
    if sys.argv[1:2] == ["rows"]:
        rows(sys.argv[3], int(sys.argv[2]), sys.argv[4])
    elif sys.argv[1:2] == ["same"]:
        print(same(built, int(sys.argv[2]) if len(sys.argv) > 2 else 3000))
    elif sys.argv[1:2] == ["profile"]:
        print(json.dumps(profile(sys.argv[2] if len(sys.argv) > 2 else str(root / "build" / "PainleveRod.fmu"),
                                 10_000)))
    elif len(sys.argv) > 1:
        fmu = sys.argv[3] if len(sys.argv) > 3 else str(root / "build" / "PainleveRod.fmu")
        print(json.dumps(run(fmu, int(sys.argv[1]), sys.argv[2] if len(sys.argv) > 2 else "auto")))
    else:
        print("\n".join(sweep_table(root / "build" / "PainleveRod.fmu")))
