# SPDX-License-Identifier: BSD-2-Clause
"""The coupled study with the FMI 3.0 FMUs (build/fmi3/PainleveRodSI.fmu on build/fmi3/ShakerTable.fmu):
in every master that loads FMI 3.0 (masters.FMI3_MASTERS: ecos) the momentum balance
closes as with FMI 2.0 and the coupled trajectory is the FMI 2.0 one (the same model cores and
solver under either layer: to round-off); the masters that do not load it refuse it with the reason
docs/coupling.md gives (should one learn FMI 3.0, its test fails and it joins FMI3_MASTERS)."""
import zipfile

import numpy as np
import pytest

from painleve.coupling import masters
from painleve.coupling.coupled import Setup, impulse_on_rod, momentum_balance, run_coupled, write_coupled_ssp
from painleve.coupling.ssp_check import check_ssp

STOP = 0.45                     # painleve couple's default run: the IWC, flights, landings on the shaking table


def test_the_fmi3_archive_is_clean_and_types_its_connectors_as_ssp_1_0_does(si_fmu3_path, table3_path, tmp_path):
    # SSP 1.0 knows ssc:Real and ssc:Integer, not FMI 3.0's Float64 and Int32 (SystemStructureCommon.xsd)
    ssp = write_coupled_ssp(tmp_path / "coupled.ssp", si_fmu3_path, table3_path, Setup(), stop_time=STOP)
    assert check_ssp(ssp) == []
    with zipfile.ZipFile(ssp) as z:
        ssd = z.read("SystemStructure.ssd").decode()
    assert "ssc:Real" in ssd and "Float64" not in ssd


@pytest.mark.parametrize("h", [1e-3, 1e-4])
@pytest.mark.parametrize("master", masters.FMI3_MASTERS)
def test_the_mean_coupling_conserves_momentum_with_fmi3_fmus(master, h, si_fmu3_path, table3_path):
    """The table holds in step k the rod's mean over step k - 1: the vertical momentum of rod and
    table changes by the external impulses plus the one in flight, to rounding."""
    s = Setup()
    r = run_coupled(si_fmu3_path, table3_path, s, stop_time=STOP, step=h, master=master)
    assert len(r) == round(STOP / h)
    np.testing.assert_allclose(r["table.F_N"][1:], r["rod.F_N_mean"][:-1], rtol=1e-15, atol=0)
    b = momentum_balance(r, s, h)
    assert b.contact == pytest.approx(impulse_on_rod(r, s), rel=1e-12)
    assert b.contact > 0.5                      # the IWC's impulse alone is 0.85 N s
    assert abs(b.residual) <= 1e-9 * b.contact, b


@pytest.mark.parametrize("coupling, h", [("mean", 1e-3), ("mean", 1e-4), ("instantaneous", 1e-4)])
@pytest.mark.parametrize("master", masters.FMI3_MASTERS)
def test_the_fmi3_coupled_trajectory_is_the_fmi2_one(master, coupling, h, si_fmu_path, table_path, si_fmu3_path,
                                                      table3_path):
    s = Setup(table=dict(F0=80.0))
    two = run_coupled(si_fmu_path, table_path, s, stop_time=STOP, step=h, master=master, coupling=coupling)
    three = run_coupled(si_fmu3_path, table3_path, s, stop_time=STOP, step=h, master=master, coupling=coupling)
    assert two.dtype.names == three.dtype.names and len(two) == len(three)
    for name in two.dtype.names:
        scale = max(1.0, float(np.max(np.abs(two[name]))))
        np.testing.assert_allclose(three[name], two[name], rtol=1e-12, atol=1e-12 * scale, err_msg=name)
    assert np.ptp(three["table.position"]) > 1e-4 and np.max(three["rod.F_N"]) > 100     # it shook and hit


# What each master that does not load FMI 3.0 says when given the FMI 3.0 archive (masters.NO_FMI3).
REFUSALS = {"fmpy": r"Cannot find shared library .*/binaries/linux64/",      # an FMU2Slave on an FMI 3.0 FMU
            "libcosim": r"Unsupported FMI version"}


@pytest.mark.parametrize("master", [m for m in masters.MASTERS if m not in masters.FMI3_MASTERS])
def test_the_other_masters_do_not_load_fmi3(master, si_fmu3_path, table3_path):
    assert master in masters.NO_FMI3 and master in REFUSALS
    with pytest.raises(RuntimeError, match=REFUSALS[master]):
        run_coupled(si_fmu3_path, table3_path, Setup(), stop_time=1e-3, step=1e-3, master=master)

