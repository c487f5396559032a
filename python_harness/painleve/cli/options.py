"""The `painleve` command's options: argument types that turn bad input into one line
saying what to change, the FMU to use, and the parser of every subcommand."""
import argparse
import math
import os
import pathlib
import re
import textwrap
import zipfile

DEFAULT_FMU = "build/PainleveRod.fmu"
DEFAULTS = dict(theta0=1.0, phi0=0.5, v0=1.0, delta=1.0, epsilon=1e-3, w10=0.0, alpha=3.0, mu=3.0, kappa=0.0, beta=0.0)


class UsageError(Exception):
    """Bad input: exit status 2 with this one-line message."""


class RunError(Exception):
    """The run could not be done as asked: exit status 1 with this one-line message."""


class Interrupted(RunError):
    """Stopped by Ctrl-C or SIGTERM: exit status 130 with this one-line message."""


# The variables the harness reads and sets: an FMU without them is another model's.
REQUIRED_VARIABLES = ("alpha", "mu", "delta", "epsilon", "x", "v", "y", "w", "theta", "phi", "mode", "contact")


class Parser(argparse.ArgumentParser):
    """argparse that reports a bad argument in one line, with the way to the help,
    and reads -1e-3 as a number, not as an option."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message):
        raise UsageError(f"{self.prog}: {message} (see `{self.prog} --help`)")


# ------------------------------------------------------------------ argument types
def _number(text):
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
    from .case import RANGES
    lo, hi = RANGES[name]

    def check(text):
        x = _number(text)
        if not lo <= x <= hi:
            raise argparse.ArgumentTypeError(f"{option} {text} is not in [{_g(lo)}, {_g(hi)}], the FMU's range{why}")
        return x
    check.__name__ = name       # argparse names the type in its messages
    return check


epsilon_value = in_range("epsilon", "eps", ": the contact stiffness is eps^-2, so give a small positive value "
                                           "such as --eps 1e-4")


def dpi_value(text):
    x = _number(text)
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


def scheduler_address(text):
    """A dask scheduler's address, protocol://host:port or host:port (checked for form only: whether
    one answers there is known when the sweep connects)."""
    if not re.fullmatch(r"((tcp|tls|ucx|ws|wss)://)?[A-Za-z0-9._\-\[\]:]+:\d{1,5}", text):
        raise argparse.ArgumentTypeError(f"{text!r} is not a dask scheduler address such as tcp://host:8786")
    return text


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


def fmu_file(path, *, probe=True):
    """The FMU to use (--fmu, else $PAINLEVE_FMU, else build/PainleveRod.fmu where there is one, as in
    the repository after `bash run.sh`, else the one installed with the package), checked so that a
    wrong path ends in one line saying what to do: a missing file, not an FMU, another FMI version, another
    model's FMU, no binary for this platform, and (with `probe`) one that does not load or instantiate."""
    from .experiment import BUNDLED_FMU
    given = path or os.environ.get("PAINLEVE_FMU") or \
        (BUNDLED_FMU if BUNDLED_FMU.is_file() and not os.path.exists(DEFAULT_FMU) else DEFAULT_FMU)
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
    if missing:
        raise UsageError(f"{p} is an FMU of the model {md.modelName!r}, not the Painleve rod (it has no variable "
                         f"{', '.join(missing[:3])}{', ...' if len(missing) > 3 else ''}): give a PainleveRod.fmu")
    if platform not in supported_platforms(str(p)):
        raise UsageError(f"{p} has no binary for {platform} (it has {', '.join(supported_platforms(str(p)))}); "
                         f"compile it here first: python -m fmpy compile {p}")
    if probe:
        _instantiates(p)
    return str(p)


def _fmi_version(p):
    """The fmiVersion attribute of the FMU's model description, read before fmpy validates it against
    the schema of a version it may not support (None if it cannot be read)."""
    import xml.etree.ElementTree as ET
    try:
        with zipfile.ZipFile(p) as z:
            return ET.fromstring(z.read("modelDescription.xml")).get("fmiVersion")
    except Exception:
        return None


def one_line(err):
    """An exception's message on one line (what the CLI prints)."""
    return " ".join(str(err).split()) or type(err).__name__


def _instantiates(p):
    """An FMU whose binary does not load here, or that refuses to instantiate (a GUID that does not
    match its binary, a broken build), is named now, in one line, not deep inside a run."""
    from .experiment import Experiment, FmuLoadError
    try:
        with Experiment(str(p)):
            pass
    except FmuLoadError as err:
        raise UsageError(f"{p}: {err}; rebuild it (`bash run.sh main`) or give another PainleveRod.fmu") from None


# ------------------------------------------------------------------ the parser
def _case_options(parser, help_suffix=""):
    """The parameters and initial state of an IWC case (Case's fields)."""
    g = parser.add_argument_group("case: the rod's parameters and its state on the floor at t = 0 (y = 0)")
    g.add_argument("--theta0", type=_number, default=DEFAULTS["theta0"], metavar="RAD",
                   help="rod angle; Theorems 1 and 2 need it inside the Painleve wedge p_+(theta0) < 0 "
                        "(default %(default)s)")
    g.add_argument("--phi0", type=_number, default=DEFAULTS["phi0"], metavar="RAD/T",
                   help="angular velocity; b = -1 + phi0^2 sin(theta0) < 0 is Theorem 1, > 0 Theorem 2 "
                        "(default %(default)s)")
    g.add_argument("--v0", type=_number, default=DEFAULTS["v0"], help="horizontal velocity of the end, > 0 "
                   "(default %(default)s)")
    g.add_argument("--delta", type=in_range("delta", "delta"), default=DEFAULTS["delta"],
                   help="contact damping, in [0, 1e6] (default %(default)s)")
    g.add_argument("--eps", "--epsilon", dest="epsilon", type=epsilon_value, default=DEFAULTS["epsilon"],
                   help="compliance in [1e-8, 1] (the FMU's range); the contact stiffness is eps^-2 (default %(default)s)")
    g.add_argument("--w10", type=_number, default=DEFAULTS["w10"],
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


def _fmu_option(parser):
    parser.add_argument("--fmu", metavar="PATH", help=f"the FMU to simulate (default: $PAINLEVE_FMU, else "
                                                      f"{DEFAULT_FMU} if there is one, else the one installed "
                                                      f"with the package)")


def _interface_option(parser, *, all_choice=False):
    choices = ["ME", "CS"] + (["all"] if all_choice else [])
    parser.add_argument("--interface", choices=choices, default="all" if all_choice else "ME",
                        help="FMI interface: ME (Model Exchange, fmpy's CVode with exact events) or CS "
                             "(Co-Simulation, the FMU's own solver)" +
                             (", or all that the FMU declares (default)" if all_choice else " (default ME)"))


def build_parser():
    p = Parser(prog="painleve", allow_abbrev=False,
               description="The compliant Painleve rod FMU (Hogan & Kristiansen): impact without collision "
                           "simulated beside the paper's closed forms.",
               epilog="Each subcommand has its own --help. Exit status: 0 done, 1 failed (a validation check, "
                      "a simulation), 2 bad input.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    for add in (_add_iwc, _add_validate, _add_figures, _add_sweep, _add_couple):
        add(sub)
    return p


def _add_iwc(sub):
    iwc = sub.add_parser("iwc", allow_abbrev=False, help="one IWC case: simulated outcome versus the analytic one",
                         description="Simulates one case from the floor (y = 0) with the FMU and prints the "
                                     "simulated outcome beside the paper's prediction: Theorem 1 (b < 0) gives "
                                     "IWC with w = e(delta, theta0) v0; Theorem 2 (b > 0) gives IWC below the "
                                     "separatrix w1* and lift-off with w = O(eps) above it. The predictions are "
                                     "asymptotic (eps -> 0): the corrections they drop are of relative size "
                                     "eps (1 + delta)^3 (e ~ delta^-2 for large delta, the stick lasts a fast "
                                     "time ~ 1 + delta), so a case with eps (1 + delta)^3 > 2e-2 is marked "
                                     "OUTSIDE the asymptotic regime, with the reason, in the table and in "
                                     "--json (\"regime\").")
    _case_options(iwc)
    _fmu_option(iwc)
    _interface_option(iwc)
    iwc.add_argument("--json", action="store_true", help="print one JSON object instead of the table")


def _add_validate(sub):
    val = sub.add_parser("validate", allow_abbrev=False, help="the validation suite for an FMU build (for CI)",
                         description="Validates a PainleveRod.fmu: fmpy's static validation and the interface "
                                     "contract, the default experiment, then Theorem 1 and 2 cases across the "
                                     "parameter space at eps = 1e-4 ... 1e-6 through every interface the FMU "
                                     "declares. Prints a pass/fail table with the measured errors; exits 1 if "
                                     "any check fails.")
    val.add_argument("fmu", nargs="?", metavar="FMU", help=f"the FMU to validate (default: $PAINLEVE_FMU, else "
                                                           f"{DEFAULT_FMU} if there is one, else the one "
                                                           f"installed with the package)")
    _interface_option(val, all_choice=True)
    val.add_argument("--sample", type=count, default=24, metavar="N",
                     help="Theorem 1 cases drawn at random (fixed seed) beside the fixed ones (default 24)")
    val.add_argument("--kappa", type=in_range("kappa", "--kappa"), default=0.0,
                     help="every case with this compliance law's stiffening (its e: the rigid limit, "
                          "docs/nonlinear_compliance.md; default 0, the paper's linear law)")
    val.add_argument("--beta", type=in_range("beta", "--beta"), default=0.0,
                     help="every case with this damping growth with penetration (default 0)")
    val.add_argument("--report", metavar="PATH", help="also write the report: Markdown (.md) or JSON (.json)")
    val.add_argument("--json", action="store_true", help="print the checks as JSON instead of the table")


def _add_figures(sub):
    fig = sub.add_parser("figures", allow_abbrev=False, help="the paper's figures from simulations of the FMU",
                         description="Regenerates the paper's figures (GB: the quadrants of the (theta, phi) plane; eDelta0: the coefficient e(0, theta0) and e(delta, theta0); video: two rods, one IWC, one lift-off) from "
                                     "simulations of the FMU, with the analytic curves beside the simulated "
                                     "points. Writes PNG files, figures.json (the numbers behind each plot) "
                                     "and figures.md (how far the points lie from the curves).")
    _fmu_option(fig)
    fig.add_argument("--out", default="out/figures", metavar="DIR", help="where to write (default %(default)s)")
    fig.add_argument("--only", metavar="NAMES", help="a comma-separated subset of GB, eDelta0, video, eLaw")
    fig.add_argument("--dpi", type=dpi_value, default=150, help="PNG resolution, 10 to 1200 (default %(default)s)")


def _add_sweep(sub):
    sw = sub.add_parser("sweep", allow_abbrev=False, help="many IWC cases on dask, written as they finish",
                        formatter_class=argparse.RawDescriptionHelpFormatter,
                        description=textwrap.fill(
                            "Runs a grid or a random sample of IWC cases on dask (a local cluster, or a scheduler "
                            "by address) and writes one row per case to a CSV or Parquet file as batches finish. "
                            "Run the same command again to resume an interrupted sweep: finished cases are not "
                            "recomputed.", 79),
                        epilog="each parameter takes:\n"
                               "  1.0            one value\n"
                               "  0.5,1,1.2      a list (random sample: one of them)\n"
                               "  lo:hi:n        grid: n values from lo to hi (lo:hi:n:log evenly in log)\n"
                               "  lo:hi          random sample: uniform (lo:hi:log log-uniform)\n"
                               "parameters not given keep the defaults of `painleve iwc`.\n"
                               "rows: id, status (ok, outside the theorems' hypotheses, failed), the case, "
                               "the outcome,\nthe predictions and the errors (w_error = w/v0 - e).")
    g = sw.add_argument_group("parameters (see below)")
    meaning = dict(theta0="rod angle", phi0="angular velocity", delta="contact damping", v0="horizontal velocity",
                   w10="initial w / eps", alpha="m l^2 / I", mu="friction coefficient",
                   kappa="compliance law: spring stiffening", beta="compliance law: damping growth")
    for name, what in meaning.items():
        g.add_argument(f"--{name}", metavar="SPEC", help=f"{name} values ({what}; default {DEFAULTS[name]:g})")
    g.add_argument("--eps", "--epsilon", dest="epsilon", metavar="SPEC",
                   help=f"epsilon values, each in [1e-8, 1] (default {DEFAULTS['epsilon']:g})")
    sw.add_argument("--random", type=at_least_one, default=0, metavar="N",
                    help="draw N >= 1 random cases from the ranges instead of a grid")
    sw.add_argument("--seed", type=count, default=0, help="seed of the random sample (default 0)")
    sw.add_argument("--out", default="out/sweep.parquet", metavar="PATH",
                    help="results: a .csv file or a .parquet dataset (default %(default)s)")
    sw.add_argument("--scheduler", type=scheduler_address, metavar="ADDRESS", help="an existing dask scheduler, e.g. tcp://host:8786 "
                    "(its workers need the painleve package; the FMU is sent to them)")
    sw.add_argument("--workers", type=at_least_one, default=2, help="workers of the local cluster (default 2)")
    sw.add_argument("--batch", type=at_least_one, default=200, help="cases per dask task (default 200)")
    sw.add_argument("--serial", action="store_true", help="run in this process, without dask")
    _fmu_option(sw)
    _interface_option(sw)
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")


# ------------------------------------------------------------------ couple
DEFAULT_ROD_FMU = "build/PainleveRodSI.fmu"
DEFAULT_TABLE_FMU = "build/ShakerTable.fmu"


def positive(text):
    x = _number(text)
    if x <= 0:
        raise argparse.ArgumentTypeError(f"{text} is not > 0")
    return x


def start_value(text):
    """COMPONENT.NAME=VALUE, a start value for the rod or the table (checked against the FMU later)."""
    m = re.fullmatch(r"(rod|table)\.([A-Za-z_][A-Za-z0-9_]*)=(.+)", text)
    if not m:
        raise argparse.ArgumentTypeError(f"{text!r} is not COMPONENT.NAME=VALUE with COMPONENT rod or table "
                                         f"(e.g. rod.k=2e5, table.M=1e6)")
    return m.group(1), m.group(2), _number(m.group(3))


def _add_couple(sub):
    from .masters import MASTERS
    cp = sub.add_parser("couple", allow_abbrev=False, help="the rod on a shaker table, co-simulated from an SSP file",
                        description="Couples PainleveRodSI.fmu (the rod in SI units, with a moving floor as input) "
                                    "with ShakerTable.fmu (a table top on a spring-damper, shaken by a harmonic "
                                    "force, loaded by the rod's contact forces) in an SSP archive "
                                    "(SystemStructure.ssd + resources/*.fmu), checks the archive, runs it in a "
                                    "co-simulation master (fixed communication step, Jacobi with zero-order hold) "
                                    "and writes a figure: the rod and the table over time, the forces on both "
                                    "sides. Prints the impulse of the normal force on each side (equal to O(h)).")
    cp.add_argument("--rod", metavar="PATH",
                    help=f"the rod's FMU (default {DEFAULT_ROD_FMU} if there is one, else the one installed with "
                         f"the package)")
    cp.add_argument("--table", metavar="PATH",
                    help=f"the table's FMU (default {DEFAULT_TABLE_FMU} if there is one, else the one installed "
                         f"with the package)")
    cp.add_argument("--master", choices=MASTERS, default="fmpy",
                    help="fmpy (fmpy.ssp), libcosim (libcosimpy) or ecos (ecospy); the last two are installed by "
                         "`bash run.sh test` (default %(default)s)")
    cp.add_argument("--stop", type=positive, default=0.45, metavar="SECONDS", help="stop time (default %(default)s)")
    cp.add_argument("--step", type=positive, default=1e-4, metavar="SECONDS",
                    help="communication step h; the stop time must be a whole number of steps (default %(default)s)")
    cp.add_argument("--set", dest="start_values", type=start_value, action="append", default=[],
                    metavar="COMPONENT.NAME=VALUE",
                    help="a start value bound in the SSP, repeatable: a parameter or an initial state of the rod "
                         "(m, l, J, g, k, c, mu; x, v, y, w, theta, phi) or of the table (M, K, C, F0, frequency, "
                         "belt_speed; position, velocity)")
    cp.add_argument("--out", default="out/couple.png", metavar="PNG", help="the figure (default %(default)s)")
    cp.add_argument("--ssp", metavar="PATH", help="also keep the SSP archive there")
    cp.add_argument("--csv", metavar="PATH", help="also write the run's table (one row per communication point)")
    cp.add_argument("--dpi", type=dpi_value, default=150, help="PNG resolution, 10 to 1200 (default %(default)s)")


ROD_VARIABLES = ("y_floor", "w_floor", "v_floor", "F_N", "F_T", "vy_cm", "theta", "phi")
TABLE_VARIABLES = ("position", "velocity", "belt_velocity", "F_N", "F_T")


def coupled_fmu(path, role):
    """The rod's or the table's FMU for `painleve couple`, checked so that a wrong one ends in one
    line: missing, not an FMU, not FMI 2.0 (libcosim loads FMI 1.0 and 2.0 only), another model,
    no Co-Simulation, no binary for this platform. Returns the path and its variables by name."""
    default, required = {"rod": (DEFAULT_ROD_FMU, ROD_VARIABLES), "table": (DEFAULT_TABLE_FMU, TABLE_VARIABLES)}[role]
    if path is None:        # build/NAME.fmu where there is one (the repository), else the package's own
        import importlib.resources
        bundled = importlib.resources.files("painleve").joinpath(pathlib.Path(default).name)
        path = str(bundled) if bundled.is_file() and not os.path.exists(default) else default
    p = pathlib.Path(path)
    where = f"painleve couple: --{role} {p}"
    if not p.exists():
        raise UsageError(f"{where}: no such file; build it with `bash run.sh main` (it writes {default}), "
                         f"`pip install` the repository (it installs one with the package) or give the path of one")
    if p.is_dir() or not zipfile.is_zipfile(p):
        raise UsageError(f"{where} is not an FMU (a zip archive such as {default}); give the .fmu file")
    version = _fmi_version(p)
    if version != "2.0":
        raise UsageError(f"{where} is an FMI {version} FMU; the coupled study runs FMI 2.0 FMUs (build/*.fmu)")
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
