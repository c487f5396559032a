"""The harness's sweep, timed side by side: N random Theorem 1 cases through
Co-Simulation (the harness's fastest path), by main's path before issue #28's
plan (a local dask cluster of 2 worker processes, tasks of 200 cases: main's
defaults, which run_sweep(workers=2, batch=200) runs through the same loop) and by
today's (sweep.plan: the first chunk in this process, the rest here unless a
cluster finishes it sooner; on a cluster, a few large chunks per worker).

    .venv/bin/python bench/sweep_bench.py               # prints the markdown table
    .venv/bin/python bench/sweep_bench.py 10000 auto    # one run: one JSON line
    .venv/bin/python bench/sweep_bench.py profile       # where a serial sweep's time goes (cProfile)

Each run is a fresh process, so that its imports, its cluster and its peak memory
(the driver's high-water mark, VmHWM) are its own; the paths alternate, REPEATS
times each, and the table gives the median. The clock runs from the call of
run_sweep to its return, as `painleve sweep` spends it: the import of
dask.distributed, the cluster's start and close included, except in the first
row, which starts the cluster before the clock as the figures of 7.7 s (issue #28)
and 13.3 -> 4.7 s were measured."""
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

SPEC = {"theta0": "0.9:1.2", "epsilon": "1e-5:1e-3:log", "delta": "0:2"}
REPEATS = 3
PATHS = {   # name: (what the row says, run_sweep's options)
    "main-started": ("main's: 2 workers, tasks of 200, cluster started before the clock", dict(batch=200)),
    "main": ("main's: 2 workers, tasks of 200 (`painleve sweep` on main)", dict(workers=2, batch=200)),
    "cluster": ("today's on a cluster (`--workers 2`): 8 tasks", dict(workers=2)),
    "auto": ("today's default (sweep.plan)", dict()),
}
ISSUE_SECONDS = 7.7     # issue #28's 10,000-case sweep


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


def fresh(fmu, n, path):
    out = subprocess.run([sys.executable, __file__, str(n), path, str(fmu)], capture_output=True, text=True,
                         check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def sweep_table(fmu, n=10_000, large=100_000):
    """Markdown lines: every path at n cases (alternating, REPEATS each), today's default at n/4 and
    at `large` (where the cluster pays), each run in a fresh process."""
    load = os.getloadavg()[0]
    runs = {p: [] for p in PATHS}
    for _ in range(REPEATS):
        for p in PATHS:
            runs[p].append(fresh(fmu, n, p))
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
        ratios = " | ".join(f"{ref / seconds:.1f}x" if cases == n else "" for ref in (started, main, ISSUE_SECONDS))
        lines.append(f"| {cases:,} | {PATHS[p][0]} | {where} | {seconds:.2f} | {cases / seconds:,.0f} | {ratios} | "
                     f"{max(r['driver_peak_mib'] for r in results):.0f} |")
    out = subprocess.run([sys.executable, __file__, "profile", str(fmu)], capture_output=True, text=True, check=True)
    parts, total, plain = json.loads(out.stdout.strip().splitlines()[-1])
    shares = "; ".join(f"{part} {100 * seconds / total:.0f} %" for part, seconds in parts)
    return lines + ["", WHERE_THE_TIME_GOES.format(plain=plain, total=total, shares=shares)]


WHERE_THE_TIME_GOES = (
    "Where the time goes (issue #28). Today's default runs 10,000 cases in this process: a local dask cluster "
    "of 2 workers costs about 4 s before it returns results (the driver's import of dask.distributed about 1 s, "
    "the cluster 0.8-1.6 s, each worker importing the harness and extracting the FMU 1.3 s, closing 0.5 s; "
    "longer on a loaded machine, compare the first two rows), more than the whole sweep takes here, and 2 "
    "workers on 2 cores shared with other jobs rarely halve the rest (sweep.plan counts the cores the load "
    "average leaves free: at load 4 a 100,000-case sweep stays here). So the rest of the time is the cases "
    "themselves: a serial sweep of the same 10,000 cases took {plain:.2f} s in the same run; under cProfile "
    "({total:.2f} s, which inflates Python's share and not C's): {shares}. The FMU's own integration is the "
    "smaller part; the larger is Python around it, per case: fmpy's wrappers of 11 FMI calls, the fast loop "
    "reading the FMU's record and building the Outcome, the row. What would go further: fewer "
    "Python calls per case (the FMI calls through ctypes directly, the outcome from the record without a "
    "dataclass per case); a pool forked from the driver gains only on free cores: at load 4.6, 2 forked "
    "processes ran the 10,000 cases in 3.9-4.0 s where this process took 3.6-4.0 s.")


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
    step, calls = cum("fmi2.py", "fmi2DoStep"), cum("fmi1.py", "_call")
    loop, row = cum("cs_fast_loop.py", "run_co_simulation"), cum("run.py", "case_row")
    parts = [("the FMU's fmi2DoStep (its integration, in C)", step),
             ("fmpy's 10 other FMI calls a case (reset, set-up, values, initialization, reads)", calls - step),
             ("the fast loop's Python (the Outcome from the FMU's record, the flight run back)", loop - calls),
             ("the row (the case, predictions, Outcome.as_row)", row - loop),
             ("the cases rebuilt from (seed, id)", cum("spec.py", "cases")),
             ("the predictions over arrays", cum("predict_many.py", "predict_many")),
             ("the chunks' DataFrames", cum("store.py", "as_frame")),
             ("writing the Parquet parts", cum("store.py", "append"))]
    total = cum("run.py", "run_sweep")
    return parts + [("the rest (opening the store, the probe's extraction of the FMU, ...)",
                     total - sum(s for _, s in parts))], total, plain


if __name__ == "__main__":
    root = pathlib.Path(__file__).resolve().parents[1]
    if sys.argv[1:2] == ["profile"]:
        print(json.dumps(profile(sys.argv[2] if len(sys.argv) > 2 else str(root / "build" / "PainleveRod.fmu"),
                                 10_000)))
    elif len(sys.argv) > 1:
        fmu = sys.argv[3] if len(sys.argv) > 3 else str(root / "build" / "PainleveRod.fmu")
        print(json.dumps(run(fmu, int(sys.argv[1]), sys.argv[2] if len(sys.argv) > 2 else "auto")))
    else:
        print("\n".join(sweep_table(root / "build" / "PainleveRod.fmu")))
