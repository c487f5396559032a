# SPDX-License-Identifier: BSD-2-Clause
"""Sweeps of IWC cases: in this process, or on dask when that finishes sooner.

Where a sweep runs, and in what chunks, is sweep.plan's: by default its first
chunk runs here, and the rest here too unless a local cluster would finish it
sooner despite its start-up; `--workers` or `--scheduler` choose dask, `--serial`
this process. On dask the driver submits a few large chunks per worker: a local
cluster on this machine, or any scheduler by address, unchanged. Each process
keeps one `Body` per FMU and interface (fmu.body, the runner of every body
FMU: one unzip, one instance, reset between cases, fmpy's fast loop); the FMU's bytes are sent to the workers once, so they
need the `painleve` package but not the file. Results are written as chunks
finish (see `sweepstore`), so an interrupted sweep resumes without recomputing
what was written. A case's numbers do not depend on where or in which chunk it ran."""
import atexit
import contextlib
import hashlib
import logging
import os
import pathlib
import signal
import sys
import tempfile
import threading
import time
from dataclasses import dataclass

import numpy as np

from ..experiments.outcome import SimulationError, w_error
from ..fmu.body import Body
from ..theory import analytic as an
from ..theory.predict_many import predict_many
from . import plan
from .body import BodySweep
from .store import ResultStore, as_frame


@dataclass(frozen=True)
class FmuBlob:
    """An FMU's bytes and their SHA-256, the form in which workers receive it."""
    digest: str
    data: bytes

    @classmethod
    def read(cls, path):
        data = pathlib.Path(path).read_bytes()
        return cls(hashlib.sha256(data).hexdigest(), data)


_BODIES = {}   # in each process: (FMU digest, fmi_type) -> Body
# Held while a batch runs: a worker's batch runs in its executor thread, and the driver's
# clean-up (client.run(_close_bodies)) in another; freeing an FMU instance that CVode is
# integrating in the first corrupts the heap (glibc: "free(): corrupted unsorted chunks",
# seen when a sweep is interrupted with batches in flight).
_IN_USE = threading.Lock()


def body_for(blob, fmi_type, tmp_dir=None):
    """This process's Body for the FMU `blob`, created on first use. The FMU's bytes go to a
    painleve-* directory only for the Body's Experiment to extract them, and the directory goes at once
    (the Experiment keeps its own extracted copy, which close() removes). `tmp_dir`: where, if it
    exists here (the local cluster's workers: the driver removes it even if they are killed)."""
    key = (blob.digest, fmi_type)
    if key not in _BODIES:
        tmp_dir = tmp_dir if tmp_dir and os.path.isdir(tmp_dir) else None
        with tempfile.TemporaryDirectory(prefix="painleve-", dir=tmp_dir) as tmp:
            path = os.path.join(tmp, "PainleveRod.fmu")
            with open(path, "wb") as f:
                f.write(blob.data)
            _BODIES[key] = Body(path, fmi_type=fmi_type, tmp_dir=tmp_dir)
    return _BODIES[key]


@atexit.register
def _close_bodies():
    """Frees this process's FMU instances and extracted files, unless a batch is running: then
    they are in use, and go when the process ends (a local worker's files with the driver's
    directory)."""
    if not _IN_USE.acquire(blocking=False):
        return
    try:
        for body in _BODIES.values():
            body.close()
        _BODIES.clear()
    finally:
        _IN_USE.release()


def predictions(case):
    """The paper's predictions for a case as result columns, NaN where its hypotheses fail."""
    p = an.predict(case)
    return dict(theorem=p.theorem, e=p.e, predicted_w=p.e * case.v0, predicted_phi=p.phi, w1_star=p.w1_star,
                predicts_iwc=p.iwc, time_scale=p.time_scale)


# A row's outcome columns (store.COLUMNS, iwc to events) for a case that did not run: missing.
NOT_RUN = (None,) + (float("nan"),) * 9 + (None,)


def case_row(body, case, case_id, p):
    """One result row, a tuple in store.COLUMNS' order: the case, its predictions `p` (predict's),
    what the FMU did (status 'ok': Body.run, the run of every body's case), or why it did not run
    ('outside' the theorems' hypotheses, or 'failed' with the FMU's reason)."""
    try:
        case.check()
    except an.HypothesisError as err:
        return _row(case_id, "outside", str(err), case, p, None)
    try:
        outcome = body.run(case, closed_form=p)
    except SimulationError as err:
        return _row(case_id, "failed", str(err), case, p, None)
    except Exception as err:   # one bad case must not lose its batch
        return _row(case_id, "failed", f"{type(err).__name__}: {err}", case, p, None)
    return _row(case_id, "ok", "", case, p, outcome)


def _row(case_id, status, message, c, p, o):
    """The row's tuple; the errors as Outcome's (w/v0 - e, phi - predicted phi, theta - theta0)."""
    head = (case_id, status, message, c.theta0, c.phi0, c.delta, c.epsilon, c.v0, c.w10, c.alpha, c.mu, p.theorem)
    predicted = (p.e, p.e * c.v0, p.phi, p.w1_star, p.iwc)
    if o is None:
        return head + NOT_RUN + predicted + (float("nan"),) * 3 + (p.time_scale,)
    s = o.state
    return head + (o.iwc, s["w"], s["theta"], s["phi"], s["v"], o.t_return, o.compression, o.stick, o.lift_off,
                   o.flight_back, o.events) + predicted + (w_error(s["w"], c.v0, p.e), s["phi"] - p.phi,
                                                           s["theta"] - c.theta0, p.time_scale)


def run_batch(spec, ids, blob, fmi_type="ModelExchange", tmp_dir=None):
    """A batch of cases, on whichever process runs it: a typed DataFrame of rows. The rod's sweep
    (a SweepSpec): the predictions are the batch's over arrays (predict_many), handed to each case's
    run and row; a body's (sweep.body.BodySweep): its rows (BodySweep.frame)."""
    with _IN_USE:
        body = body_for(blob, fmi_type, tmp_dir)
        if isinstance(spec, BodySweep):
            return spec.frame(body, ids)
        cases = spec.cases(ids)
        return as_frame([case_row(body, case, i, p)
                         for i, case, p in zip(np.asarray(ids).tolist(), cases, predict_many(cases))])


@dataclass
class SweepResult:
    total: int
    skipped: int        # done before this run (resumed)
    ran: int
    seconds: float
    out: str


def _batches(remaining, size):
    for start in range(0, len(remaining), size):
        yield remaining[start:start + size]


def _progress(total, initial, enabled):
    from tqdm import tqdm
    return tqdm(total=total, initial=initial, unit="case", desc="sweep", disable=not enabled, file=sys.stderr,
                dynamic_ncols=True, mininterval=0.5, smoothing=0.05)


def run_sweep(spec, fmu_path, out, *, fmi_type="ModelExchange", scheduler=None, workers=None, batch=None,
              serial=False, progress=True, start_up=plan.LOCAL_START_UP_SECONDS,
              say=lambda text: print(text, file=sys.stderr)):
    """Runs every case of `spec` not yet in `out`; returns a SweepResult. Where (sweep.plan): in this
    process if `serial`; on the `scheduler`'s workers, or a local cluster of `workers`, when either is
    given; otherwise the first chunk here and the rest here or on a local cluster of the cores other
    jobs leave free, whichever finishes sooner (`start_up`: the cluster's start-up in seconds). `batch`: cases
    per chunk (default: sized by sweep.plan from the cases' cost). The numbers are the same on every path."""
    blob = FmuBlob.read(fmu_path)
    store = ResultStore(out)
    done = store.open({**spec.describe(), "fmu_sha256": blob.digest, "fmi_type": fmi_type})
    remaining = np.setdiff1d(np.arange(spec.total, dtype=np.int64), done)
    if len(done):
        say(f"resuming {out}: {len(done)} of {spec.total} cases already done, {len(remaining)} to run")
    start = time.monotonic()
    chosen = not serial and (scheduler is not None or workers is not None)
    # Connected before the progress bar starts: a scheduler that does not answer is one line, no bar.
    dask = _connect(scheduler, workers) if len(remaining) and chosen else None
    # The local cluster's workers extract the FMU in here, removed on every way out, even when
    # the workers are stopped before they could clean up (Ctrl-C); a scheduler's workers may
    # be on other machines and outlive the sweep: they clean up themselves (_close_bodies).
    with tempfile.TemporaryDirectory(prefix="painleve-sweep-") as work, \
            _progress(spec.total, len(done), progress) as bar:
        def here(ids):
            for chunk in ids:
                df = run_batch(spec, chunk, blob, fmi_type)
                store.append(df)
                bar.update(len(df))
        on_dask = dict(store=store, bar=bar, scheduler=scheduler, say=say, tmp_dir=None if scheduler else work)
        if not len(remaining):
            pass
        elif dask is not None:
            _run_on_dask(spec, remaining, blob, fmi_type, dask, batch=batch, **on_dask)
        else:
            # The probe's rate is its cases' alone: the FMU extracted before the clock, and the
            # first write (pyarrow's import, 0.2-0.5 s) after it.
            body_for(blob, fmi_type)
            probe, rest = remaining[:batch or plan.PROBE_CASES], remaining[batch or plan.PROBE_CASES:]
            t = time.monotonic()
            df = run_batch(spec, probe, blob, fmi_type)
            per_case = (time.monotonic() - t) / len(probe)
            store.append(df)
            bar.update(len(df))
            workers = max(2, int(plan.free_cores()))
            if not serial and len(rest) and plan.cluster_pays(per_case, len(rest), workers, start_up):
                _close_bodies()            # this process's instance: the workers have theirs
                _run_on_dask(spec, rest, blob, fmi_type, _connect(None, workers), batch=batch, per_case=per_case,
                             **on_dask)
            else:
                here(_batches(rest, plan.serial_chunk(per_case, batch)))
    return SweepResult(total=spec.total, skipped=len(done), ran=len(remaining),
                       seconds=time.monotonic() - start, out=str(out))


def _connect(scheduler, workers):
    from dask.distributed import Client, LocalCluster
    if scheduler:
        return Client(scheduler, timeout="10s"), None
    # The workers log CRITICAL only: a batch's failure reaches the driver through its future, and
    # what else a worker logs at ERROR is its lost connection when a Ctrl-C closes the cluster under
    # it (a heartbeat that finds the scheduler gone, seen on a loaded machine).
    with _workers_ignore_ctrl_c():
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                               silence_logs=logging.CRITICAL)
    return Client(cluster), cluster


@contextlib.contextmanager
def _workers_ignore_ctrl_c():
    """Worker processes started in here inherit SIGINT ignored: Ctrl-C in a terminal reaches
    the whole process group, and it is the driver that stops the workers, cleanly."""
    try:
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:          # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def _run_on_dask(spec, ids, blob, fmi_type, dask, *, store, bar, scheduler, say, batch=None, per_case=None,
                 tmp_dir=None):
    """The cases `ids` in chunks of `batch` (default: sweep.plan's, at `per_case` seconds a case if measured)."""
    from dask.distributed import as_completed
    client, cluster = dask
    try:
        n_workers = max(1, len(client.scheduler_info().get("workers", {})))
        say(f"dask: {'scheduler ' + scheduler if scheduler else 'local cluster'} with {n_workers} worker(s)")
        batches = _batches(ids, plan.task_chunk(len(ids), n_workers, per_case, batch))
        blob_future = client.scatter(blob, broadcast=True, hash=False)

        def submit(ids):
            return client.submit(run_batch, spec, ids, blob_future, fmi_type, tmp_dir, pure=False)
        # Keep a few batches per worker in flight: enough to stay busy, few enough to stop quickly.
        queue = as_completed([submit(ids) for _, ids in zip(range(3 * n_workers), batches)])
        for future in queue:
            df = future.result()
            store.append(df)
            bar.update(len(df))
            future.release()
            nxt = next(batches, None)
            if nxt is not None:
                queue.add(submit(nxt))
    except BaseException:
        # Interrupted with batches in flight: closing the cluster under them can make a pending
        # tornado callback fail on a closed connection, logged with a traceback that says nothing
        # to the user (what was written is kept; the CLI says how to resume).
        # The same for distributed's own ERROR lines about the connections it is closing.
        for name in ("tornado.application", "distributed"):
            logging.getLogger(name).setLevel(logging.CRITICAL)
        raise
    finally:
        try:    # each worker frees its FMU instance and extracted files (workers do not run atexit)
            client.run(_close_bodies)
        except Exception:
            pass
        client.close()
        if cluster is not None:
            cluster.close()
