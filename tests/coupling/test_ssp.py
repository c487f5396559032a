# SPDX-License-Identifier: BSD-2-Clause
"""The SSP archive generator (painleve.coupling.ssp), its validation (painleve.coupling.ssp_check: fmpy's schema
check, fmpy's FMU validation and the cross-checks fmpy leaves out) and the three masters that
run it (painleve.coupling.masters), on two PainleveRod instances (no inputs: nothing is connected).
Each master must give each rod what fmpy's Co-Simulation of that rod alone gives, to the
FMU's solver tolerance, with the start value bound in the archive reaching its rod only."""
import zipfile

import fmpy
import numpy as np
import pytest

from painleve.coupling import masters
from painleve.coupling.ssp import SSD_NAME, Component, Connection, start_values, write_ssp
from painleve.coupling.ssp_check import check_ssp

RTOL = 1e-6             # the FMU's CVODE tolerance in its default experiment
STEP, STOP = 2e-4, 0.1  # its default grid


@pytest.fixture(scope="module")
def two_rods(fmu_path, tmp_path_factory):
    comps = [Component("rod1", fmu_path, outputs=("w", "F_N")),
             Component("rod2", fmu_path, {"delta": 0.5}, outputs=("w",))]
    return write_ssp(tmp_path_factory.mktemp("ssp") / "two_rods.ssp", "two_rods", comps, stop_time=STOP)


@pytest.fixture(scope="module")
def alone(fmu_path):
    """w on the grid, fmpy's Co-Simulation of one rod, by delta."""
    def w(delta):
        r = fmpy.simulate_fmu(fmu_path, fmi_type="CoSimulation", start_values={"delta": delta},
                              stop_time=STOP, output_interval=STEP, output=["w"])
        return r["w"][1:]
    return {1.0: w(1.0), 0.5: w(0.5)}


def test_the_archive_holds_the_ssd_and_one_copy_of_the_fmu(two_rods):
    with zipfile.ZipFile(two_rods) as z:
        assert sorted(z.namelist()) == [SSD_NAME, "resources/PainleveRod.fmu"]
    assert start_values(two_rods) == {"rod1": {}, "rod2": {"delta": 0.5}}


def test_the_generated_archive_is_valid(two_rods):
    assert check_ssp(two_rods) == []


def test_the_check_finds_what_the_standard_forbids(fmu_path, tmp_path):
    bad = write_ssp(tmp_path / "bad.ssp", "bad",
                    [Component("rod1", fmu_path, {"delta": -1.0, "F_N": 2.0}, outputs=("w",)),
                     Component("rod2", fmu_path, outputs=("F_N",))],
                    [Connection(("rod1", "w"), ("rod2", "F_N"))])
    problems = check_ssp(bad)
    assert any("rod1.w -> rod2.F_N" in p and "from an output to an input" in p for p in problems), problems
    assert any(p.startswith("rod1.delta = -1.0: outside [0,") for p in problems), problems      # min 0
    assert any(p.startswith("rod1.F_N: bound, but its start value cannot be set") for p in problems), problems
    assert len(problems) == 3, problems
    # and what the schema forbids: a connection without its start connector's name
    with zipfile.ZipFile(bad) as z:
        ssd = z.read(SSD_NAME).decode().replace('startConnector="w" ', "")
    broken = tmp_path / "broken.ssp"
    with zipfile.ZipFile(broken, "w") as z:
        z.writestr(SSD_NAME, ssd)
        z.write(fmu_path, "resources/PainleveRod.fmu")
    problems = check_ssp(broken)
    assert len(problems) == 1 and "startConnector" in problems[0], problems


@pytest.mark.parametrize("master", masters.MASTERS)
def test_each_master_runs_both_rods_with_the_bound_start_value(master, two_rods, alone):
    r = masters.run(master, two_rods, STOP, STEP, ["rod1.w", "rod2.w"])
    np.testing.assert_allclose(r["time"], STEP * np.arange(1, len(r) + 1), rtol=0, atol=1e-12)
    assert len(r) == round(STOP / STEP)
    for name, delta in (("rod1.w", 1.0), ("rod2.w", 0.5)):
        gap = np.max(np.abs(r[name] - alone[delta]))
        assert gap <= 10 * RTOL * (1 + np.max(np.abs(alone[delta]))), f"{master}: {name} off by {gap:.3g}"
    assert abs(r["rod1.w"][-1] - r["rod2.w"][-1]) > 1e-3          # delta reached rod2 only


def test_a_grid_that_does_not_end_at_the_stop_time_is_refused(two_rods):
    with pytest.raises(ValueError, match="not a whole number of steps"):
        masters.run("fmpy", two_rods, STOP, 3e-4, ["rod1.w"])
