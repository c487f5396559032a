# SPDX-License-Identifier: BSD-2-Clause
"""A sweep's worker frees its FMU instances only when no batch is using them: the driver's
clean-up (client.run(_close_bodies)) runs in another thread of the worker than the batch,
and an instance freed while CVode integrates in it corrupts the heap (an interrupted sweep's
worker printed glibc's "free(): corrupted unsorted chunks")."""
import threading

from painleve.sweep import run as sweep


class Recorder:
    def __init__(self):
        self.closed = False

    def close(self):
        self.closed = True


def test_clean_up_leaves_an_instance_a_running_batch_uses_and_frees_it_after(monkeypatch):
    experiment = Recorder()
    monkeypatch.setattr(sweep, "_BODIES", {("digest", "ModelExchange"): experiment})
    running, finish = threading.Event(), threading.Event()

    def batch():                         # what run_batch holds while it integrates
        with sweep._IN_USE:
            running.set()
            finish.wait(10)

    worker = threading.Thread(target=batch)
    worker.start()
    running.wait(10)
    sweep._close_bodies()           # the driver's clean-up, mid-batch
    assert not experiment.closed and sweep._BODIES
    finish.set()
    worker.join(10)
    sweep._close_bodies()           # the same once the batch is done
    assert experiment.closed and not sweep._BODIES
