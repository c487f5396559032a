# SPDX-License-Identifier: BSD-2-Clause
"""Every FMU shows its model's icon: model.png at the root of an FMI 2.0 FMU and
terminalsAndIcons/icon.png in an FMI 3.0 one (the places the standards name), the drawing
cmake/fmu_icons.py makes (fmu_src/models/NAME/icon.png, committed: the script run again gives
the same bytes)."""
import struct
import subprocess
import sys
import zipfile

import pytest

from conftest import ROOT

BUILD = ROOT / "build"
MODELS = ROOT / "fmu_src" / "models"
FMUS = sorted(p for folder in (BUILD, BUILD / "fmi3", BUILD / "platforms", BUILD / "platforms" / "fmi3")
              for p in folder.glob("*.fmu"))


def test_the_script_draws_the_committed_icons(tmp_path):
    subprocess.run([sys.executable, str(ROOT / "cmake" / "fmu_icons.py"), str(tmp_path)], check=True,
                   capture_output=True)
    drawn = sorted(p.parent.name for p in tmp_path.glob("*/icon.png"))
    assert drawn == sorted(p.parent.name for p in MODELS.glob("*/icon.png")) and drawn
    for name in drawn:
        assert (tmp_path / name / "icon.png").read_bytes() == (MODELS / name / "icon.png").read_bytes(), name


@pytest.mark.parametrize("fmu", FMUS, ids=lambda p: p.relative_to(BUILD).as_posix())
def test_every_fmu_carries_its_models_icon(fmu):
    where = "terminalsAndIcons/icon.png" if fmu.parent.name == "fmi3" else "model.png"
    png = zipfile.ZipFile(fmu).read(where)
    assert png == (MODELS / fmu.stem / "icon.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", png[16:24]) == (256, 256)
