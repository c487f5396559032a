# SPDX-License-Identifier: BSD-2-Clause
"""Fixtures shared by the FMU tests: the built FMU, found where run.sh builds it; and the
temporary directory of the whole session, checked at its end for what the harness left."""
import os
import pathlib
import shutil
import tempfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]

# The suite's own temporary directory (inherited by every command it starts), so that what the
# harness leaves behind is this run's and nobody else's on a shared machine.
SESSION_TMP = pathlib.Path(tempfile.mkdtemp(prefix="pytest-painleve-tmp-"))
os.environ["TMPDIR"] = str(SESSION_TMP)
tempfile.tempdir = None         # gettempdir() reads TMPDIR again


def leftovers():
    """The harness's temporary files and directories (painleve-*) in the session's temporary directory."""
    return sorted(p.name for p in SESSION_TMP.glob("painleve-*"))


@pytest.fixture(scope="session", autouse=True)
def nothing_left_behind():
    """After the whole suite (failed runs, interrupted sweeps, FMUs that do not load included), the
    harness has removed every painleve-* file and directory it made: an error at teardown otherwise."""
    yield
    import gc
    gc.collect()                # instances whose owners the tests dropped
    left = leftovers()
    if not left:
        shutil.rmtree(SESSION_TMP, ignore_errors=True)
    assert not left, f"left in {SESSION_TMP}: {left}"


def built_fmu(*parts):
    """The path of an FMU the build made under build/ (a test fails, naming it, if it is missing)."""
    path = ROOT / "build" / pathlib.Path(*parts)
    if not path.exists():
        pytest.fail(f"{path} is missing: `bash run.sh test` builds it before running the tests")
    return str(path)


@pytest.fixture(scope="session")
def fmu_path():
    return built_fmu("PainleveRod.fmu")


@pytest.fixture(scope="session")
def fmu3_path():
    """The same model as an FMI 3.0 FMU."""
    return built_fmu("fmi3", "PainleveRod.fmu")


@pytest.fixture(scope="session")
def si_fmu_path():
    """The rod in SI units with inputs (fmu_src/models/PainleveRodSI)."""
    return built_fmu("PainleveRodSI.fmu")


@pytest.fixture(scope="session")
def arm_path():
    """The two-link arm on the contact core (fmu_src/models/TwoLinkArm)."""
    return built_fmu("TwoLinkArm.fmu")


@pytest.fixture(scope="session")
def arm3_path():
    """The same arm as an FMI 3.0 FMU."""
    return built_fmu("fmi3", "TwoLinkArm.fmu")


@pytest.fixture(scope="session")
def table_path():
    """The shaker table (fmu_src/models/ShakerTable)."""
    return built_fmu("ShakerTable.fmu")


@pytest.fixture(scope="session")
def si_fmu3_path():
    """The rod in SI units as an FMI 3.0 FMU."""
    return built_fmu("fmi3", "PainleveRodSI.fmu")


@pytest.fixture(scope="session")
def table3_path():
    """The shaker table as an FMI 3.0 FMU."""
    return built_fmu("fmi3", "ShakerTable.fmu")


@pytest.fixture(scope="session")
def loaded(fmu_path):
    """The built FMU loaded once by the harness (extracted; raw instances from .instantiate)."""
    from painleve.fmu.experiment import Experiment
    with Experiment(fmu_path) as experiment:
        yield experiment


@pytest.fixture
def ran(monkeypatch):
    """The (interface, case) of every painleve.fmu.body.Body.run, in order: the one runner of every
    body FMU, which the tests of validate and sweep check their cases go through."""
    from painleve.fmu.body import Body
    seen = []
    run = Body.run

    def recorded(body, case, *args, **kwargs):
        seen.append((body.fmi_type, case))
        return run(body, case, *args, **kwargs)
    monkeypatch.setattr(Body, "run", recorded)
    return seen
