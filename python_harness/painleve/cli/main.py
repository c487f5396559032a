# SPDX-License-Identifier: BSD-2-Clause
"""The `painleve` command: one IWC case, validation of an FMU build, the
paper's figures from simulations of the FMU, and sweeps on dask.

    painleve iwc --theta0 1.0 --phi0 0.5 --eps 1e-4
    painleve validate build/PainleveRod.fmu --report out/validation.md
    painleve figures --out out/figures
    painleve sweep --theta0 0.5:1.4:10 --eps 1e-5:1e-3:3:log --out out/sweep.parquet
    painleve couple --master libcosim --set table.F0=100 --out out/couple.png

Bad input ends with one line that says what to change (exit status 2); a
failed validation or a simulation the FMU gave up on exits with status 1.

The command parses and delegates: each command is a module here with its options
(`add_parser`) and its run (`run`), over the harness's layers; nothing below imports the CLI."""
import os
import sys

from ..experiments import interrupt
from . import couple, figures, iwc, sweep, validate
from .errors import Interrupted, UsageError, one_line, user_error
from .options import Parser

COMMANDS = {"iwc": iwc, "validate": validate, "figures": figures, "sweep": sweep, "couple": couple}


def build_parser():
    p = Parser(prog="painleve", allow_abbrev=False,
               description="The compliant Painleve rod FMU (Hogan & Kristiansen): impact without collision "
                           "simulated beside the paper's closed forms.",
               epilog="Each subcommand has its own --help. Exit status: 0 done, 1 failed (a validation check, "
                      "a simulation), 2 bad input.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    for command in COMMANDS.values():
        command.add_parser(sub)
    return p


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
        with interrupt.caught():
            status = COMMANDS[args.command].run(args)
            interrupt.check()   # a Ctrl-C that Python dropped (in a C callback) while the command ran
        return status
    except BrokenPipeError:     # `painleve ... | head`: the reader left; say nothing more
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except (Exception, KeyboardInterrupt) as err:
        # A failure that a Ctrl-C caused (its KeyboardInterrupt dropped in a C callback) is the Ctrl-C.
        dropped = interrupt.pending() and not isinstance(err, (KeyboardInterrupt, Interrupted))
        known = user_error(KeyboardInterrupt() if dropped else err, command)
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
