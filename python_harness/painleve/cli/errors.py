# SPDX-License-Identifier: BSD-2-Clause
"""The one place where a failure becomes what the user of the `painleve` command reads:
the errors a command raises, and the exit status and one line each ends in."""


class UsageError(Exception):
    """Bad input: exit status 2 with this one-line message."""


class RunError(Exception):
    """The run could not be done as asked: exit status 1 with this one-line message."""


class Interrupted(RunError):
    """Stopped by Ctrl-C or SIGTERM: exit status 130 with this one-line message."""


def one_line(err):
    """An exception's message on one line (what the CLI prints)."""
    return " ".join(str(err).split()) or type(err).__name__


def user_error(err, command):
    """(exit status, one line) for a failure, or None for a failure that is not the user's
    (a bug: its traceback is shown, on request)."""
    from ..experiments.outcome import SimulationError
    from ..fmu.body import BodyError
    from ..fmu.experiment import FmuLoadError
    where = f"painleve {command}" if command else "painleve"
    if isinstance(err, UsageError):
        return 2, str(err)
    if isinstance(err, Interrupted):
        return 130, str(err)
    if isinstance(err, RunError):
        return 1, str(err)
    if isinstance(err, KeyboardInterrupt):
        return 130, f"{where}: interrupted (Ctrl-C); nothing more was written"
    if isinstance(err, BodyError):
        return 2, f"{where}: {err}"
    if isinstance(err, FmuLoadError):
        return 2, f"{where}: {err}; give a PainleveRod.fmu built for this machine"
    if isinstance(err, SimulationError):
        return 1, (f"{where}: the simulation failed: {err}; try a smaller --eps or --delta "
                   f"(the asymptotic regime needs eps (1 + delta)^3 <= 2e-2)")
    if isinstance(err, MemoryError):
        return 1, f"{where}: out of memory; ask for fewer cases or points"
    if isinstance(err, OSError) and getattr(err, "filename", None):
        return 2, (f"{where}: cannot use {err.filename} ({err.strerror or one_line(err)}); "
                   f"give a path that exists and can be written")
    if isinstance(err, OSError):
        return 1, f"{where}: {one_line(err)}"
    return None
