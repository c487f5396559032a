# SPDX-License-Identifier: BSD-2-Clause
"""Where a sweep runs and in what chunks, from what its first cases cost.

A dask cluster pays only for a sweep longer than its start-up: a local cluster of
two worker processes costs about 4 s on this 2-core machine (the driver's import
of dask.distributed 0.9-1.1 s, the cluster 0.8-1.6 s, its workers importing the
harness and extracting the FMU before their first results 1.3 s, closing it
0.5-0.6 s; measured at load 2-3), when a Co-Simulation case costs about 120-170 us
in one process. So an automatic sweep runs
its first chunk in this process (the probe), and finishes here unless the rest,
at the probe's rate, takes longer here than the cluster's start-up plus the rest
shared among its workers (no more of them than the cores the load of other
processes leaves free). On the cluster, chunks are large (a few tasks per
worker, each at most TASK_SECONDS of work): a task costs dask a few
milliseconds of scheduling and transfer, and each chunk one DataFrame and one
written part. The chunks never change a case's numbers: each case runs alone
on a reset instance, its values drawn from (seed, id) alone."""
import math
import os

LOCAL_START_UP_SECONDS = 4.0     # a local cluster, until its workers return results (above)
PROBE_CASES = 256                # the first chunk, run here to measure the rate
SERIAL_CHUNK_SECONDS = 0.5       # a chunk in this process: what Ctrl-C may lose, ~1 % overhead a chunk
TASK_SECONDS = 5.0               # the most work in one dask task: progress, and a prompt stop
TASKS_PER_WORKER = 4             # enough for the workers to finish together
MAX_CHUNK = 5_000                # rows held in memory at once by a chunk (~10 MB)


def cores():
    """The cores this process may run on (the local cluster's workers by default)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:      # not on Linux
        return max(1, os.cpu_count() or 1)


def free_cores():
    """The cores other processes leave free: cores() less the 1-minute load average without this
    process's own 1 (at least 1). On a machine shared with other jobs a cluster gains only those:
    at load 4 on 2 cores, a local cluster's 100,000 cases took 65 s where one process takes 35 s."""
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):     # no load average here: assume the cores are free
        return float(cores())
    return max(1.0, min(float(cores()), cores() - max(0.0, load - 1.0)))


def cluster_pays(seconds_per_case, cases, workers, start_up=LOCAL_START_UP_SECONDS):
    """Whether `cases` finish sooner on `workers` processes that first need `start_up` seconds
    than here: start_up + T / w < T, with w no more than the free cores that run them."""
    w = min(workers, free_cores())
    serial = seconds_per_case * cases
    return w > 1 and start_up + serial / w < serial


def serial_chunk(seconds_per_case, batch=None):
    """Cases per chunk in this process: `batch` if given, else SERIAL_CHUNK_SECONDS of work."""
    if batch:
        return int(batch)
    return _bounded(SERIAL_CHUNK_SECONDS / max(seconds_per_case, 1e-9))


def task_chunk(cases, workers, seconds_per_case=None, batch=None):
    """Cases per dask task: `batch` if given, else TASKS_PER_WORKER tasks per worker, each no
    more than TASK_SECONDS of work at the measured rate (when there is one)."""
    if batch:
        return int(batch)
    size = math.ceil(cases / (TASKS_PER_WORKER * max(1, workers)))
    if seconds_per_case:
        size = min(size, TASK_SECONDS / seconds_per_case)
    return _bounded(size)


def _bounded(size):
    return int(min(MAX_CHUNK, max(1, size)))
