# SPDX-License-Identifier: BSD-2-Clause
"""libcosim and ecos run PainleveRod.fmu from a system structure file, two instances
at once: an OspSystemStructure.xml (libcosim; one rod with a parameter set in the
file), an SSP SystemStructure.ssd as a directory (libcosim) and as an .ssp archive
(ecos). The rod has no inputs, so nothing is connected: each instance must give what
fmpy's Co-Simulation of the same rod gives, to the FMU's solver tolerance."""
import shutil
import zipfile

import fmpy
import pytest

RTOL = 1e-6             # the FMU's CVODE tolerance in the default experiment
STEP = 2e-4             # fmpy's default grid for the default experiment: stop/500
STOP = 0.1

OSP = """<?xml version="1.0" encoding="UTF-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure" version="0.1">
  <StartTime>0.0</StartTime>
  <BaseStepSize>{step}</BaseStepSize>
  <Algorithm>fixedStep</Algorithm>
  <Simulators>
    <Simulator name="rod1" source="PainleveRod.fmu"/>
    <Simulator name="rod2" source="PainleveRod.fmu">
      <InitialValues>
        <InitialValue variable="delta"><Real value="0.5"/></InitialValue>
      </InitialValues>
    </Simulator>
  </Simulators>
</OspSystemStructure>
"""

SSD = """<?xml version="1.0" encoding="UTF-8"?>
<ssd:SystemStructureDescription xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription"
    version="1.0" name="two rods">
  <ssd:System name="floor">
    <ssd:Elements>
      <ssd:Component name="rod1" source="resources/PainleveRod.fmu"/>
      <ssd:Component name="rod2" source="resources/PainleveRod.fmu"/>
    </ssd:Elements>
  </ssd:System>
  <ssd:DefaultExperiment startTime="0" stopTime="{stop}"/>
</ssd:SystemStructureDescription>
"""


@pytest.fixture(scope="module")
def fmpy_w(fmu_path):
    """w at t = 0.1 in fmpy's Co-Simulation, by delta."""
    def w(delta):
        r = fmpy.simulate_fmu(fmu_path, fmi_type="CoSimulation", start_values={"delta": delta},
                              stop_time=STOP, output_interval=STEP, output=["w"])
        return float(r["w"][-1])
    return {1.0: w(1.0), 0.5: w(0.5)}


def ssp_directory(fmu_path, tmp_path):
    (tmp_path / "resources").mkdir(parents=True)
    shutil.copy(fmu_path, tmp_path / "resources" / "PainleveRod.fmu")
    (tmp_path / "SystemStructure.ssd").write_text(SSD.format(stop=STOP))
    return tmp_path


def libcosim_w(execution):
    """Runs a libcosim execution to STOP; w of each instance, by name."""
    from libcosimpy.CosimObserver import CosimObserver
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    assert execution.simulate_until(round(STOP * 1e9))          # nanoseconds
    assert execution.status().current_time == round(STOP * 1e9)
    return {s.name.decode(): observer.last_real_values(s.index, [7])[0] for s in execution.slave_infos()}


def close(w, expected):
    return w > 0 and abs(w - expected) <= 10 * RTOL * (1 + abs(expected))


def test_libcosim_runs_two_rods_from_an_osp_system_structure_with_a_parameter_set_in_it(fmu_path, tmp_path, fmpy_w):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    log_output_level(CosimLogLevel.WARNING)
    shutil.copy(fmu_path, tmp_path / "PainleveRod.fmu")
    (tmp_path / "OspSystemStructure.xml").write_text(OSP.format(step=STEP))
    w = libcosim_w(CosimExecution.from_osp_config_file(str(tmp_path / "OspSystemStructure.xml")))
    assert set(w) == {"rod1", "rod2"}
    assert close(w["rod1"], fmpy_w[1.0]) and close(w["rod2"], fmpy_w[0.5]), w
    assert abs(w["rod1"] - w["rod2"]) > 1e-3        # the parameter reached rod2 only


def test_libcosim_runs_two_rods_from_an_ssp_system_structure(fmu_path, tmp_path, fmpy_w):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    log_output_level(CosimLogLevel.WARNING)
    w = libcosim_w(CosimExecution.from_ssp_file(str(ssp_directory(fmu_path, tmp_path)), round(STEP * 1e9)))
    assert set(w) == {"rod1", "rod2"}
    assert close(w["rod1"], fmpy_w[1.0]) and close(w["rod2"], fmpy_w[1.0]), w


def test_ecos_runs_two_rods_from_an_ssp_archive(fmu_path, tmp_path, fmpy_w):
    from ecospy import EcosLib, EcosSimulation
    EcosLib.set_log_level("warn")
    source = ssp_directory(fmu_path, tmp_path / "ssp")
    archive = tmp_path / "two_rods.ssp"
    with zipfile.ZipFile(archive, "w") as ssp:
        for name in ("SystemStructure.ssd", "resources/PainleveRod.fmu"):
            ssp.write(source / name, name)
    with EcosSimulation(ssp_path=str(archive), step_size=STEP) as sim:
        assert sim.init()
        sim.step(round(STOP / STEP))
        assert sim.get_time() == pytest.approx(STOP, rel=1e-12)
        w = {name: sim.get_real(f"{name}::w") for name in ("rod1", "rod2")}
        sim.terminate()
    assert close(w["rod1"], fmpy_w[1.0]) and close(w["rod2"], fmpy_w[1.0]), w
