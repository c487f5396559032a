# SPDX-License-Identifier: BSD-2-Clause
"""`painleve figures`: the paper's figures from simulations of the FMU."""
from . import body
from .errors import UsageError
from .fmus import fmu_file
from .options import at_least_one, dpi_value, fmu_option, output_path


def add_parser(sub):
    fig = sub.add_parser("figures", allow_abbrev=False, help="the paper's figures from simulations of the FMU",
                         description="Regenerates the paper's figures (GB: the quadrants of the (theta, phi) plane; eDelta0: the coefficient e(0, theta0) and e(delta, theta0); video: two rods, one IWC, one lift-off) from "
                                     "simulations of the FMU, with the analytic curves beside the simulated "
                                     "points. Writes PNG files, figures.json (the numbers behind each plot) "
                                     "and figures.md (how far the points lie from the curves), and, as for every body FMU, "
                                     "paradox_region.png/.json (p_plus < 0 from the FMU's own outputs).")
    fmu_option(fig)
    fig.add_argument("--out", default="out/figures", metavar="DIR", help="where to write (default %(default)s)")
    fig.add_argument("--only", metavar="NAMES", help="a comma-separated subset of GB, eDelta0, video, eLaw, paradox "
                     "(the paradox region, p_plus < 0 from the FMU's outputs, which every body FMU gets)")
    fig.add_argument("--dpi", type=dpi_value, default=150, help="PNG resolution, 10 to 1200 (default %(default)s)")
    body.body_options(fig)
    fig.add_argument("--points", type=at_least_one, default=81, metavar="N",
                     help="the paradox region: grid points per coordinate (default %(default)s)")


def run(args):
    from ..figures.paper import FIGURES, make_figures
    if args.fmu or args.set or args.guess:
        fmu = fmu_file(args.fmu, allow_body=True)
        if body.is_body(fmu, args):
            output_path(args.out, "painleve figures: --out", directory=True)
            return body.run_figures(args, fmu)
    only = None
    if args.only:
        only = [n.strip() for n in args.only.split(",") if n.strip()] or None
        unknown = [n for n in only or () if n not in FIGURES]
        if unknown:
            raise UsageError(f"painleve figures: unknown figure {unknown[0]!r}; --only takes a comma-separated "
                             f"subset of {', '.join(FIGURES)}")
    fmu = fmu_file(args.fmu)
    output_path(args.out, "painleve figures: --out", directory=True)
    written = make_figures(fmu, args.out, only=only, dpi=args.dpi, points=args.points)
    for path in written:
        print(path)
    return 0
