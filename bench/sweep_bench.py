"""The harness's dask sweep, timed: N random Theorem 1 cases on a local cluster
of 2 worker processes, through Co-Simulation (the harness's fastest path).

    .venv/bin/python bench/sweep_bench.py 10000     # prints one JSON line

Each run is a fresh process (and cluster) so that its peak memory is its own:
the driver's and each worker's high-water mark (VmHWM). Run at two sizes, equal
peaks mean memory does not grow with the number of cases."""
import json
import pathlib
import subprocess
import sys
import tempfile
import time

WHERE_THE_TIME_GOES = (
    "Where a sweep case's time goes (issue #28, measured at a load of 6-7): the FMU integrates an IWC cas"
    "e in 20-40 us (the table above); the harness's Co-Simulation fast loop spends about 350 us more a ca"
    "se in fmpy's ctypes calls (reset, start values, initialization, then a doStep and the record's reads"
    " every 4 eps until the rod is back in the air) and the outcome; the rest is dask's batches and the P"
    'arquet store. The same 10,000 cases at the same load: 36.6 s with CVODE Co-Simulation (commit 7cee6f'
    "a), 26.6 s with the explicit pair: the FMU's share was already small, and a fourfold faster sweep ne"
    'eds fewer fmpy calls a case (one doStep to the horizon where no second contact follows).')
SPEC = {"theta0": "0.9:1.2", "epsilon": "1e-5:1e-3:log", "delta": "0:2"}


def peak_rss_mib():
    for line in pathlib.Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def run(fmu, n, interface="CS"):
    import logging

    from dask.distributed import Client, LocalCluster

    from painleve.sweep.run import run_sweep
    from painleve.sweep.spec import SweepSpec
    spec = SweepSpec.from_texts(SPEC, samples=n, seed=7)
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                           silence_logs=logging.ERROR)
    client = Client(cluster)
    with tempfile.TemporaryDirectory() as tmp:
        t = time.monotonic()
        result = run_sweep(spec, fmu, pathlib.Path(tmp) / "sweep.parquet",
                           fmi_type={"CS": "CoSimulation", "ME": "ModelExchange"}[interface],
                           scheduler=cluster.scheduler_address, progress=False, say=lambda text: None)
        seconds = time.monotonic() - t
    workers = sorted(client.run(peak_rss_mib).values())
    client.close()
    cluster.close()
    return dict(cases=result.ran, seconds=seconds, cases_per_second=result.ran / seconds, interface=interface,
                driver_peak_mib=peak_rss_mib(), worker_peak_mib=workers)


def sweep_table(fmu, n):
    """Markdown lines: the sweep at n cases and at n/4 (for the memory), each in a fresh process."""
    results = []
    for size in (n // 4, n):
        out = subprocess.run([sys.executable, __file__, str(size), str(fmu)], capture_output=True, text=True,
                             check=True)
        results.append(json.loads(out.stdout.strip().splitlines()[-1]))
    lines = [f"`painleve.sweep.run.run_sweep` on a local dask cluster, 2 worker processes, random Theorem 1 cases "
             f"{SPEC}, Co-Simulation fast loop; each size in a fresh process.", "",
             "| cases | seconds | cases/s | driver peak MiB | worker peaks MiB |", "|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['cases']} | {r['seconds']:.1f} | {r['cases_per_second']:.0f} | "
                     f"{r['driver_peak_mib']:.0f} | {', '.join(f'{w:.0f}' for w in r['worker_peak_mib'])} |")
    return lines + ["", WHERE_THE_TIME_GOES]


if __name__ == "__main__":
    root = pathlib.Path(__file__).resolve().parents[1]
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 10_000
    fmu = sys.argv[2] if len(sys.argv) > 2 else str(root / "build" / "PainleveRod.fmu")
    print(json.dumps(run(fmu, size)))
