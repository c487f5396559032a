# SPDX-License-Identifier: BSD-2-Clause
"""The source FMU as a tool builds it: every source in sources/ and in <SourceFiles>,
fmpy's own build of it (with and without CVODE), and the sources linked statically
twice into one program under two FMI2_FUNCTION_PREFIXes. The FMU carries the CVODE
subset of the pinned SUNDIALS (sundials_src/, tests/platforms/test_source_fmu_cvode.py
builds Co-Simulation from it); the builds here take it out first, as an FMU built
without the pinned sources has it (helpers.source_build.without_bundle)."""
import pathlib
import re
import subprocess
import zipfile
from xml.etree import ElementTree

import fmpy
import numpy as np
import pytest

from conftest import ROOT
from helpers.source_build import source_build, sundials_libraries, with_cvode

FMU_SRC = ROOT / "fmu_src"
# PainleveRod's folders, its own first, then the shared ones (the build's include path).
FOLDERS = [FMU_SRC / "models" / "PainleveRod", FMU_SRC / "models", FMU_SRC / "rod", FMU_SRC / "contact", FMU_SRC / "fmi",
           FMU_SRC / "common"]
GENERATED = ROOT / "build" / "generated" / "PainleveRod"
FMI_HEADERS = pathlib.Path(fmpy.__file__).parent / "c-code"
OUTPUTS = ["x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy", "mode", "contact"]


def fmi2_files(pattern):
    """The files of FOLDERS that match pattern, less the FMI 3.0 layer's."""
    return [p for folder in FOLDERS for p in sorted(folder.glob(pattern)) if not p.name.startswith("fmi3_")]


def default_experiment(fmu, fmi_type):
    return fmpy.simulate_fmu(fmu, fmi_type=fmi_type, output=OUTPUTS)


def test_source_files_are_every_source_for_both_interfaces(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        md = ElementTree.fromstring(z.read("modelDescription.xml"))
        me, cs = ([f.get("name") for f in md.findall(f"{i}/SourceFiles/File")] for i in ("ModelExchange", "CoSimulation"))
        own = [n for n in me if not n.startswith("sundials_src/")]
        assert me == cs and set(own) == {p.name for p in fmi2_files("*.c")}
        # Beside the model's own files (flat), only the CVODE subset: its sources in <SourceFiles>.
        files = [n[len("sources/"):] for n in z.namelist() if n.startswith("sources/") and not n.endswith("/")]
        flat = {n for n in files if "/" not in n} - {"cvode_bundled.h"}
        bundled_c = {n for n in files if n.startswith("sundials_src/") and n.endswith(".c")}
    headers = {p.name for p in fmi2_files("*.h")} | {"model_description.h", "model_dependencies.h"}
    assert flat == set(own) | headers
    assert bundled_c == set(me) - set(own) and "sundials_src/cvode.c" in bundled_c


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
def test_fmpy_compile_with_cvode_matches_the_cmake_build(fmu_path, tmp_path, fmi_type):
    unzipped = source_build(fmu_path, tmp_path, with_cvode(), bundled=False)
    a, b = default_experiment(fmu_path, fmi_type), default_experiment(unzipped, fmi_type)
    assert b["w"][-1] > 0 and b["contact"].any()
    for name in ("y", "w", "v", "phi", "energy"):
        np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-12, err_msg=name)


def test_fmpy_compile_without_cvode_runs_model_exchange_and_says_why_cosimulation_cannot(fmu_path, tmp_path):
    unzipped = source_build(fmu_path, tmp_path, bundled=False)
    assert default_experiment(unzipped, "ModelExchange")["w"][-1] > 0
    messages = []
    with pytest.raises(Exception):
        fmpy.simulate_fmu(unzipped, fmi_type="CoSimulation", logger=lambda *m: messages.append(m[-1]))
    assert any(b"without SUNDIALS CVODE" in m for m in messages), messages


def compile_with_prefix(prefix, out):
    """The sources as objects under FMI2_FUNCTION_PREFIX=prefix, in a static library."""
    objects = []
    for source in fmi2_files("*.c"):
        obj = out / f"{prefix}{source.stem}.o"
        subprocess.run(["cc", "-c", "-std=c99", "-O1", "-Wall", "-Wextra", "-Werror", f"-DFMI2_FUNCTION_PREFIX={prefix}",
                        "-DHAVE_CVODE", *(f"-I{folder}" for folder in FOLDERS), f"-I{GENERATED}", f"-I{FMI_HEADERS}",
                        str(source), "-o", str(obj)], check=True, capture_output=True, text=True)
        objects.append(obj)
    library = out / f"lib{prefix}.a"
    subprocess.run(["ar", "rcs", str(library), *map(str, objects)], check=True)
    return library


def test_two_prefixed_copies_link_into_one_program_and_run_side_by_side(fmu_path, tmp_path):
    libraries = [compile_with_prefix(p, tmp_path) for p in ("A_", "B_")]
    for prefix, library in zip(("A_", "B_"), libraries):
        symbols = subprocess.run(["nm", "-g", "--defined-only", str(library)], capture_output=True, text=True,
                                 check=True).stdout
        names = re.findall(r"^[0-9a-f]+ [A-Z] (\S+)$", symbols, re.M)
        assert names and [n for n in names if not n.startswith(prefix)] == [], "names without the prefix"
    program = tmp_path / "two_prefixes"
    subprocess.run(["cc", "-std=c99", "-Wall", "-Werror", f"-I{FMI_HEADERS}", f"-I{GENERATED}",
                    str(ROOT / "tests" / "c" / "two_prefixes.c"), *map(str, libraries), *sundials_libraries(), "-lm",
                    "-o", str(program)], check=True, capture_output=True, text=True)
    run = subprocess.run([str(program)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    w_a, w_b, w_alone = map(float, run.stdout.split())
    assert w_a == w_b == w_alone
    # fmpy's run of the shipped binary on the program's communication grid (100 steps to 0.1).
    fmpy_w = fmpy.simulate_fmu(fmu_path, fmi_type="CoSimulation", output_interval=1e-3, output=["w"])["w"][-1]
    assert w_a == pytest.approx(fmpy_w, rel=1e-12) and w_a > 0
