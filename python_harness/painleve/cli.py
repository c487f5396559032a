"""The `painleve` command: one IWC case, validation of an FMU build, the
paper's figures from simulations of the FMU, and sweeps on dask.

    painleve iwc --theta0 1.0 --phi0 0.5 --eps 1e-4
    painleve validate build/PainleveRod.fmu --report out/validation.md
    painleve figures --out out/figures
    painleve sweep --theta0 0.5:1.4:10 --eps 1e-5:1e-3:3:log --out out/sweep.parquet

Bad input ends with one line that says what to change (exit status 2); a
failed validation or a simulation the FMU gave up on exits with status 1."""
import argparse
import math
import os
import pathlib
import re
import signal
import sys
import textwrap
import time
import zipfile

from .report import to_json

DEFAULT_FMU = "build/PainleveRod.fmu"
FMI_TYPES = {"ME": "ModelExchange", "CS": "CoSimulation"}     # --interface's names, fmpy's
DEFAULTS = dict(theta0=1.0, phi0=0.5, v0=1.0, delta=1.0, epsilon=1e-3, w10=0.0, alpha=3.0, mu=3.0)


class UsageError(Exception):
    """Bad input: exit status 2 with this one-line message."""


class RunError(Exception):
    """The run could not be done as asked: exit status 1 with this one-line message."""


class Interrupted(RunError):
    """Stopped by Ctrl-C or SIGTERM: exit status 130 with this one-line message."""


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


def epsilon_value(text):
    x = _number(text)
    if not 1e-8 <= x < 1:
        raise argparse.ArgumentTypeError(f"eps = {text} is not in [1e-8, 1): the contact stiffness is eps^-2, "
                                         f"so give a small positive value such as --eps 1e-4")
    return x


def nonnegative(text):
    x = _number(text)
    if x < 0:
        raise argparse.ArgumentTypeError(f"{text} is negative; give a value >= 0")
    return x


def positive(text):
    x = _number(text)
    if x <= 0:
        raise argparse.ArgumentTypeError(f"{text} is not > 0")
    return x


def count(text):
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if n < 0:
        raise argparse.ArgumentTypeError(f"{text} is negative")
    return n


def fmu_file(path):
    """The FMU to use (--fmu, else $PAINLEVE_FMU, else the one installed with the package, else
    build/PainleveRod.fmu), checked so that a wrong path ends in one line saying what to do."""
    from .experiment import BUNDLED_FMU
    given = path or os.environ.get("PAINLEVE_FMU") or (BUNDLED_FMU if BUNDLED_FMU.exists() else DEFAULT_FMU)
    p = pathlib.Path(given)
    if not p.exists():
        how = "" if path else " (the default; set PAINLEVE_FMU or pass --fmu)"
        raise UsageError(f"no FMU at {p}{how}: `pip install` the repository (it builds one into the package), "
                         f"build it with `bash run.sh main`, which writes {DEFAULT_FMU}, "
                         f"or give the path of a PainleveRod.fmu")
    if p.is_dir() or not zipfile.is_zipfile(p):
        raise UsageError(f"{p} is not an FMU (an FMU is a zip archive such as {DEFAULT_FMU}); give the .fmu file")
    from fmpy import platform, read_model_description, supported_platforms
    try:
        read_model_description(str(p))
    except Exception as err:
        raise UsageError(f"{p} has no readable modelDescription.xml ({err}); rebuild it with `bash run.sh main`")
    if platform not in supported_platforms(str(p)):
        raise UsageError(f"{p} has no binary for {platform} (it has {', '.join(supported_platforms(str(p)))}); "
                         f"compile it here first: python -m fmpy compile {p}")
    return str(p)


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
    g.add_argument("--delta", type=nonnegative, default=DEFAULTS["delta"], help="contact damping, >= 0 "
                   "(default %(default)s)")
    g.add_argument("--eps", "--epsilon", dest="epsilon", type=epsilon_value, default=DEFAULTS["epsilon"],
                   help="compliance in [1e-8, 1); the contact stiffness is eps^-2 (default %(default)s)")
    g.add_argument("--w10", type=_number, default=DEFAULTS["w10"],
                   help="initial vertical velocity in the contact's scale, w(0) = eps*w10; Theorem 2 needs "
                        "w10 < 0, and predicts IWC for w10 < w1*, lift-off above (default %(default)s)")
    g.add_argument("--alpha", type=positive, default=DEFAULTS["alpha"],
                   help="m l^2 / I, > 0; 3 for a uniform rod (default %(default)s)")
    g.add_argument("--mu", type=nonnegative, default=DEFAULTS["mu"],
                   help="friction coefficient, >= 0; a Painleve wedge needs mu > 2 sqrt(1+alpha)/alpha "
                        "(default %(default)s)")


def _fmu_option(parser):
    parser.add_argument("--fmu", metavar="PATH", help=f"the FMU to simulate (default: $PAINLEVE_FMU, else the "
                                                      f"one installed with the package, else {DEFAULT_FMU})")


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
    for add in (_add_iwc, _add_validate, _add_figures, _add_sweep):
        add(sub)
    return p


def _add_iwc(sub):
    iwc = sub.add_parser("iwc", allow_abbrev=False, help="one IWC case: simulated outcome versus the analytic one",
                         description="Simulates one case from the floor (y = 0) with the FMU and prints the "
                                     "simulated outcome beside the paper's prediction: Theorem 1 (b < 0) gives "
                                     "IWC with w = e(delta, theta0) v0; Theorem 2 (b > 0) gives IWC below the "
                                     "separatrix w1* and lift-off with w = O(eps) above it.")
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
    val.add_argument("fmu", nargs="?", metavar="FMU", help=f"the FMU to validate (default: $PAINLEVE_FMU or "
                                                           f"{DEFAULT_FMU})")
    _interface_option(val, all_choice=True)
    val.add_argument("--sample", type=count, default=24, metavar="N",
                     help="Theorem 1 cases drawn at random (fixed seed) beside the fixed ones (default 24)")
    val.add_argument("--report", metavar="PATH", help="also write the report: Markdown (.md) or JSON (.json)")
    val.add_argument("--json", action="store_true", help="print the checks as JSON instead of the table")


def _add_figures(sub):
    fig = sub.add_parser("figures", allow_abbrev=False, help="the paper's figures from simulations of the FMU",
                         description="Regenerates the paper's figures fig:GB, fig:eDelta0 (a, b) and video from "
                                     "simulations of the FMU, with the analytic curves beside the simulated "
                                     "points. Writes PNG files, figures.json (the numbers behind each plot) "
                                     "and figures.md (how far the points lie from the curves).")
    _fmu_option(fig)
    fig.add_argument("--out", default="out/figures", metavar="DIR", help="where to write (default %(default)s)")
    fig.add_argument("--only", metavar="NAMES", help="a comma-separated subset of GB, eDelta0, video")
    fig.add_argument("--dpi", type=positive, default=150, help="PNG resolution (default %(default)s)")


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
                   w10="initial w / eps", alpha="m l^2 / I", mu="friction coefficient")
    for name, what in meaning.items():
        g.add_argument(f"--{name}", metavar="SPEC", help=f"{name} values ({what}; default {DEFAULTS[name]:g})")
    g.add_argument("--eps", "--epsilon", dest="epsilon", metavar="SPEC",
                   help=f"epsilon values, each in [1e-8, 1) (default {DEFAULTS['epsilon']:g})")
    sw.add_argument("--random", type=count, default=0, metavar="N",
                    help="draw N random cases from the ranges instead of a grid")
    sw.add_argument("--seed", type=count, default=0, help="seed of the random sample (default 0)")
    sw.add_argument("--out", default="out/sweep.parquet", metavar="PATH",
                    help="results: a .csv file or a .parquet dataset (default %(default)s)")
    sw.add_argument("--scheduler", metavar="ADDRESS", help="an existing dask scheduler, e.g. tcp://host:8786 "
                    "(its workers need the painleve package; the FMU is sent to them)")
    sw.add_argument("--workers", type=count, default=2, help="workers of the local cluster (default 2)")
    sw.add_argument("--batch", type=count, default=200, help="cases per dask task (default 200)")
    sw.add_argument("--serial", action="store_true", help="run in this process, without dask")
    _fmu_option(sw)
    _interface_option(sw)
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")


# ------------------------------------------------------------------ iwc
def _hypothesis_hint(case, err):
    """What to change, for the hypothesis that failed."""
    from . import analytic as an
    text = str(err)
    if "w10" in text:
        w1s = an.predict(case).w1_star
        if math.isnan(w1s):
            return "give --w10 < 0"
        return f"give --w10 < 0 (IWC below the separatrix w1* = {w1s:.4f}, lift-off above it)"
    if "p_+" in text or "q_+" in text:
        if case.mu <= an.mu_P(case.alpha):
            return f"raise --mu above mu_P(alpha) = {an.mu_P(case.alpha):.4f}, or lower --alpha"
        t1, t2 = an.theta_1(alpha=case.alpha, mu=case.mu), an.theta_2(alpha=case.alpha, mu=case.mu)
        return f"choose --theta0 inside the Painleve wedge ({t1:.4f}, {t2:.4f})"
    if "v0" in text:
        return "give --v0 > 0 (the rod's end slips forward)"
    if "a(theta0" in text:
        return "give --phi0 != 0"
    return "see `painleve iwc --help`"


def _fmt(x):
    return "nan" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.6g}"


def iwc_report(case, o):
    """(heading lines, table rows) for one simulated case beside its predictions."""
    from . import analytic as an
    predicted = an.predict(case)
    quadrant = {1: "inconsistent, b < 0", 2: "indeterminate, b > 0"}[predicted.theorem]
    lam = predicted.lambda_plus
    heading = [f"Theorem {predicted.theorem} ({quadrant}, p_+ = "
               f"{an.p_plus(case.theta0, alpha=case.alpha, mu=case.mu):.4g}): alpha={case.alpha:g} mu={case.mu:g} "
               f"delta={case.delta:g} eps={case.epsilon:g}; theta0={case.theta0:g} phi0={case.phi0:g} "
               f"v0={case.v0:g} w(0)=eps*{case.w10:g}"]
    if predicted.theorem == 2:
        heading.append(f"separatrix w1* = {predicted.w1_star:.6g}: the paper predicts "
                       f"{'IWC (w10 < w1*)' if predicted.iwc else 'lift-off (w10 > w1*)'}")
    ev = predicted.e * case.v0
    rows = [("outcome", "IWC" if o.iwc else "lift-off", "IWC" if predicted.iwc else "lift-off", "")]
    if predicted.iwc:
        rows.append(("w at return (y = 0)", _fmt(o.w), f"{ev:.6g} (e v0)",
                     f"{o.w - ev:+.3e} ({(o.w - ev) / ev:+.3%} of e v0)"))
        rows.append(("phi", _fmt(o.phi), f"{predicted.phi:.6g}", f"{o.phi_error:+.3e}"))
    else:
        rows.append(("w at return (y = 0)", _fmt(o.w), "O(eps)", f"w/eps = {o.w / case.epsilon:.3g}"))
        rows.append(("phi", _fmt(o.phi), f"{case.phi0:.6g} + O(eps)", f"{o.phi - case.phi0:+.3e}"))
    rows.append(("theta", _fmt(o.theta), f"{case.theta0:.6g}", f"{o.theta_error:+.3e}"))
    if predicted.iwc:
        rows += [("v", _fmt(o.v), "0 + O(eps)", f"v/eps = {o.v / case.epsilon:+.3g}"),
                 ("t_return", _fmt(o.t_return), f"{case.epsilon * math.log(1 / case.epsilon) / lam:.4g} "
                  f"(eps ln(1/eps)/lambda_+)", "leading order only")]
    else:
        rows += [("v", _fmt(o.v), f"{case.v0:.6g} + O(eps)", f"{o.v - case.v0:+.3e}"),
                 ("t_return", _fmt(o.t_return), "O(eps)", f"t/eps = {o.t_return / case.epsilon:.3g}")]
    rows += [
             ("compression / stick / lift-off / flight back",
              f"{_fmt(o.compression)} / {_fmt(o.stick)} / {_fmt(o.lift_off)} / {_fmt(o.flight_back)}", "",
              "durations (see painleve.outcome)"),
             ("events", str(o.events), "", "mode switches (-1: not seen through CS)")]
    return heading, rows


def cmd_iwc(args):
    from . import analytic as an
    from .case import Case
    from .experiment import Experiment
    from .sweep import predictions
    case = Case(**{k: getattr(args, k) for k in DEFAULTS})
    try:
        case.check()
    except an.HypothesisError as err:
        raise UsageError(f"painleve iwc: {err}; {_hypothesis_hint(case, err)}") from None
    fmu = fmu_file(args.fmu)
    with Experiment(fmu, fmi_type=FMI_TYPES[args.interface]) as experiment:
        outcome = experiment.run(case)
    if args.json:
        row = outcome.as_row()
        print(to_json({"fmu": fmu, "interface": args.interface, "case": {k: row[k] for k in DEFAULTS},
                     "predicted": predictions(case),
                     "simulated": {k: row[k] for k in ("iwc", "w", "theta", "phi", "v", "t_return",
                                                       "compression", "stick", "lift_off", "flight_back",
                                                       "events")},
                     "errors": {k: row[k] for k in ("w_error", "phi_error", "theta_error")}}))
        return 0
    heading, rows = iwc_report(case, outcome)
    print(f"IWC of the Painleve rod: {fmu} through {'Model Exchange' if args.interface == 'ME' else 'Co-Simulation'}")
    print("\n".join(heading))
    widths = [max(len(r[i]) for r in rows + [("quantity", "simulated", "analytic (eps -> 0)", "")])
              for i in range(3)]
    print(f"{'quantity':<{widths[0]}}  {'simulated':<{widths[1]}}  {'analytic (eps -> 0)':<{widths[2]}}  difference")
    for r in rows:
        print(f"{r[0]:<{widths[0]}}  {r[1]:<{widths[1]}}  {r[2]:<{widths[2]}}  {r[3]}")
    return 0


# ------------------------------------------------------------------ validate
def cmd_validate(args):
    from . import report
    from .sweep import FmuBlob
    from .validate import validate
    fmu = fmu_file(args.fmu)
    interfaces = None if args.interface == "all" else [args.interface]
    start = time.monotonic()
    checks = validate(fmu, interfaces=interfaces, sample=args.sample)
    seconds = time.monotonic() - start
    digest = FmuBlob.read(fmu).digest
    if args.report:
        path = pathlib.Path(args.report)
        path.parent.mkdir(parents=True, exist_ok=True)
        if path.suffix.lower() == ".json":
            path.write_text(to_json(_checks_json(checks, fmu, digest, seconds), indent=1))
        else:
            path.write_text(report.markdown(checks, fmu_path=fmu, sha256=digest, seconds=seconds))
    if args.json:
        print(to_json(_checks_json(checks, fmu, digest, seconds)))
    else:
        print(f"Validation of {fmu} (sha256 {digest[:12]}…), {seconds:.1f} s"
              + (f"; report in {args.report}" if args.report else ""))
        print(report.table(checks))
    return 0 if all(c.passed for c in checks) else 1


def _checks_json(checks, fmu, digest, seconds):
    return {"fmu": fmu, "sha256": digest, "seconds": seconds, "passed": all(c.passed for c in checks),
            "failed": [c.id for c in checks if not c.passed], "checks": [c.as_dict() for c in checks]}


# ------------------------------------------------------------------ figures
def cmd_figures(args):
    from .figures import FIGURES, make_figures
    only = None
    if args.only:
        only = [n.strip() for n in args.only.split(",") if n.strip()]
        unknown = [n for n in only if n not in FIGURES]
        if unknown:
            raise UsageError(f"painleve figures: unknown figure {unknown[0]!r}; --only takes a comma-separated "
                             f"subset of {', '.join(FIGURES)}")
    fmu = fmu_file(args.fmu)
    written = make_figures(fmu, args.out, only=only, dpi=args.dpi)
    for path in written:
        print(path)
    return 0


# ------------------------------------------------------------------ sweep
def cmd_sweep(args):
    from .sweep import run_sweep
    from .sweepspec import PARAMS, SpecError, SweepSpec
    from .sweepstore import ResultStore, StoreError
    texts = {p: getattr(args, p) for p in PARAMS if getattr(args, p) is not None}
    try:
        spec = SweepSpec.from_texts(texts, samples=args.random, seed=args.seed)
    except SpecError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    if spec.total == 0:
        raise UsageError("painleve sweep: the sweep has no cases; give --random N > 0 or non-empty ranges")
    if not args.serial and not args.scheduler and args.workers < 1:
        raise UsageError("painleve sweep: --workers must be >= 1 (or use --serial)")
    fmu = fmu_file(args.fmu)
    # Ctrl-C, and kill's SIGTERM, stop the sweep cleanly (even where a shell started it ignoring SIGINT).
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, _interrupt)
    try:
        result = run_sweep(spec, fmu, args.out, fmi_type=FMI_TYPES[args.interface], scheduler=args.scheduler,
                           workers=args.workers, batch=max(1, args.batch), serial=args.serial,
                           progress=not args.no_progress)
    except StoreError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    except KeyboardInterrupt:
        done = len(ResultStore(args.out).read()) if pathlib.Path(args.out).exists() else 0
        raise Interrupted(f"painleve sweep: interrupted; {done} of {spec.total} cases are in {args.out}: "
                       f"run the same command to resume") from None
    except OSError as err:
        if args.scheduler:
            raise RunError(f"painleve sweep: cannot reach the dask scheduler {args.scheduler} ({err}); "
                           f"check the address, or leave out --scheduler for a local cluster") from None
        raise
    df = ResultStore(args.out).read()
    counts = df["status"].value_counts().to_dict()
    iwc = int(df["iwc"].fillna(False).sum())
    rate = result.ran / result.seconds if result.seconds > 0 else float("nan")
    print(f"{len(df)} of {spec.total} cases in {args.out} ({', '.join(f'{v} {k}' for k, v in counts.items())}; "
          f"{iwc} IWC); this run: {result.ran} cases in {result.seconds:.1f} s ({rate:.0f} cases/s)"
          + (f", {result.skipped} already done" if result.skipped else ""))
    return 0


def _interrupt(signum, frame):
    raise KeyboardInterrupt


COMMANDS = {"iwc": cmd_iwc, "validate": cmd_validate, "figures": cmd_figures, "sweep": cmd_sweep}


def main(argv=None):
    parser = build_parser()
    try:
        args, extra = parser.parse_known_args(sys.argv[1:] if argv is None else argv)
        if extra:
            unknown = next((a for a in extra if a.startswith("-")), extra[0])
            raise UsageError(f"painleve {args.command}: unknown option or parameter {unknown!r} "
                             f"(see `painleve {args.command} --help` for the options)")
        return COMMANDS[args.command](args)
    except UsageError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    except RunError as err:
        print(f"error: {err}", file=sys.stderr)
        return 130 if isinstance(err, Interrupted) else 1
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:     # `painleve ... | head`: the reader left; say nothing more
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except Exception as err:
        from .outcome import SimulationError
        if isinstance(err, SimulationError):
            print(f"error: the simulation failed: {err}; try a smaller --eps or --delta "
                  f"(the asymptotic regime needs eps (1 + delta)^3 << 1)", file=sys.stderr)
            return 1
        raise


if __name__ == "__main__":
    sys.exit(main())
