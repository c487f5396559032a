# SPDX-License-Identifier: BSD-2-Clause
"""The `painleve` command run as a user runs it, for the tests of tests/cli: a subprocess of
the installed console script (else the module), and its one-line error."""
import pathlib
import subprocess
import sys


def painleve_command():
    """The installed console script beside this Python, else the module (same code)."""
    script = pathlib.Path(sys.executable).with_name("painleve")
    return [str(script)] if script.exists() else [sys.executable, "-m", "painleve"]


def run(*args, check_rc=None, timeout=300, cwd=None):
    r = subprocess.run(painleve_command() + [str(a) for a in args], capture_output=True, text=True,
                       timeout=timeout, cwd=cwd)
    if check_rc is not None:
        assert r.returncode == check_rc, f"exit {r.returncode}\nstdout:\n{r.stdout}\nstderr:\n{r.stderr}"
    return r


def one_line_error(r):
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert "Traceback" not in r.stderr, r.stderr
    assert len(lines) == 1, r.stderr
    return lines[0]
