"""The `painleve` command: one IWC case, validation of an FMU build, the
paper's figures from simulations of the FMU, and sweeps on dask.

    painleve iwc --theta0 1.0 --phi0 0.5 --eps 1e-4
    painleve validate build/PainleveRod.fmu --report out/validation.md
    painleve figures --out out/figures
    painleve sweep --theta0 0.5:1.4:10 --eps 1e-5:1e-3:3:log --out out/sweep.parquet
    painleve couple --master libcosim --set table.F0=100 --out out/couple.png

Bad input ends with one line that says what to change (exit status 2); a
failed validation or a simulation the FMU gave up on exits with status 1."""
import math
import os
import pathlib
import shutil
import signal
import sys
import time

from .cli_parser import (DEFAULTS, Interrupted, RunError, UsageError, build_parser, fmu_file, one_line,
                         output_path)
from .report import to_json


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
    from .acceptance import regime_of
    predicted = an.predict(case)
    quadrant = {1: "inconsistent, b < 0", 2: "indeterminate, b > 0"}[predicted.theorem]
    lam = predicted.lambda_plus
    heading = [f"Theorem {predicted.theorem} ({quadrant}, p_+ = "
               f"{an.p_plus(case.theta0, alpha=case.alpha, mu=case.mu):.4g}): alpha={case.alpha:g} mu={case.mu:g} "
               f"delta={case.delta:g} eps={case.epsilon:g}; theta0={case.theta0:g} phi0={case.phi0:g} "
               f"v0={case.v0:g} w(0)=eps*{case.w10:g}"]
    inside, reason = regime_of(case)
    heading.append(f"asymptotic regime: {'inside' if inside else 'OUTSIDE'} ({reason})")
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
             ("events", str(o.events), "", "mode switches")]
    return heading, rows


def cmd_iwc(args):
    from . import analytic as an
    from .case import Case
    from .experiment import FMI_TYPES, Experiment
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
                     "predicted": predictions(case), "regime": _regime_json(case),
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


def _regime_json(case):
    from .acceptance import REGIME, regime_measure, regime_of
    inside, reason = regime_of(case)
    return {"inside": inside, "measure": regime_measure(case.epsilon, case.delta), "limit": REGIME,
            "reason": reason}


# ------------------------------------------------------------------ validate
def cmd_validate(args):
    from . import report
    from .sweep import FmuBlob
    from .validate import validate
    fmu = fmu_file(args.fmu, probe=False)       # one that does not instantiate fails a check (exit 1)
    if args.report:
        output_path(args.report, "painleve validate: --report")
    interfaces = None if args.interface == "all" else [args.interface]
    start = time.monotonic()
    checks = validate(fmu, interfaces=interfaces, sample=args.sample, law=dict(kappa=args.kappa, beta=args.beta))
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
    output_path(args.out, "painleve figures: --out", directory=True)
    written = make_figures(fmu, args.out, only=only, dpi=args.dpi)
    for path in written:
        print(path)
    return 0


# ------------------------------------------------------------------ sweep
def cmd_sweep(args):
    from .experiment import FMI_TYPES
    from .sweep import run_sweep
    from .sweepspec import PARAMS, SpecError, SweepSpec
    from .sweepstore import ResultStore, StoreError
    texts = {p: getattr(args, p) for p in PARAMS if getattr(args, p) is not None}
    try:
        spec = SweepSpec.from_texts(texts, samples=args.random, seed=args.seed)
    except SpecError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    try:
        ResultStore(args.out)       # the output's kind, from its name
    except StoreError as err:
        raise UsageError(f"painleve sweep: {err}") from None
    output_path(args.out, "painleve sweep: --out", directory=pathlib.Path(args.out).suffix.lower() in (".parquet", ".pq"))
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
        raise Interrupted(f"painleve sweep: interrupted; {done} of {spec.total} cases are saved in {args.out}: "
                          f"run the same command to resume") from None
    except OSError as err:
        if args.scheduler and not getattr(err, "filename", None):
            raise RunError(f"painleve sweep: cannot reach the dask scheduler {args.scheduler} "
                           f"({one_line(err)}); check the address, or leave out --scheduler for a local "
                           f"cluster") from None
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


# ------------------------------------------------------------------ couple
def cmd_couple(args):
    import tempfile

    import numpy as np
    from .cli_parser import coupled_fmu
    from .coupled import RECORD, ROD_INPUTS, TABLE_INPUTS, Setup, impulse_on_rod, impulse_on_table, write_coupled_ssp
    from .coupled_figure import coupled_figure
    from .masters import MasterUnavailable, run, steps_of
    from .ssp_check import check_ssp
    rod, rod_vars = coupled_fmu(args.rod, "rod")
    table, table_vars = coupled_fmu(args.table, "table")
    setup = Setup()
    for comp, name, value in args.start_values:
        variables, connected = (rod_vars, ROD_INPUTS) if comp == "rod" else (table_vars, TABLE_INPUTS)
        settable = sorted(n for n, w in variables.items()
                          if (w.causality == "parameter" or w.initial == "exact") and n not in connected)
        v = variables.get(name)
        if name not in settable:
            raise UsageError(f"painleve couple: --set {comp}.{name}: the {comp} has no {'such variable' if v is None else 'start value to set there'}; "
                             f"it takes {', '.join(settable)}")
        (setup.rod if comp == "rod" else setup.table)[name] = value
    try:
        n = steps_of(args.stop, args.step)
    except ValueError:
        raise UsageError(f"painleve couple: --stop {args.stop:g} is not a whole number of --step {args.step:g}; "
                         f"give a step that divides it") from None
    output_path(args.out, "painleve couple: --out")
    for option in ("ssp", "csv"):
        if getattr(args, option):
            output_path(getattr(args, option), f"painleve couple: --{option}")
    with tempfile.TemporaryDirectory(prefix="painleve-couple-") as work:
        ssp = write_coupled_ssp(pathlib.Path(work) / "coupled.ssp", rod, table, setup, stop_time=args.stop)
        problems = check_ssp(ssp)
        if problems:
            raise UsageError(f"painleve couple: the SSP is not valid: {problems[0]}"
                             + (f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""))
        start = time.monotonic()
        try:
            r = run(args.master, ssp, args.stop, args.step, RECORD)
        except MasterUnavailable as err:
            raise UsageError(f"painleve couple: {err}") from None
        except Exception as err:
            raise RunError(f"painleve couple: the {args.master} run failed: {one_line(err)}; check the --set values "
                           f"(a smaller --step keeps the explicit coupling stable)") from None
        seconds = time.monotonic() - start
        if args.ssp:
            shutil.copyfile(ssp, args.ssp)
    rod_si, case = setup.si_rod(), setup.case()
    coupled_figure(r, args.out, setup=setup, dpi=args.dpi,
                   title=f"rod on shaker table ({args.master}, h = {args.step:g} s): alpha = {rod_si.alpha:.3g}, "
                         f"epsilon = {rod_si.epsilon:.3g}, delta = {rod_si.delta:.3g}, mu = {rod_si.mu:.3g}")
    if args.csv:
        np.savetxt(args.csv, np.column_stack([r[name] for name in r.dtype.names]), delimiter=",",
                   header=",".join(r.dtype.names), comments="", fmt="%.17g")
    on_rod, on_table = impulse_on_rod(r, setup), impulse_on_table(r, args.step)
    print(f"Rod on shaker table: {rod} + {table}, master {args.master} (Jacobi, zero-order hold), "
          f"h = {args.step:g} s, t = 0 .. {args.stop:g} s ({n} steps, {seconds:.2f} s)")
    contact_time = math.sqrt(rod_si.m / rod_si.k)
    start = (f"theta0 = {case.theta0:.4g}, v0 = {case.v0:.4g}, phi0 = {case.phi0:.4g} (on the table, relative to it)"
             if case is not None else "the rod starts off the table")
    print(f"rod: alpha = {rod_si.alpha:.4g}, epsilon = {rod_si.epsilon:.4g}, delta = {rod_si.delta:.4g}, "
          f"mu = {rod_si.mu:.4g}; {start}; contact time scale sqrt(m/k) = {contact_time:.3g} s = "
          f"{contact_time / args.step:.3g} h")
    difference = on_rod - on_table
    print(f"impulse of F_N over the run: on the rod {on_rod:.6g} N s (its momentum), on the table {on_table:.6g} N s "
          f"(the inputs it held); difference {difference:+.3g} N s ({difference / on_table:+.2%}), the zero-order "
          f"hold's error: O(h) once h is well below the contact time (a contact shorter than a step escapes the "
          f"samples)")
    print(f"at t = {args.stop:g}: rod y = {r['rod.y'][-1]:.6g} m, w = {r['rod.w'][-1]:.6g} m/s, "
          f"theta = {r['rod.theta'][-1]:.6g}; table z = {r['table.position'][-1]:.6g} m, "
          f"z' = {r['table.velocity'][-1]:.6g} m/s")
    print(f"figure: {args.out}" + (f"; SSP: {args.ssp}" if args.ssp else "") + (f"; table: {args.csv}" if args.csv else ""))
    return 0


COMMANDS = {"iwc": cmd_iwc, "validate": cmd_validate, "figures": cmd_figures, "sweep": cmd_sweep,
            "couple": cmd_couple}


def user_error(err, command):
    """The one place where a failure becomes what the user reads: (exit status, one line), or None
    for a failure that is not the user's (a bug: its traceback is shown, on request)."""
    from .experiment import FmuLoadError
    from .outcome import SimulationError
    where = f"painleve {command}" if command else "painleve"
    if isinstance(err, UsageError):
        return 2, str(err)
    if isinstance(err, Interrupted):
        return 130, str(err)
    if isinstance(err, RunError):
        return 1, str(err)
    if isinstance(err, KeyboardInterrupt):
        return 130, f"{where}: interrupted (Ctrl-C); nothing more was written"
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


def main(argv=None):
    parser = build_parser()
    command = None
    try:
        args, extra = parser.parse_known_args(sys.argv[1:] if argv is None else argv)
        command = args.command
        if extra:
            unknown = next((a for a in extra if a.startswith("-")), extra[0])
            raise UsageError(f"painleve {args.command}: unknown option or parameter {unknown!r} "
                             f"(see `painleve {args.command} --help` for the options)")
        return COMMANDS[args.command](args)
    except BrokenPipeError:     # `painleve ... | head`: the reader left; say nothing more
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except (Exception, KeyboardInterrupt) as err:
        known = user_error(err, command)
        if known is None:
            if os.environ.get("PAINLEVE_TRACEBACK"):
                raise
            known = 1, (f"painleve {command or ''}: internal error {type(err).__name__}: {one_line(err)} "
                        f"(a bug: please report it with the command; PAINLEVE_TRACEBACK=1 shows the traceback)")
        status, line = known
        print(f"error: {line}", file=sys.stderr)
        return status


if __name__ == "__main__":
    sys.exit(main())
