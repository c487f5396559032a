# SPDX-License-Identifier: BSD-2-Clause
"""`painleve iwc`: one IWC case simulated with the FMU, beside the paper's prediction
(a table, or one JSON object)."""
import math

from ..experiments.strict_json import to_json
from .errors import UsageError
from . import body
from .fmus import fmu_file
from .options import DEFAULTS, case_options, fmu_option, interface_option


def add_parser(sub):
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
    case_options(iwc)
    body.body_options(iwc)
    fmu_option(iwc)
    interface_option(iwc)
    iwc.add_argument("--json", action="store_true", help="print one JSON object instead of the table")


def run(args):
    """One path for every body FMU: the case (the rod's Case from the rod's options, for an FMU of the rod's
    model without --set; a BodyCase from --set otherwise), its start and the theory there from the FMU's own
    coefficients (fmu.body_case.predict), its run through the interface asked for (Body.run); then the table
    or JSON, with the rod's closed forms beside for the rod's Case."""
    from ..experiments.case import Case
    from ..fmu.body import Body
    from ..fmu.body_case import predict
    from ..fmu.experiment import FMI_TYPES
    from ..theory import analytic as an
    generic = False
    if args.set or args.guess or args.fmu:
        fmu = fmu_file(args.fmu, allow_body=True)
        generic = body.is_body(fmu, args)
    if generic:
        case = body.iwc_case(args)
    else:
        if args.v0 is None:
            args.v0 = DEFAULTS["v0"]
        case = Case(**{k: getattr(args, k) for k in DEFAULTS})
        try:
            case.check()
        except an.HypothesisError as err:
            raise UsageError(f"painleve iwc: {err}; {_hypothesis_hint(case, err)}") from None
        fmu = fmu_file(args.fmu)
    with Body(fmu, fmi_type=FMI_TYPES[args.interface]) as b:
        predicted = predict(b, case)
        if generic and predicted.hypotheses:
            raise UsageError(f"painleve iwc: {predicted.hypotheses} at the start "
                             + ", ".join(f"{k}={v:.6g}" for k, v in predicted.start.items())
                             + "; choose a configuration inside the paradox region (painleve figures --fmu "
                               "shows it) or another --v0")
        outcome = b.run(case, predicted)
        name = b.name
    if generic:
        return body.print_iwc(args, fmu, name, case, predicted, outcome)
    return _print_rod(args, fmu, case, predicted, outcome)


def _print_rod(args, fmu, case, general, outcome):
    """The rod's table or JSON: the closed forms (analytic.predict) beside the simulation, and the theory
    from the FMU's coefficients (`general`, fmu.body_case.predict), which they must equal."""
    from ..sweep.run import predictions
    co = general.coefficients
    from_fmu = {"coefficients": {k: float(getattr(co, k)) for k in ("a", "b", "p_plus", "p_minus", "q_plus", "q_minus",
                                                                    "S_w")},
                "quadrant": general.quadrant, "theorem": general.theorem, "e": general.e, "w1_star": general.w1_star}
    if args.json:
        row = outcome.as_row()
        print(to_json({"fmu": fmu, "interface": args.interface, "case": {k: row[k] for k in DEFAULTS},
                     "predicted": predictions(case), "from_fmu": from_fmu, "regime": _regime_json(case),
                     "simulated": {k: row[k] for k in ("iwc", "w", "theta", "phi", "v", "t_return",
                                                       "compression", "stick", "lift_off", "flight_back",
                                                       "events")},
                     "errors": {k: row[k] for k in ("w_error", "phi_error", "theta_error")}}))
        return 0
    heading, rows = iwc_report(case, outcome)
    heading.append(f"from the FMU's coefficients (theory.general): {general.quadrant}, Theorem {general.theorem}, "
                   f"e = {_fmt(general.e)}" + (f", w1* = {_fmt(general.w1_star)}" if general.theorem == 2 else ""))
    print(f"IWC of the Painleve rod: {fmu} through {'Model Exchange' if args.interface == 'ME' else 'Co-Simulation'}")
    print("\n".join(heading))
    widths = [max(len(r[i]) for r in rows + [("quantity", "simulated", "analytic (eps -> 0)", "")])
              for i in range(3)]
    print(f"{'quantity':<{widths[0]}}  {'simulated':<{widths[1]}}  {'analytic (eps -> 0)':<{widths[2]}}  difference")
    for r in rows:
        print(f"{r[0]:<{widths[0]}}  {r[1]:<{widths[1]}}  {r[2]:<{widths[2]}}  {r[3]}")
    return 0


def _regime_json(case):
    from ..experiments.acceptance import REGIME, regime_measure, regime_of
    inside, reason = regime_of(case)
    return {"inside": inside, "measure": regime_measure(case.epsilon, case.delta), "limit": REGIME,
            "reason": reason}


def _hypothesis_hint(case, err):
    """What to change, for the hypothesis that failed."""
    from ..theory import analytic as an
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
    from ..experiments.acceptance import regime_of
    from ..theory import analytic as an
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
              "durations (see painleve.experiments.outcome)"),
             ("events", str(o.events), "", "mode switches")]
    return heading, rows
