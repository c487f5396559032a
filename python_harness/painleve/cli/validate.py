# SPDX-License-Identifier: BSD-2-Clause
"""`painleve validate`: the validation suite on an FMU build, as a table, JSON or a report file."""
import pathlib
import time

from ..experiments import interrupt
from ..experiments.strict_json import to_json
from . import body
from .errors import UsageError
from .fmus import DEFAULT_FMU, fmu_file
from .options import count, in_range, interface_option, output_path


def add_parser(sub):
    val = sub.add_parser("validate", allow_abbrev=False, help="the validation suite for an FMU build (for CI)",
                         description="Validates a PainleveRod.fmu: fmpy's static validation and the interface "
                                     "contract, the default experiment, then Theorem 1 and 2 cases across the "
                                     "parameter space at eps = 1e-4 ... 1e-6 through every interface the FMU "
                                     "declares. Prints a pass/fail table with the measured errors; exits 1 if "
                                     "any check fails.")
    val.add_argument("fmu", nargs="?", metavar="FMU", help=f"the FMU to validate (default: $PAINLEVE_FMU, else "
                                                           f"{DEFAULT_FMU} if there is one, else the one "
                                                           f"installed with the package)")
    val.add_argument("--fmu", dest="fmu_option", metavar="PATH", help="the FMU, as the positional FMU (a body FMU "
                     "such as TwoLinkArm.fmu is validated through the generic body path)")
    body.body_options(val, case=True)
    interface_option(val, all_choice=True)
    val.add_argument("--sample", type=count, default=24, metavar="N",
                     help="Theorem 1 cases drawn at random (fixed seed) beside the fixed ones (default 24)")
    val.add_argument("--kappa", type=in_range("kappa", "--kappa"), default=0.0,
                     help="every case with this compliance law's stiffening (its e: the rigid limit, "
                          "docs/nonlinear_compliance.md; default 0, the paper's linear law)")
    val.add_argument("--beta", type=in_range("beta", "--beta"), default=0.0,
                     help="every case with this damping growth with penetration (default 0)")
    val.add_argument("--report", metavar="PATH", help="also write the report: Markdown (.md) or JSON (.json)")
    val.add_argument("--json", action="store_true", help="print the checks as JSON instead of the table")


def run(args):
    from ..sweep.run import FmuBlob
    from ..validation import report
    from ..validation.body import validate_fmu
    if args.fmu and args.fmu_option:
        raise UsageError("painleve validate: give the FMU once (positional or --fmu)")
    args.fmu = args.fmu or args.fmu_option
    generic = False
    if args.fmu or args.set or args.guess:
        fmu = fmu_file(args.fmu, probe=False, allow_body=True)
        generic = body.is_body(fmu, args)
    if not generic:
        body.refuse_body_options(args, "validate", (("v0", None), ("delta", 1.0)))
        fmu = fmu_file(args.fmu, probe=False)       # one that does not instantiate fails a check (exit 1)
    if args.report:
        output_path(args.report, "painleve validate: --report")
    interfaces = None if args.interface == "all" else [args.interface]
    case = body.validate_case(args) if generic else None       # None: the rod's own cases
    start = time.monotonic()
    checks = validate_fmu(fmu, case, interfaces=interfaces, sample=args.sample,
                          law=dict(kappa=args.kappa, beta=args.beta))
    seconds = time.monotonic() - start
    digest = FmuBlob.read(fmu).digest
    interrupt.check()           # nothing written after a Ctrl-C
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
        print(f"Validation of {fmu}{' (generic body path)' if generic else ''} (sha256 {digest[:12]}…), "
              f"{seconds:.1f} s"
              + (f"; report in {args.report}" if args.report else ""))
        print(report.table(checks))
    return 0 if all(c.passed for c in checks) else 1


def _checks_json(checks, fmu, digest, seconds):
    return {"fmu": fmu, "sha256": digest, "seconds": seconds, "passed": all(c.passed for c in checks),
            "failed": [c.id for c in checks if not c.passed], "checks": [c.as_dict() for c in checks]}
