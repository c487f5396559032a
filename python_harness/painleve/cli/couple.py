# SPDX-License-Identifier: BSD-2-Clause
"""`painleve couple`: the SI rod on a shaker table, co-simulated from an SSP archive in one
of three masters; a figure, the impulses on both sides, the state at the end."""
import argparse
import math
import pathlib
import re
import shutil
import time

from .errors import RunError, UsageError, one_line
from .fmus import DEFAULT_ROD_FMU, DEFAULT_TABLE_FMU, coupled_fmu
from .options import dpi_value, number, output_path, positive


def add_parser(sub):
    from ..coupling.coupled import COUPLINGS
    from ..coupling.masters import MASTERS
    cp = sub.add_parser("couple", allow_abbrev=False, help="the rod on a shaker table, co-simulated from an SSP file",
                        description="Couples PainleveRodSI.fmu (the rod in SI units, with a moving floor as input) "
                                    "with ShakerTable.fmu (a table top on a spring-damper, shaken by a harmonic "
                                    "force, loaded by the rod's contact forces) in an SSP archive "
                                    "(SystemStructure.ssd + resources/*.fmu), checks the archive, runs it in a "
                                    "co-simulation master (fixed communication step, Jacobi with zero-order hold) "
                                    "and writes a figure: the rod and the table over time, the forces on both "
                                    "sides. The table holds over each step the rod's contact forces averaged over "
                                    "the step before (the impulse the rod received / h), so it receives exactly the "
                                    "rod's impulses whatever the contact's duration; --coupling instantaneous hands "
                                    "it the forces at the communication points instead. Prints the system's momentum "
                                    "balance (closed to rounding with the step means).")
    cp.add_argument("--rod", metavar="PATH",
                    help=f"the rod's FMU (default {DEFAULT_ROD_FMU} if there is one, else the one installed with "
                         f"the package; with --fmi-version 3 build/fmi3/PainleveRodSI.fmu)")
    cp.add_argument("--table", metavar="PATH",
                    help=f"the table's FMU (default {DEFAULT_TABLE_FMU} if there is one, else the one installed "
                         f"with the package; with --fmi-version 3 build/fmi3/ShakerTable.fmu)")
    cp.add_argument("--master", choices=MASTERS, default="fmpy",
                    help="fmpy (fmpy.ssp), libcosim (libcosimpy) or ecos (ecospy); the last two are installed by "
                         "`bash run.sh test` (default %(default)s)")
    cp.add_argument("--fmi-version", choices=("2", "3"), default="2",
                    help="couple the FMI 2.0 FMUs (build/*.fmu) or the FMI 3.0 ones (build/fmi3/*.fmu), which "
                         "ecos runs and fmpy's SSP master and libcosim do not (default %(default)s)")
    cp.add_argument("--coupling", choices=tuple(COUPLINGS), default="mean",
                    help="what the table's loads are connected to: the rod's contact forces averaged over the last "
                         "communication step (mean: the impulse the rod received / h) or their values at the "
                         "communication points (instantaneous: an impulse between two samples is lost) "
                         "(default %(default)s)")
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


def run(args):
    import tempfile

    import numpy as np

    from ..coupling.coupled import RECORD, ROD_INPUTS, TABLE_INPUTS, Setup, write_coupled_ssp
    from ..coupling.masters import FMI3_MASTERS, NO_FMI3, MasterUnavailable, run, steps_of
    from ..coupling.ssp_check import check_ssp
    from ..figures.coupled import coupled_figure
    if args.fmi_version == "3" and args.master not in FMI3_MASTERS:
        raise UsageError(f"painleve couple: --fmi-version 3 --master {args.master}: {NO_FMI3[args.master]}; "
                         f"--master {' or '.join(FMI3_MASTERS)} runs FMI 3.0 FMUs")
    rod, rod_vars = coupled_fmu(args.rod, "rod", f"{args.fmi_version}.0")
    table, table_vars = coupled_fmu(args.table, "table", f"{args.fmi_version}.0")
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
        ssp = write_coupled_ssp(pathlib.Path(work) / "coupled.ssp", rod, table, setup, stop_time=args.stop,
                                coupling=args.coupling)
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
    print(f"Rod on shaker table: {rod} + {table} (FMI {args.fmi_version}.0), master {args.master} "
          f"(Jacobi, zero-order hold), {args.coupling} coupling, "
          f"h = {args.step:g} s, t = 0 .. {args.stop:g} s ({n} steps, {seconds:.2f} s)")
    contact_time = math.sqrt(rod_si.m / rod_si.k)
    start = (f"theta0 = {case.theta0:.4g}, v0 = {case.v0:.4g}, phi0 = {case.phi0:.4g} (on the table, relative to it)"
             if case is not None else "the rod starts off the table")
    print(f"rod: alpha = {rod_si.alpha:.4g}, epsilon = {rod_si.epsilon:.4g}, delta = {rod_si.delta:.4g}, "
          f"mu = {rod_si.mu:.4g}; {start}; contact time scale sqrt(m/k) = {contact_time:.3g} s = "
          f"{contact_time / args.step:.3g} h")
    print_balance(r, setup, args.step, args.coupling)
    print(f"at t = {args.stop:g}: rod y = {r['rod.y'][-1]:.6g} m, w = {r['rod.w'][-1]:.6g} m/s, "
          f"theta = {r['rod.theta'][-1]:.6g}; table z = {r['table.position'][-1]:.6g} m, "
          f"z' = {r['table.velocity'][-1]:.6g} m/s")
    print(f"figure: {args.out}" + (f"; SSP: {args.ssp}" if args.ssp else "") + (f"; table: {args.csv}" if args.csv else ""))
    return 0


def print_balance(r, setup, step, coupling):
    """The impulses of F_N on both sides and the system's vertical momentum balance."""
    from ..coupling.coupled import impulse_on_rod, impulse_on_table, momentum_balance
    b = momentum_balance(r, setup, step, coupling)
    on_rod, on_table = impulse_on_rod(r, setup), impulse_on_table(r, step)
    print(f"impulse of F_N over the run: on the rod {on_rod:.9g} N s (its momentum), on the table {on_table:.9g} N s "
          f"(the inputs it held), in flight {b.in_flight:.3g} N s (the rod's last step: the table holds it next)")
    print(f"momentum balance (vertical, N s): rod {b.rod:+.9g} + table {b.table:+.9g} = gravity {b.gravity:+.9g} + "
          f"table's mount {b.mount:+.9g} + drive {b.drive:+.9g} + in flight {b.in_flight:+.3g}; residual "
          f"{b.residual:+.3g} N s ({b.residual / on_rod:+.2e} of the rod's impulse)"
          + (": the impulses the samples of F_N missed (a contact shorter than a step escapes them)"
             if coupling == "instantaneous" else ": closed, the table took every impulse the rod received"))


def start_value(text):
    """COMPONENT.NAME=VALUE, a start value for the rod or the table (checked against the FMU later)."""
    m = re.fullmatch(r"(rod|table)\.([A-Za-z_][A-Za-z0-9_]*)=(.+)", text)
    if not m:
        raise argparse.ArgumentTypeError(f"{text!r} is not COMPONENT.NAME=VALUE with COMPONENT rod or table "
                                         f"(e.g. rod.k=2e5, table.M=1e6)")
    return m.group(1), m.group(2), number(m.group(3))
