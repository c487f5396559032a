# SPDX-License-Identifier: BSD-2-Clause
"""Every platform's binary of a multi-platform FMU (build/platforms/, `bash run.sh platforms`),
run by the project's platform driver (tests/platforms/platform_driver.c) compiled for that
platform: x86_64-linux natively, x86_64-windows under wine64, aarch64-linux under qemu-user
with the cross sysroot. One process per binary runs all its cases (wine starts slowly)."""
import os
import pathlib
import struct
import subprocess
import zipfile

from fmpy import read_model_description

ROOT = pathlib.Path(__file__).resolve().parents[2]
DRIVER = [ROOT / "tests" / "platforms" / n for n in ("platform_driver.c", "platform_fmi.c")]
SYSROOT = "/usr/aarch64-linux-gnu"

# FMI 3.0 folder: compiler, its extra options, how to run what it makes, FMI 2.0 folder.
TARGETS = {
    "x86_64-linux": dict(cc="gcc", flags=["-ldl"], run=[], fmi2="linux64", suffix=".so"),
    "x86_64-windows": dict(cc="x86_64-w64-mingw32-gcc-win32", flags=["-static-libgcc", "-D__USE_MINGW_ANSI_STDIO=1"],
                           run=["/usr/lib/wine/wine64"], fmi2="win64", suffix=".dll"),
    "aarch64-linux": dict(cc="aarch64-linux-gnu-gcc", flags=["-ldl"], run=["qemu-aarch64", "-L", SYSROOT],
                          fmi2=None, suffix=".so"),
}


def fmi_headers():
    import fmpy
    return pathlib.Path(fmpy.__file__).parent / "c-code"


def build_driver(target, out_dir):
    """The platform driver for TARGET in OUT_DIR, without fused multiply-add like the FMUs."""
    t = TARGETS[target]
    exe = pathlib.Path(out_dir) / f"platform_driver-{target}"
    subprocess.run([t["cc"], "-std=c99", "-O2", "-ffp-contract=off", "-Wall", "-Wextra", "-Werror",
                    "-D_POSIX_C_SOURCE=200809L", f"-I{fmi_headers()}", "-o", str(exe), *map(str, DRIVER),
                    *t["flags"]], check=True, capture_output=True, text=True)
    return exe.with_suffix(".exe") if target == "x86_64-windows" else exe


def folder(target, fmi_version):
    return target if fmi_version == 3 else TARGETS[target]["fmi2"]


def unpack(fmu, out_dir):
    out = pathlib.Path(out_dir) / pathlib.Path(fmu).parent.name / pathlib.Path(fmu).stem
    with zipfile.ZipFile(fmu) as z:
        z.extractall(out)
    return out


def bits(x):
    return format(struct.unpack("<Q", struct.pack("<d", float(x)))[0], "016x")


def value(text):
    return struct.unpack("<d", struct.pack("<Q", int(text, 16)))[0]


def driver_input(md, library, cases, outputs):
    """The driver's stdin: the header, then each case (kind, start, stop, step, {vr: value})."""
    vrs = {v.name: v.valueReference for v in md.modelVariables}
    out = [vrs[n] for n in outputs]
    nz = md.numberOfEventIndicators or 0
    lines = [f"{md.fmiVersion[0]} {library} {md.guid} {len(md.derivatives)} {nz}"]
    for kind, start, stop, step, values in cases:
        params = " ".join(f"{vrs[n]} {bits(v)}" for n, v in values.items())
        lines.append(f"case {kind} {bits(start)} {bits(stop)} {bits(step)} {len(values)} {params} "
                     f"{len(out)} " + " ".join(map(str, out)))
    return "\n".join(lines + ["end", ""])


def wine_environment(prefix):
    env = dict(os.environ, WINEPREFIX=str(prefix), WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=")
    env.pop("DISPLAY", None)
    return env


def run_binary(target, driver, fmu_dir, cases, outputs, wine_prefix):
    """The driver's stdout for CASES on the binary of TARGET in the unpacked FMU FMU_DIR."""
    md = read_model_description(str(fmu_dir / "modelDescription.xml"))
    version = int(md.fmiVersion[0])
    library = fmu_dir / "binaries" / folder(target, version) / (md.modelExchange.modelIdentifier
                                                                 + TARGETS[target]["suffix"])
    assert library.is_file(), f"{library} is missing"
    path = str(library)
    if target == "x86_64-windows":
        path = "Z:" + path.replace("/", "\\")
    text = driver_input(md, path, cases, outputs)
    result = subprocess.run([*TARGETS[target]["run"], str(driver)], input=text, capture_output=True, text=True,
                            timeout=900, env=wine_environment(wine_prefix))
    assert result.returncode == 0, f"{target} {library.name}: exit {result.returncode}\n{result.stderr[-2000:]}"
    return result.stdout


def parse(stdout):
    """[(case, [status lines], [[t, outputs...] per communication point])]."""
    cases = []
    for line in stdout.splitlines():
        word, *rest = line.split()
        if word == "case":
            cases.append((int(rest[0]), [], []))
        elif word == "status":
            cases[-1][1].append(" ".join(rest))
        elif word == "at":
            cases[-1][2].append([value(x) for x in rest])
    return cases


def differences(reference, other, kinds, outputs):
    """{(kind, output): largest |difference| / the output's largest |value| in the case}, over the
    cases of two parsed runs (kinds: each case's ME or CS). Relative to the output's scale, not
    pointwise: a mean force that is zero to rounding (1e-14 beside forces of 1) is not a result.
    A run whose cases, statuses or communication points do not match gives inf."""
    worst = {}
    if len(reference) != len(other):
        return {("all", "cases"): float("inf")}
    for (k, s, rows), (k2, s2, rows2) in zip(reference, other):
        if k != k2 or s != s2 or len(rows) != len(rows2):
            return {(kinds[k], "run"): float("inf")}
        for j, (column, column2) in enumerate(zip(zip(*rows), zip(*rows2))):
            scale = max(max(abs(a) for a in column), 1e-300)
            key = (kinds[k], outputs[j - 1] if j else "time")
            d = max(abs(a - b) for a, b in zip(column, column2)) / scale
            worst[key] = max(worst.get(key, 0.0), d)
    return worst
