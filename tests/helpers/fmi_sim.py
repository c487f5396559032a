# SPDX-License-Identifier: BSD-2-Clause
"""fmi-sim (crates.io, Rust): a second FMI 2.0 importer, independent of fmpy.

`bash run.sh test` installs it into .tools/. Its Model Exchange is forward Euler
with the step equal to the output interval (stop/500 unless given), events found
by the indicators' signs at step ends; its Co-Simulation calls fmi2DoStep once per
output interval, so the FMU's own CVODE does the integrating.
"""
import pathlib
import subprocess

import numpy as np

from conftest import ROOT

FMI_SIM = ROOT / ".tools" / "bin" / "fmi-sim"
INTERFACES = {"ME": "model-exchange", "CS": "co-simulation"}


def run_fmi_sim(fmu_path, tmp_path, interface, *, start_values=None, stop_time=None, output_interval=None):
    """Runs fmi-sim on the FMU; the result as a structured array of every variable."""
    if not FMI_SIM.exists():
        raise FileNotFoundError(f"{FMI_SIM} is missing: `bash run.sh test` installs fmi-sim")
    out = tmp_path / f"fmi_sim_{interface}.csv"
    cmd = [str(FMI_SIM), "--model", str(fmu_path), "-o", str(out), INTERFACES[interface], "--print-all"]
    for name, value in (start_values or {}).items():
        cmd += ["--init-values", f"{name}={value!r}"]
    if stop_time is not None:
        cmd += ["-f", repr(stop_time)]
    if output_interval is not None:
        cmd += ["--output-interval", repr(output_interval)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({done.returncode}): {done.stderr[:2000]}")
    rows = np.genfromtxt(out, delimiter=",", names=True, dtype=None, encoding=None)
    result = np.zeros(rows.shape, dtype=[(n, float) for n in rows.dtype.names])
    for name in rows.dtype.names:
        if rows[name].dtype.kind in "USO":      # a Boolean column: true, false
            result[name] = [str(c).strip().lower() == "true" for c in rows[name]]
        else:
            result[name] = rows[name]
    return result


def fmi3_fmu_fmi_sim_can_read(fmu3_path, tmp_path, nominals=2):
    """A copy of the FMI 3.0 FMU that fmi-sim 0.7.0 (fmi-schema 0.8.0) parses.

    Its Float64 variable element has no `nominal`, `unit` or `quantity` attribute
    (FMI 3.0's fmi3Variable.xsd has both: RealVariableAttributes), so it refuses
    the FMU with 'unknown field "unit" (or another) in element "FmiFloat64"'.
    The copy is the same FMU with those attributes left out of
    modelDescription.xml: the binary is untouched, units are for people, and the
    nominals only serve an importer's error control, which fmi-sim does not have
    (fixed-step Euler; in Co-Simulation the FMU's CVODE takes its nominals from
    the model, not from the XML). `nominals`: how many the model declares (PainleveRod
    y and w, ShakerTable position and velocity, PainleveRodSI none)."""
    import re
    import zipfile

    out = tmp_path / (pathlib.Path(fmu3_path).stem + "3_for_fmi_sim.fmu")
    with zipfile.ZipFile(fmu3_path) as src, zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                text, n = re.subn(r' nominal="[^"]*"', "", data.decode())
                assert n == nominals, f"expected {nominals} nominals, found {n}"
                text = re.sub(r' unit="[^"]*"', "", text)
                text = re.sub(r'(<Float64 [^>]*?) quantity="[^"]*"', r"\1", text)
                data = text.encode()
            dst.writestr(item, data)
    return out
