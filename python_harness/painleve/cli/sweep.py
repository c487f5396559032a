# SPDX-License-Identifier: BSD-2-Clause
"""`painleve sweep`: many IWC cases, here or on dask, written as they finish, resumable."""
import argparse
import pathlib
import re
import textwrap

from .errors import Interrupted, RunError, UsageError, one_line
from .fmus import fmu_file
from .options import DEFAULTS, at_least_one, count, fmu_option, interface_option, output_path


def add_parser(sub):
    sw = sub.add_parser("sweep", allow_abbrev=False, help="many IWC cases, here or on dask, written as they finish",
                        formatter_class=argparse.RawDescriptionHelpFormatter,
                        description=textwrap.fill(
                            "Runs a grid or a random sample of IWC cases, in this process or on dask (a local "
                            "cluster when the sweep is long enough to pay for its start-up, or a scheduler by "
                            "address), and writes one row per case to a CSV or Parquet file as chunks finish. "
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
    sw.add_argument("--workers", type=at_least_one, metavar="N",
                    help="run on a local dask cluster of N worker processes (default: the first cases run in this "
                         "process, the rest on a cluster of this machine's cores only when it finishes sooner "
                         "despite its start-up of a few seconds)")
    sw.add_argument("--batch", type=at_least_one, metavar="N", help="cases per chunk, i.e. per dask task and per "
                    "written part (default: a few chunks per worker, each at most a few seconds of work)")
    sw.add_argument("--serial", action="store_true", help="run in this process, without dask")
    fmu_option(sw)
    interface_option(sw)
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")
    b = sw.add_argument_group("any body FMU (TwoLinkArm.fmu, ...): a grid or --random draws, run and written as the "
                              "rod's are (here or on dask, resumable)")
    b.add_argument("--set", action="append", default=[], metavar="NAME=SPEC",
                   help="a start value or parameter of the body and its values (a SPEC as below), e.g. "
                        "theta1=-1.2:-0.8:9 or mu=1,2 (with --random: theta1=-1.6:-0.4); with --eps, --delta, "
                        "--v0, --w10 the sweep's axes. Each case's other states are solved so that the contact "
                        "point is on the floor. Rows: the case, the theory there (quadrant, p_plus, b, theorem, "
                        "e, w1*, predicts_iwc) and the simulation (iwc, w, v, t_return, the phases): the paradox "
                        "map from simulation beside p_plus < 0")
    b.add_argument("--guess", action="append", default=[], metavar="NAME=VALUE",
                   help="where to start solving for a state that is not given (picks a branch, e.g. theta2=-1.3)")
    b.add_argument("--solve", action="append", default=[], metavar="NAME",
                   help="a parameter solved for with the states not given, e.g. H (the arm's pivot height) to put "
                        "the tip on the floor at the drawn theta1, theta2")
    b.add_argument("--map", metavar="PNG", help="also draw the paradox map: each case over the first two --set "
                   "axes, the simulation's IWC beside the theory's p_plus < 0 (figures.body.sweep_map_figure)")

def run(args):
    """One path for every body FMU: the sweep's cases (the rod's SweepSpec from the rod's options, for an FMU
    of the rod's model without --set; a body's sweep.body.BodySweep from --set otherwise), run by sweep.run
    (every case through fmu.body.Body, here or on dask, written as chunks finish, resumable); then the
    summary, a body's with its paradox map."""
    from ..fmu.experiment import FMI_TYPES
    from ..sweep.run import run_sweep
    from ..sweep.store import COLUMNS, ResultStore, StoreError
    from . import body
    generic = bool(args.set or args.guess or args.fmu) and \
        body.is_body(fmu_file(args.fmu, probe=False, allow_body=True), args)
    spec, map_axes = body_spec(args) if generic else (rod_spec(args), None)
    try:
        ResultStore(args.out)       # the output's kind, from its name
    except StoreError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    output_path(args.out, "painleve sweep: --out", directory=pathlib.Path(args.out).suffix.lower() in (".parquet", ".pq"))
    if args.map:
        output_path(args.map, "painleve sweep: --map")
    fmu = fmu_file(args.fmu, allow_body=generic)
    # Ctrl-C, and kill's SIGTERM, stop the sweep cleanly: main (interrupt.caught) makes them KeyboardInterrupt.
    try:
        result = run_sweep(spec, fmu, args.out, fmi_type=FMI_TYPES[args.interface], scheduler=args.scheduler,
                           workers=args.workers, batch=args.batch, serial=args.serial,
                           progress=not args.no_progress)
    except StoreError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    except KeyboardInterrupt:
        done = len(ResultStore(args.out).read(None)) if pathlib.Path(args.out).exists() else 0
        raise Interrupted(f"painleve sweep: interrupted; {done} of {spec.total} cases are saved in {args.out}: "
                          f"run the same command to resume") from None
    except OSError as err:
        if args.scheduler and not getattr(err, "filename", None):
            raise RunError(f"painleve sweep: cannot reach the dask scheduler {args.scheduler} "
                           f"({one_line(err)}); check the address, or leave out --scheduler for a local "
                           f"cluster") from None
        raise
    if generic:
        from ..sweep.body import typed
        return body_summary(args, fmu, typed(ResultStore(args.out).read(None)), map_axes)
    df = ResultStore(args.out).read(COLUMNS)
    counts = df["status"].value_counts().to_dict()
    iwc = int(df["iwc"].fillna(False).sum())
    rate = result.ran / result.seconds if result.seconds > 0 else float("nan")
    print(f"{len(df)} of {spec.total} cases in {args.out} ({', '.join(f'{v} {k}' for k, v in counts.items())}; "
          f"{iwc} IWC); this run: {result.ran} cases in {result.seconds:.1f} s ({rate:.0f} cases/s)"
          + (f", {result.skipped} already done" if result.skipped else ""))
    return 0


def rod_spec(args):
    """The rod's SweepSpec from its options (a body's refused: the rod's cases solve nothing)."""
    from ..sweep.spec import PARAMS, SpecError, SweepSpec
    body_only = [f"--{k}" for k in ("solve", "map") if getattr(args, k)]
    if body_only:
        raise UsageError(f"painleve sweep: {body_only[0]} is an option of a body's sweep (--set NAME=SPEC); the "
                         f"rod's own sweep solves nothing and draws no paradox map")
    texts = {p: getattr(args, p) for p in PARAMS if getattr(args, p) is not None}
    try:
        return SweepSpec.from_texts(texts, samples=args.random, seed=args.seed)
    except SpecError as err:
        raise UsageError(f"painleve sweep: {err}") from None


ROD_ONLY = ("theta0", "phi0", "alpha", "mu", "kappa", "beta")


def body_spec(args):
    """(sweep.body.BodySweep, the --map's two axes or None) from --set, --guess, --solve, --eps, --delta,
    --v0, --w10, --random, --seed (the rod's parameters refused)."""
    from ..sweep.body import BodySweep, axes_of
    from ..sweep.spec import SpecError
    from .body import assignment
    given = [k for k in ROD_ONLY if getattr(args, k) is not None]
    if given:
        raise UsageError(f"painleve sweep: --{given[0]} is an option of the rod's sweep; a body's sweep runs over "
                         f"--set NAME=SPEC, --eps, --delta, --v0, --w10")
    texts = {}
    for item in args.set:
        name, sep, text = item.partition("=")
        if not sep or not name.strip() or not text.strip():
            raise UsageError(f"painleve sweep: --set takes NAME=SPEC, such as theta1=-1.2:-0.8:9; got {item!r}")
        texts[name.strip()] = text
    case_texts = {k: getattr(args, k) for k in ("epsilon", "delta", "v0", "w10") if getattr(args, k) is not None}
    try:
        axes = axes_of(texts, case_texts, random=args.random > 0)
    except SpecError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    map_axes = [a.name for a in axes if a.name in texts][:2]
    if args.map and len(map_axes) < 2:
        raise UsageError("painleve sweep: --map draws the cases over the first two --set axes; give two")
    spec = BodySweep(axes=axes, samples=args.random, seed=args.seed, guess=tuple(assignment(g) for g in args.guess),
                     solve=tuple(s.strip() for s in args.solve))
    return spec, map_axes


def body_summary(args, fmu, df, map_axes):
    """A body's sweep's summary line (its statuses, the paradox map from simulation beside p_plus < 0, the
    theory's predictions met), and the map in --map."""
    counts = df["status"].value_counts().to_dict()
    ran = df[df["iwc"].notna()]
    paradox = ran["p_plus"] < 0
    told = df[df["predicts_iwc"].notna() & df["iwc"].notna()]
    agree = int((told["predicts_iwc"].astype(bool) == told["iwc"].astype(bool)).sum())
    print(f"{len(df)} cases of {fmu} ({args.interface}) in {args.out} "
          f"({', '.join(f'{v} {k}' for k, v in counts.items())}); paradox map: "
          f"{int((ran['iwc'].astype(bool) & paradox).sum())} IWC of {int(paradox.sum())} runs with p_plus < 0, "
          f"{int((ran['iwc'].astype(bool) & ~paradox).sum())} of {int((~paradox).sum())} with p_plus >= 0; "
          f"the theory's prediction met in {agree} of {len(told)}")
    if args.map:
        from ..figures.body import sweep_map_figure
        print(sweep_map_figure(df, map_axes, args.map, title=pathlib.Path(fmu).name))
    return 0


def scheduler_address(text):
    """A dask scheduler's address, protocol://host:port or host:port (checked for form only: whether
    one answers there is known when the sweep connects)."""
    if not re.fullmatch(r"((tcp|tls|ucx|ws|wss)://)?[A-Za-z0-9._\-\[\]:]+:\d{1,5}", text):
        raise argparse.ArgumentTypeError(f"{text!r} is not a dask scheduler address such as tcp://host:8786")
    return text
