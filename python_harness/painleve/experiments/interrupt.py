# SPDX-License-Identifier: BSD-2-Clause
"""Ctrl-C (SIGINT) and SIGTERM that are not lost. Python raises KeyboardInterrupt wherever the
signal finds it; inside a function that C calls back (fmpy's CVode right-hand side or root
function, an FMU's logger) or a `__del__`, Python prints the exception and drops it, and the run
goes on, or fails for want of the callback's answer (SUNDIALS then prints its own error). So
`caught` keeps the signal in a flag; where it lands inside fmpy's CVode callbacks it only sets the
flag, and Python's report of a dropped one is silenced; the next run that asks (`check`) stops,
and the command can tell an interruption from a failure it caused (`pending`)."""
import contextlib
import os
import signal
import sys

_caught = False
_CALLBACKS = os.sep + os.path.join("fmpy", "sundials") + os.sep   # CVode's callbacks into Python


def _in_callback(frame):
    """Whether the signal landed in a function that C called back (fmpy's CVode solver)."""
    while frame is not None:
        if _CALLBACKS in frame.f_code.co_filename:
            return True
        frame = frame.f_back
    return False


def _handler(signum, frame):
    global _caught
    _caught = True
    if not _in_callback(frame):
        raise KeyboardInterrupt


@contextlib.contextmanager
def caught():
    """Within: SIGINT and SIGTERM raise KeyboardInterrupt (or, inside a CVode callback, wait for the
    next `check`) and are remembered (main thread only); the handlers before are back after."""
    global _caught
    _caught = False
    before = {sig: signal.signal(sig, _handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    hook = sys.unraisablehook

    def quiet(unraisable):      # the KeyboardInterrupt Python drops is the flag's: not a traceback
        if not (_caught and isinstance(unraisable.exc_value, KeyboardInterrupt)):
            hook(unraisable)
    sys.unraisablehook = quiet
    try:
        yield
    finally:
        sys.unraisablehook = hook
        for sig, handler in before.items():
            signal.signal(sig, handler)


def pending():
    """True once a signal has arrived within `caught`, whether or not its KeyboardInterrupt got through."""
    return _caught


def check():
    """KeyboardInterrupt if a signal arrived whose own KeyboardInterrupt was dropped or held back."""
    if _caught:
        raise KeyboardInterrupt
