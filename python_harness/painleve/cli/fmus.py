# SPDX-License-Identifier: BSD-2-Clause
"""The FMUs a `painleve` command runs, checked before any simulation so that a wrong one
ends in one line saying what to do: PainleveRod.fmu for iwc, validate, figures and sweep,
the rod in SI units and the shaker table for couple."""
import os
import pathlib
import zipfile

from .errors import UsageError, one_line

DEFAULT_FMU = "build/PainleveRod.fmu"
DEFAULT_ROD_FMU = "build/PainleveRodSI.fmu"
DEFAULT_TABLE_FMU = "build/ShakerTable.fmu"
DEFAULT_FMI3_DIR = "build/fmi3"        # the FMI 3.0 FMUs (not installed with the package)

# The variables the harness reads and sets: an FMU without them is another model's.
REQUIRED_VARIABLES = ("alpha", "mu", "delta", "epsilon", "x", "v", "y", "w", "theta", "phi", "mode", "contact")
ROD_VARIABLES = ("y_floor", "w_floor", "v_floor", "F_N", "F_T", "vy_cm", "theta", "phi")
TABLE_VARIABLES = ("position", "velocity", "belt_velocity", "F_N", "F_T")


# What a body FMU has instead (fmu.body.REQUIRED): the generic path of iwc, validate and figures.
BODY_VARIABLES = ("y", "v", "w", "contact", "epsilon", "delta", "a", "b", "p_plus", "p_minus", "q_plus", "q_minus")


def fmu_file(path, *, probe=True, allow_body=False):
    """The FMU to use (--fmu, else $PAINLEVE_FMU, else build/PainleveRod.fmu where there is one, as in
    the repository after `bash run.sh`, else the one installed with the package), checked so that a
    wrong path ends in one line saying what to do: a missing file, not an FMU, another FMI version, another
    model's FMU, no binary for this platform, and (with `probe`) one that does not load or instantiate."""
    given = path or os.environ.get("PAINLEVE_FMU") or _repository_or_bundled(DEFAULT_FMU)
    p = pathlib.Path(given)
    if not p.exists():
        how = "" if path else " (the default; set PAINLEVE_FMU or pass --fmu)"
        raise UsageError(f"no FMU at {p}{how}: `pip install` the repository (it builds one into the package), "
                         f"build it with `bash run.sh main`, which writes {DEFAULT_FMU}, "
                         f"or give the path of a PainleveRod.fmu")
    if p.is_dir() or not zipfile.is_zipfile(p):
        raise UsageError(f"{p} is not an FMU (an FMU is a zip archive such as {DEFAULT_FMU}); give the .fmu file")
    from fmpy import platform, read_model_description, supported_platforms
    version = _fmi_version(p)
    if version is not None and not (version.startswith("2.") or version.startswith("3.")):
        raise UsageError(f"{p} is an FMI {version} FMU; painleve runs FMI 2.0 and 3.0 (build/PainleveRod.fmu, "
                         f"build/fmi3/PainleveRod.fmu)")
    try:
        md = read_model_description(str(p))
    except Exception as err:
        raise UsageError(f"{p} has no readable modelDescription.xml ({one_line(err)}); "
                         f"rebuild it with `bash run.sh main`") from None
    if not (md.fmiVersion.startswith("2.") or md.fmiVersion.startswith("3.")):
        raise UsageError(f"{p} is an FMI {md.fmiVersion} FMU; painleve runs FMI 2.0 and 3.0 (build/PainleveRod.fmu, "
                         f"build/fmi3/PainleveRod.fmu)")
    names = {v.name for v in md.modelVariables}
    missing = [n for n in REQUIRED_VARIABLES if n not in names]
    if missing and allow_body and all(n in names for n in BODY_VARIABLES):
        missing = []        # a body FMU: the generic path runs it
    if missing:
        raise UsageError(f"{p} is an FMU of the model {md.modelName!r}, not the Painleve rod (it has no variable "
                         f"{', '.join(missing[:3])}{', ...' if len(missing) > 3 else ''}): give a PainleveRod.fmu")
    if platform not in supported_platforms(str(p)):
        raise UsageError(f"{p} has no binary for {platform} (it has {', '.join(supported_platforms(str(p)))}); "
                         f"compile it here first: python -m fmpy compile {p}")
    if probe:
        _instantiates(p)
    return str(p)


def _repository_or_bundled(default):
    """build/NAME.fmu where there is one (the repository after `bash run.sh`), else the one installed
    with the package."""
    from ..fmu.experiment import bundled
    installed = bundled(pathlib.Path(default).name)
    return str(installed) if installed.is_file() and not os.path.exists(default) else default


def _fmi_version(p):
    """The fmiVersion attribute of the FMU's model description, read before fmpy validates it against
    the schema of a version it may not support (None if it cannot be read)."""
    import xml.etree.ElementTree as ET
    try:
        with zipfile.ZipFile(p) as z:
            return ET.fromstring(z.read("modelDescription.xml")).get("fmiVersion")
    except Exception:
        return None


def _instantiates(p):
    """An FMU whose binary does not load here, or that refuses to instantiate (a GUID that does not
    match its binary, a broken build), is named now, in one line, not deep inside a run."""
    from ..fmu.experiment import Experiment, FmuLoadError
    try:
        with Experiment(str(p)):
            pass
    except FmuLoadError as err:
        raise UsageError(f"{p}: {err}; rebuild it (`bash run.sh main`) or give another PainleveRod.fmu") from None


def coupled_fmu(path, role, fmi_version="2.0"):
    """The rod's or the table's FMU for `painleve couple`, checked so that a wrong one ends in one
    line: missing, not an FMU, not of fmi_version ("2.0", or "3.0": build/fmi3/), another model,
    no Co-Simulation, no binary for this platform. Returns the path and its variables by name."""
    default, required = {"rod": (DEFAULT_ROD_FMU, ROD_VARIABLES), "table": (DEFAULT_TABLE_FMU, TABLE_VARIABLES)}[role]
    if fmi_version == "3.0":
        default = f"{DEFAULT_FMI3_DIR}/{pathlib.Path(default).name}"
    if path is None:
        path = _repository_or_bundled(default) if fmi_version == "2.0" else default
    p = pathlib.Path(path)
    where = f"painleve couple: --{role} {p}"
    if not p.exists():
        installed = ", `pip install` the repository (it installs one with the package)" if fmi_version == "2.0" else ""
        raise UsageError(f"{where}: no such file; build it with `bash run.sh main` (it writes {default})"
                         f"{installed} or give the path of one")
    if p.is_dir() or not zipfile.is_zipfile(p):
        raise UsageError(f"{where} is not an FMU (a zip archive such as {default}); give the .fmu file")
    version = _fmi_version(p)
    if version not in ("2.0", "3.0"):
        raise UsageError(f"{where} is an FMI {version} FMU; the coupled study runs FMI 2.0 and 3.0 FMUs")
    if version != fmi_version:
        raise UsageError(f"{where} is an FMI {version} FMU; --fmi-version {fmi_version[0]} couples FMI {fmi_version} "
                         f"FMUs ({default}): give --fmi-version {version[0]} to couple it")
    from fmpy import platform, read_model_description, supported_platforms
    try:
        md = read_model_description(str(p))
    except Exception as err:
        raise UsageError(f"{where} has no readable modelDescription.xml ({one_line(err)}); rebuild it") from None
    names = {v.name: v for v in md.modelVariables}
    missing = [n for n in required if n not in names]
    if missing:
        raise UsageError(f"{where} is an FMU of the model {md.modelName!r}, not the {role} (it has no variable "
                         f"{', '.join(missing[:3])}); give {default}")
    if md.coSimulation is None:
        raise UsageError(f"{where} has no Co-Simulation interface, which the masters drive")
    if platform not in supported_platforms(str(p)):
        raise UsageError(f"{where} has no binary for {platform}; compile it here first")
    return str(p), names
