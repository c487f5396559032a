# SPDX-License-Identifier: BSD-2-Clause
"""Where a sweep runs (sweep.plan: this process, or a local dask cluster after a first chunk
here) and in what chunks never changes its numbers: every path gives the rows of one serial
chunk bit for bit, and the FMU's w at the return still falls on Theorem 1's e. The plan's own
rule: the cluster only when start-up + T / workers < T, a few bounded chunks per worker."""
import math

import numpy as np
import pandas as pd
import pytest

from painleve.sweep import plan
from painleve.sweep.run import run_sweep
from painleve.sweep.spec import SweepSpec
from painleve.sweep.store import ResultStore

SPEC = SweepSpec.from_texts({"theta0": "0.6:1.2:6", "phi0": "0.5,1.3", "epsilon": "1e-5,1e-3", "delta": "0,1"})


def sweep(path, fmu_path, **how):
    said = []
    result = run_sweep(SPEC, fmu_path, path, fmi_type="CoSimulation", progress=False, say=said.append, **how)
    assert result.ran == SPEC.total == 48
    return ResultStore(path).read(), said


def test_every_path_of_a_sweep_gives_the_rows_of_one_serial_chunk_bit_for_bit(fmu_path, tmp_path, monkeypatch):
    monkeypatch.setattr(plan, "free_cores", lambda: 2.0)   # the decision as on an idle 2-core machine
    serial, _ = sweep(tmp_path / "serial.parquet", fmu_path, serial=True, batch=48)
    here, said_here = sweep(tmp_path / "here.csv", fmu_path, batch=5, start_up=math.inf)
    cluster, said_cluster = sweep(tmp_path / "cluster.parquet", fmu_path, batch=7, start_up=0.0)
    assert said_here == []                                  # the probe of 5, then chunks of 5, all here
    assert len(said_cluster) == 1 and "local cluster with 2 worker(s)" in said_cluster[0]
    assert list(serial["id"]) == list(range(48))
    for rows in (here, cluster):
        pd.testing.assert_frame_equal(serial, rows, check_exact=True)
    fine = serial[(serial["status"] == "ok") & (serial["theorem"] == 1) & (serial["epsilon"] == 1e-5)]
    assert len(fine) >= 8 and np.all(np.abs(fine["w_error"] / fine["e"]) < 0.01)


def test_the_cluster_only_when_it_finishes_sooner_despite_its_start_up(monkeypatch):
    monkeypatch.setattr(plan, "free_cores", lambda: 2.0)
    # On two workers after 4 s of start-up: 4 + T/2 < T beyond T = 8 s of work in one process.
    assert not plan.cluster_pays(120e-6, 10_000, 2, start_up=4.0)          # 1.2 s
    assert not plan.cluster_pays(100e-6, 79_000, 2, start_up=4.0)          # 7.9 s
    assert plan.cluster_pays(100e-6, 81_000, 2, start_up=4.0)              # 8.1 s
    assert not plan.cluster_pays(100e-6, 79_000, 8, start_up=4.0)          # 8 workers share 2 cores: as 2
    assert not plan.cluster_pays(100e-6, 81_000, 1, start_up=0.0)          # one worker is no faster
    monkeypatch.setattr(plan, "free_cores", lambda: 1.0)   # one core, or two with another job on one
    assert not plan.cluster_pays(1e-3, 10**7, 8, start_up=4.0)
    monkeypatch.setattr(plan, "free_cores", lambda: 1.5)   # half a core more: 4 + T/1.5 < T beyond T = 12 s
    assert not plan.cluster_pays(1e-4, 119_000, 2, start_up=4.0) and plan.cluster_pays(1e-4, 121_000, 2, start_up=4.0)


def test_the_free_cores_are_the_cores_less_the_load_of_other_processes(monkeypatch):
    monkeypatch.setattr(plan, "cores", lambda: 2)
    for load, free in ((0.3, 2.0), (1.0, 2.0), (1.5, 1.5), (4.0, 1.0)):
        monkeypatch.setattr(plan.os, "getloadavg", lambda load=load: (load, load, load))
        assert plan.free_cores() == free


@pytest.mark.parametrize("cases, workers, per_case, batch, size", [
    (10_000, 2, None, None, 1250),          # 4 tasks per worker
    (10_000, 2, 120e-6, None, 1250),        # each 0.15 s of work
    (10_000, 2, 0.01, None, 500),           # at most 5 s of work a task
    (10**7, 2, 1e-6, None, 5000),           # at most 5,000 rows held at once
    (3, 4, None, None, 1),
    (10_000, 2, 0.01, 7, 7),                # --batch given
])
def test_a_dask_task_is_a_few_per_worker_and_bounded(cases, workers, per_case, batch, size):
    assert plan.task_chunk(cases, workers, per_case, batch) == size


def test_a_chunk_here_is_half_a_second_of_work_unless_given():
    assert plan.serial_chunk(1e-3) == 500 and plan.serial_chunk(1e-2) == 50
    assert plan.serial_chunk(1e-7) == 5000 and plan.serial_chunk(10.0) == 1 and plan.serial_chunk(1e-3, batch=7) == 7
