# SPDX-License-Identifier: BSD-2-Clause
"""What every `painleve` command's options share: a parser that reports bad input in one
line saying what to change, argument types, the case and FMU options, and the probe of a
path a command will write."""
import argparse
import math
import pathlib
import re

from .errors import UsageError
from .fmus import DEFAULT_FMU

DEFAULTS = dict(theta0=1.0, phi0=0.5, v0=1.0, delta=1.0, epsilon=1e-3, w10=0.0, alpha=3.0, mu=3.0, kappa=0.0, beta=0.0)


class Parser(argparse.ArgumentParser):
    """argparse that reports a bad argument in one line, with the way to the help,
    and reads -1e-3 as a number, not as an option."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message):
        raise UsageError(f"{self.prog}: {message} (see `{self.prog} --help`)")


# ------------------------------------------------------------------ argument types
def number(text):
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return x


def _g(x):
    """1e-08 as 1e-8, 1e+06 as 1e6: numbers as the help and docs/model.md write them."""
    return f"{x:g}".replace("e+0", "e").replace("e-0", "e-").replace("e+", "e")


def in_range(name, option, why=""):
    """An argument type: a number inside the FMU's range of parameter `name` (case.RANGES)."""
    from ..experiments.case import RANGES
    lo, hi = RANGES[name]

    def check(text):
        x = number(text)
        if not lo <= x <= hi:
            raise argparse.ArgumentTypeError(f"{option} {text} is not in [{_g(lo)}, {_g(hi)}], the FMU's range{why}")
        return x
    check.__name__ = name       # argparse names the type in its messages
    return check


epsilon_value = in_range("epsilon", "eps", ": the contact stiffness is eps^-2, so give a small positive value "
                                           "such as --eps 1e-4")


def dpi_value(text):
    x = number(text)
    if not 10 <= x <= 1200:
        raise argparse.ArgumentTypeError(f"{text} is not in [10, 1200] dots per inch (a figure is ~10 inches wide)")
    return x


def count(text):
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if n < 0:
        raise argparse.ArgumentTypeError(f"{text} is negative")
    return n


def at_least_one(text):
    n = count(text)
    if n < 1:
        raise argparse.ArgumentTypeError(f"{text} is not >= 1")
    return n


def positive(text):
    x = number(text)
    if x <= 0:
        raise argparse.ArgumentTypeError(f"{text} is not > 0")
    return x


def output_path(path, option, *, directory=False):
    """The path a command will write (a file, or a directory with `directory`), made ready and probed
    before any simulation runs, so that a path that cannot be written ends in one line at once
    rather than after minutes of work."""
    import tempfile
    p = pathlib.Path(path)
    where = p if directory else p.parent
    blocking = next((a for a in [where, *where.parents] if a.exists()), None)
    if blocking is not None and not blocking.is_dir():
        raise UsageError(f"{option} {path}: {blocking} is a file, not a directory; give a path in a writable "
                         f"directory")
    try:
        if p.exists() and directory != p.is_dir():
            raise UsageError(f"{option} {path}: it is {'a file' if directory else 'a directory'}; "
                             f"give {'a directory' if directory else 'a file name'}")
        where.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=where):      # the directory takes a new file
            pass
    except OSError as err:
        raise UsageError(f"{option} {path}: cannot write there ({err.strerror or err}); "
                         f"give a path in a writable directory") from None
    return str(p)


# ------------------------------------------------------------------ options of several commands
def case_options(parser, help_suffix=""):
    """The parameters and initial state of an IWC case (Case's fields)."""
    g = parser.add_argument_group("case: the rod's parameters and its state on the floor at t = 0 (y = 0)")
    g.add_argument("--theta0", type=number, default=DEFAULTS["theta0"], metavar="RAD",
                   help="rod angle; Theorems 1 and 2 need it inside the Painleve wedge p_+(theta0) < 0 "
                        "(default %(default)s)")
    g.add_argument("--phi0", type=number, default=DEFAULTS["phi0"], metavar="RAD/T",
                   help="angular velocity; b = -1 + phi0^2 sin(theta0) < 0 is Theorem 1, > 0 Theorem 2 "
                        "(default %(default)s)")
    g.add_argument("--v0", type=number, default=None, help="horizontal velocity of the end, > 0 (default "
                   f"{DEFAULTS['v0']:g}; a body FMU: the slip speed of its own start)")
    g.add_argument("--delta", type=in_range("delta", "delta"), default=DEFAULTS["delta"],
                   help="contact damping, in [0, 1e6] (default %(default)s)")
    g.add_argument("--eps", "--epsilon", dest="epsilon", type=epsilon_value, default=DEFAULTS["epsilon"],
                   help="compliance in [1e-8, 1] (the FMU's range); the contact stiffness is eps^-2 (default %(default)s)")
    g.add_argument("--w10", type=number, default=DEFAULTS["w10"],
                   help="initial vertical velocity in the contact's scale, w(0) = eps*w10; Theorem 2 needs "
                        "w10 < 0, and predicts IWC for w10 < w1*, lift-off above (default %(default)s)")
    g.add_argument("--alpha", type=in_range("alpha", "alpha"), default=DEFAULTS["alpha"],
                   help="m l^2 / I, in [1e-6, 1e6]; 3 for a uniform rod (default %(default)s)")
    g.add_argument("--mu", type=in_range("mu", "mu"), default=DEFAULTS["mu"],
                   help="friction coefficient, in [0, 1e6]; a Painleve wedge needs mu > 2 sqrt(1+alpha)/alpha "
                        "(default %(default)s)")
    g.add_argument("--kappa", type=in_range("kappa", "kappa"), default=DEFAULTS["kappa"],
                   help="compliance law: the spring's stiffening, scaled force d + kappa d^2 at scaled penetration "
                        "d = -y/eps, in [0, 1e6]; e is then the rigid limit computed numerically "
                        "(docs/nonlinear_compliance.md; default %(default)s: the paper's linear law)")
    g.add_argument("--beta", type=in_range("beta", "beta"), default=DEFAULTS["beta"],
                   help="compliance law: the damping's growth with penetration, delta (1 + beta d), in [0, 1e6] "
                        "(default %(default)s)")


def fmu_option(parser):
    parser.add_argument("--fmu", metavar="PATH", help=f"the FMU to simulate (default: $PAINLEVE_FMU, else "
                                                      f"{DEFAULT_FMU} if there is one, else the one installed "
                                                      f"with the package)")


def interface_option(parser, *, all_choice=False):
    choices = ["ME", "CS"] + (["all"] if all_choice else [])
    parser.add_argument("--interface", choices=choices, default="all" if all_choice else "ME",
                        help="FMI interface: ME (Model Exchange, fmpy's CVode with exact events) or CS "
                             "(Co-Simulation, the FMU's own solver)" +
                             (", or all that the FMU declares (default)" if all_choice else " (default ME)"))
