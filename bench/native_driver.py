# SPDX-License-Identifier: BSD-2-Clause
"""Runs IWC cases through the native Model Exchange driver (bench/native:
painleve_native_me, the FMU under SUNDIALS CVODE with no Python in the loop)
and reads its TSV back.

    rows = run_native("build/bench/native/painleve_native_me", "build/PainleveRod.fmu", [Case(epsilon=1e-4)])
    rows[0]["w"], rows[0]["nsteps"], rows[0]["wall_seconds"]

Each row has the case's fields (theta0 ... mu) and rtol, the state at the
rod's return to y = 0 (w, v, theta, phi, t_return), iwc (bool), the solver's
counts (nsteps, nfev incl. the difference-quotient Jacobian's, njev, ngev,
nevents: event iterations incl. the one at the return, one more than
Outcome.events unless delta = 0), wall_seconds (median over `repeat` runs),
peak_rss_kib (the driver process's own peak, VmHWM), and `case`, the Case it came from.
"""
import os
import pathlib
import shutil
import subprocess
import tempfile

FIELDS = ("theta0", "phi0", "v0", "delta", "epsilon", "w10", "alpha", "mu")
INTEGERS = {"nsteps", "nfev", "njev", "ngev", "nevents", "switches", "contact",
            "steps", "rhs", "flight_evaluations", "cvode_steps", "cvode_rhs", "events"}   # the last: painleve_native_cs


def case_line(case):
    """One stdin line: the case's numbers, repr so that they round-trip exactly."""
    return " ".join(repr(float(getattr(case, name))) for name in FIELDS)


def _parse(stdout, cases):
    lines = stdout.splitlines()
    if not lines:
        raise RuntimeError("the native driver printed nothing")
    header = lines[0].split("\t")
    rows, peak_rss = [], None
    for line in lines[1:]:
        if line.startswith("#"):
            if line.startswith("# peak_rss_kib\t"):
                peak_rss = int(line.split("\t")[1])
            continue
        values = line.split("\t")
        if len(values) != len(header):
            raise RuntimeError(f"the native driver printed a line of {len(values)} fields, not {len(header)}: {line!r}")
        row = {}
        for name, text in zip(header, values):
            row[name] = int(text) if name in INTEGERS else bool(int(text)) if name == "iwc" else float(text)
        rows.append(row)
    if len(rows) != len(cases):
        raise RuntimeError(f"the native driver reported {len(rows)} cases for {len(cases)} given:\n{stdout}")
    for row, case in zip(rows, cases):
        row["peak_rss_kib"] = peak_rss
        row["case"] = case
    return rows


def run_native_cs(executable, fmu_path, cases, *, rtol=None, repeat=1, timeout=None):
    """Runs `cases` through bench/native's painleve_native_cs (the FMU's own Co-Simulation,
    one fmi2DoStep over each case, from C); one dict per case as run_native's, its w, v,
    theta, phi at the return to the floor run back in closed form from the state at the
    horizon (as the harness's Co-Simulation fast loop does), wall_seconds and
    fixed_seconds (the run without its step: reset, set values, initialization, reads)."""
    from painleve.experiments.outcome import flight_back_to_floor
    rows = run_native(executable, fmu_path, cases, rtol=rtol, repeat=repeat, jacobian=None, timeout=timeout)
    for row in rows:
        if row["contact"] or not row["y"] > 0:
            raise RuntimeError(f"{row['case']}: not in flight at the horizon (contact {row['contact']}, y {row['y']})")
        _, back = flight_back_to_floor(row)
        row.update((k, back[k]) for k in ("w", "v", "theta", "phi"))
    return rows


def run_native(executable, fmu_path, cases, *, rtol=None, repeat=1, jacobian="dq", timeout=None):
    """Runs `cases` (painleve.experiments.case.Case) through `executable` on the FMU at
    `fmu_path` (a .fmu, extracted here to a temporary directory, an extracted FMU
    directory, or its binaries/linux64/*.so); one dict per case. rtol None: the
    harness's min(1e-6, eps/100) per case. Raises RuntimeError with the driver's
    stderr if it fails (bad input, a value the FMU refuses, a failed run)."""
    executable = pathlib.Path(executable)
    if not executable.is_file() or not os.access(executable, os.X_OK):
        raise FileNotFoundError(f"{executable} is missing: `cmake --build build` builds it (needs SUNDIALS CVODE)")
    if jacobian not in ("dq", "analytic", None):
        raise ValueError(f"jacobian must be 'dq' or 'analytic', not {jacobian!r}")
    cases = list(cases)
    tmp = None
    try:
        target = str(fmu_path)
        if os.path.isfile(target) and target.endswith(".fmu"):
            from fmpy import extract
            tmp = tempfile.mkdtemp(prefix="painleve-native-")
            target = extract(target, tmp)
        cmd = [str(executable), target, "--repeat", str(int(repeat))] + (["--jacobian", jacobian] if jacobian else [])
        if rtol is not None:
            cmd += ["--rtol", repr(float(rtol))]
        stdin = "".join(case_line(c) + "\n" for c in cases)
        done = subprocess.run(cmd, input=stdin, capture_output=True, text=True, timeout=timeout, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"{executable.name} exited with status {done.returncode}: {done.stderr.strip()}")
        return _parse(done.stdout, cases)
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
