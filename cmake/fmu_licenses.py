# SPDX-License-Identifier: BSD-2-Clause
"""documentation/licenses/ of every FMU a build makes: the project's license, the
license of the SUNDIALS the binaries link and of the SUNDIALS the sources carry
(each copied from where that SUNDIALS came from), and the FMI headers' (the
comment each header of fmpy's c-code carries), with the versions, and
license.txt, the folder's entry point (FMI 3.0, 2.4.1), naming them all.

    python3 fmu_licenses.py OUT_DIR PROJECT_LICENSE FMI_HEADERS_DIR
        [--sundials ROLE VERSION ORIGIN LICENSE_FILE]...

ROLE is "binaries" (the static CVODE in binaries/) or "sources" (the CVODE
subset in sources/).
"""
import argparse
import importlib.metadata
import re
import shutil
from pathlib import Path

PROJECT_FILE = "PainleveRod-LICENSE.txt"
FMI_FILE = "FMI-headers-LICENSE.txt"
FMI_HEADERS = ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h",
               "fmi3Functions.h", "fmi3FunctionTypes.h", "fmi3PlatformTypes.h")


def sundials_file(version):
    return f"SUNDIALS-{version}-LICENSE.txt"


def header_license(text):
    """The license of an FMI header: its comment from the copyright line to the comment's end."""
    match = re.search(r"^[ \t]*(Copyright \(C\).*?)\*/", text, re.S | re.M)
    if not match:
        raise SystemExit("an FMI header without its copyright comment")
    return "\n".join(line.strip() for line in match.group(1).rstrip().splitlines()) + "\n"


def header_version(text, name):
    match = re.search(rf'#define {name} "([^"]+)"', text)
    return match.group(1) if match else None


def fmi_notice(headers):
    """The FMI headers' licenses, one block per distinct text, and the versions they declare."""
    blocks = {}
    versions = []
    for name in FMI_HEADERS:
        text = (headers / name).read_text(encoding="utf-8", errors="replace")
        blocks.setdefault(header_license(text), []).append(name)
        for macro in ("fmi2Version", "fmi3Version"):
            version = header_version(text, macro)
            if version:
                versions.append(f"{macro} \"{version}\" ({name})")
    try:
        fmpy = f"fmpy {importlib.metadata.version('fmpy')}"
    except importlib.metadata.PackageNotFoundError:
        fmpy = "fmpy"
    parts = [f"The FMI headers the binaries are compiled with: {fmpy}'s c-code folder.\n"
             f"Versions: {', '.join(versions)}.\n"]
    for block, names in blocks.items():
        parts.append(f"\n--- {', '.join(names)} ---\n\n{block}")
    return "".join(parts)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out", type=Path)
    parser.add_argument("project_license", type=Path)
    parser.add_argument("fmi_headers", type=Path)
    parser.add_argument("--sundials", nargs=4, action="append", default=[],
                        metavar=("ROLE", "VERSION", "ORIGIN", "LICENSE_FILE"))
    args = parser.parse_args()
    out = args.out
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    shutil.copyfile(args.project_license, out / PROJECT_FILE)
    (out / FMI_FILE).write_text(fmi_notice(args.fmi_headers), encoding="utf-8")
    lines = ["Licenses of this FMU and of what it contains.", "",
             f"{PROJECT_FILE}: the FMU itself (the model, its FMI layer and its build),",
             "  BSD-2-Clause, copyright The PainleveRod authors.", ""]
    roles = {"binaries": "statically linked into the binaries in binaries/",
             "sources": "its CVODE subset in sources/ (sundials_src/ and the headers' folders)"}
    for role, version, origin, license_file in args.sundials:
        name = sundials_file(version)
        if (out / name).exists() and (out / name).read_bytes() != Path(license_file).read_bytes():
            name = sundials_file(f"{version}-{role}")
        shutil.copyfile(license_file, out / name)
        lines += [f"{name}: SUNDIALS {version} CVODE, {roles[role]},",
                  f"  BSD-3-Clause, copyright Lawrence Livermore National Security; from {origin}.", ""]
    lines += [f"{FMI_FILE}: the FMI 2.0 and 3.0 headers (fmi2*.h, fmi3*.h) the binaries are",
              "  compiled with, BSD-2-Clause, copyright Modelica Association Project \"FMI\".", ""]
    (out / "license.txt").write_text("\n".join(lines), encoding="utf-8")


if __name__ == "__main__":
    main()
