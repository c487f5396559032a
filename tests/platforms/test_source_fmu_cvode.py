# SPDX-License-Identifier: BSD-2-Clause
"""A source FMU that builds Co-Simulation anywhere. Every FMU the build makes
(build/ and build/fmi3/, and the multi-platform ones of build/platforms/ and build/platforms/fmi3/,
`bash run.sh platforms`; tests/package/test_cvode_build_paths.py covers the sdist's wheel and the
build that downloads the sources itself) carries the CVODE subset of the
pinned SUNDIALS in sources/ (cmake/PainleveCvodeSources.cmake), listed in FMI 2.0's
<SourceFiles> and FMI 3.0's buildDescription.xml. Built as an importer builds it (fmpy's
build_platform_binary, with no options of ours) by a compiler that sees no SUNDIALS of the
system's (a sysroot without its headers, no SUNDIALS library linked), its Co-Simulation runs the
default experiment as the multi-platform FMU's binary does (the same SUNDIALS), and as its own
binary does to the solver's tolerance where that links Debian's SUNDIALS 6 (build/)."""
import pathlib
import re
import subprocess

import fmpy
import numpy as np
import pytest

from helpers.source_build import assert_cvode_compiled_in, cosimulation_from_sources

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILT = sorted(str(p.relative_to(ROOT / "build")) for pattern in ("*.fmu", "fmi3/*.fmu")
               for p in (ROOT / "build").glob(pattern))
FMUS = BUILT + [f"platforms/{f}" for f in BUILT]


def test_the_source_build_covers_every_fmu_the_build_makes():
    """FMUS is every FMU of build/, build/fmi3/, build/platforms/ and build/platforms/fmi3/, and those
    are both FMI versions of every model CMakeLists.txt adds."""
    made = sorted(str(p.relative_to(ROOT / "build")) for pattern in ("*.fmu", "fmi3/*.fmu", "platforms/*.fmu",
                                                                    "platforms/fmi3/*.fmu")
                  for p in (ROOT / "build").glob(pattern))
    assert sorted(FMUS) == made
    models = re.findall(r"^painleve_add_model\((\w+)[^)]*\bFMI3\b", (ROOT / "CMakeLists.txt").read_text(), re.M)
    expected = [f"{where}{model}.fmu" for where in ("", "fmi3/", "platforms/", "platforms/fmi3/") for model in models]
    assert models and sorted(FMUS) == sorted(expected)


def bundled_version():
    text = subprocess.run(["grep", "-h", "SUNDIALS_VERSION \"", str(ROOT / "build-platforms" / "x86_64-linux" /
                                                                    "cvode_bundle" / "sundials" / "sundials_config.h")],
                          capture_output=True, text=True, check=True).stdout
    return text.split('"')[1]


@pytest.mark.parametrize("fmu", FMUS)
def test_source_build_without_system_sundials_runs_cosimulation_like_the_shipped_binary(fmu, tmp_path, monkeypatch):
    built = ROOT / "build" / fmu
    shipped = ROOT / "build" / "platforms" / fmu.removeprefix("platforms/")
    assert built.is_file() and shipped.is_file(), f"{built} or {shipped} is missing (bash run.sh platforms)"
    monkeypatch.setenv("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    unzipped, binary = cosimulation_from_sources(built, tmp_path)
    md = fmpy.read_model_description(unzipped)
    assert_cvode_compiled_in(binary, bundled_version())
    a = fmpy.simulate_fmu(str(shipped), fmi_type="CoSimulation")
    b = fmpy.simulate_fmu(unzipped, fmi_type="CoSimulation")
    assert len(a) == len(b) > 10
    for name in a.dtype.names:
        x, y = a[name].astype(float), b[name].astype(float)
        scale = max(np.abs(x).max(), 1e-300)
        assert np.abs(x - y).max() <= 1e-12 * scale, name
    if built != shipped:
        # The plain build's own binary (Debian's SUNDIALS 6): the same run to the solver's
        # tolerance (the default experiment's), relative to each output's scale.
        md_tolerance = float(md.defaultExperiment.tolerance or 1e-6)
        c = fmpy.simulate_fmu(str(built), fmi_type="CoSimulation")
        assert len(c) == len(b)
        worst = {}
        for name in c.dtype.names:
            x, y = c[name].astype(float), b[name].astype(float)
            worst[name] = np.abs(x - y).max() / max(np.abs(x).max(), 1e-300)
        print(fmu, "own binary (SUNDIALS 6) against the source build:", max(worst.values()))
        assert max(worst.values()) <= 100 * md_tolerance, worst
