"""Fixtures shared by the FMU tests: the built FMU, found where run.sh builds it."""
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def fmu_path():
    path = ROOT / "build" / "PainleveRod.fmu"
    if not path.exists():
        pytest.fail(f"{path} is missing: `bash run.sh test` builds it before running the tests")
    return str(path)


@pytest.fixture(scope="session")
def fmu3_path():
    """The same model as an FMI 3.0 FMU."""
    path = ROOT / "build" / "fmi3" / "PainleveRod.fmu"
    if not path.exists():
        pytest.fail(f"{path} is missing: `bash run.sh test` builds it before running the tests")
    return str(path)


@pytest.fixture(scope="session")
def loaded(fmu_path):
    """The built FMU loaded once by the harness (extracted; raw instances from .instantiate)."""
    from painleve.experiment import Experiment
    with Experiment(fmu_path) as experiment:
        yield experiment
