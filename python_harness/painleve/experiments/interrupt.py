"""Ctrl-C (SIGINT) and SIGTERM that are not lost. Python raises KeyboardInterrupt wherever the
signal finds it; inside a function that C calls back (fmpy's CVode right-hand side, an FMU's
logger) or a `__del__`, Python prints the exception and drops it, and the run goes on (or fails
for want of the callback's answer). `caught` keeps the signal in a flag as well, so that the next
run that asks (`check`) stops then, and the command that caught it can tell an interruption from
the failure it caused (`pending`)."""
import contextlib
import signal

_caught = False


def _handler(signum, frame):
    global _caught
    _caught = True
    raise KeyboardInterrupt


@contextlib.contextmanager
def caught():
    """Within: SIGINT and SIGTERM raise KeyboardInterrupt and are remembered (main thread only);
    the handlers before are back after."""
    global _caught
    _caught = False
    before = {sig: signal.signal(sig, _handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, handler in before.items():
            signal.signal(sig, handler)


def pending():
    """True once a signal has arrived within `caught`, whether or not its KeyboardInterrupt got through."""
    return _caught


def check():
    """KeyboardInterrupt if a signal arrived whose own KeyboardInterrupt was dropped."""
    if _caught:
        raise KeyboardInterrupt
