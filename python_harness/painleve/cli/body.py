# SPDX-License-Identifier: BSD-2-Clause
"""`painleve iwc`, `validate` and `figures` for any body FMU (`--fmu TwoLinkArm.fmu`, or the rod
through the same path with `--set`): the start, the theory and the figure from the FMU's own outputs
(fmu.body, validation.body, figures.body), through either interface, nothing body-specific here."""
import math

from ..experiments.strict_json import to_json
from .errors import UsageError
from .options import DEFAULTS, number

ROD_MODEL = "PainleveRod"      # the model whose FMU the rod's own path (its Case, its closed forms) runs
# The rod's options that a body's case has no use for: given with another value, they are an error.
ROD_ONLY = ("theta0", "phi0", "alpha", "mu", "kappa", "beta")


def assignment(text):
    """NAME=VALUE as (name, float)."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip():
        raise UsageError(f"--set/--guess take NAME=VALUE, such as theta1=2.9; got {text!r}")
    try:
        return name.strip(), number(value)
    except Exception:
        raise UsageError(f"--set/--guess {text}: {value!r} is not a finite number") from None


def body_options(parser, *, case=False):
    g = parser.add_argument_group("any body FMU (TwoLinkArm.fmu, ...): the start on the floor")
    g.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a start value (a parameter, or a state that fixes the configuration, e.g. theta1=2.9); "
                        "the states not given are solved for so that the contact point is on the floor (y = 0) "
                        "with velocity (v0, w0). Repeat it for several. With the rod's FMU it runs the rod "
                        "through the same generic path")
    g.add_argument("--guess", action="append", default=[], metavar="NAME=VALUE",
                   help="where to start solving for a state that is not given (picks a branch, e.g. theta2=-1)")
    if case:   # validate has no case options of its own
        g.add_argument("--v0", type=number, default=None, help="slip speed of the contact point (default: that of "
                       "the FMU's own start)")
        g.add_argument("--delta", type=number, default=1.0, help="contact damping, scaled (default 1)")


def is_body(fmu, args):
    """The generic path: --set or --guess was given, or the FMU is not of the rod's model."""
    from fmpy import read_model_description
    return bool(getattr(args, "set", None) or getattr(args, "guess", None)) or \
        read_model_description(fmu).modelName != ROD_MODEL


def refuse_rod_options(args, command, also=()):
    """A UsageError naming the first of the rod's options (ROD_ONLY, and `also`: (name, default) pairs) given
    with a value other than its default: the body path cannot honour it."""
    given = [k for k in ROD_ONLY if hasattr(args, k) and getattr(args, k) != DEFAULTS[k]]
    given += [k for k, default in also if getattr(args, k, default) != default]
    if given:
        raise UsageError(f"painleve {command}: --{given[0]} is an option of the rod's own path and does nothing "
                         f"for a body FMU; give the body's start values with --set NAME=VALUE")


def refuse_body_options(args, command, options):
    """A UsageError naming the first of a body's options (`options`: (name, default) pairs) given with another
    value on the rod's own path, which has its own cases and cannot honour it."""
    given = [k for k, default in options if getattr(args, k, default) != default]
    if given:
        raise UsageError(f"painleve {command}: --{given[0]} is an option of a body's case (with --set NAME=VALUE "
                         f"or a body FMU); the rod's own {command} runs its own cases")


def _case(args, epsilon):
    from ..experiments.case import BodyCase
    return BodyCase(given=tuple(assignment(s) for s in args.set), v0=args.v0, epsilon=epsilon, delta=args.delta,
                    w0=epsilon * getattr(args, "w10", 0.0), guess=tuple(assignment(s) for s in args.guess))


def _fmt(x):
    return "nan" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.6g}"


def iwc_case(args):
    """`painleve iwc`'s BodyCase from --set, --guess, --v0, --eps, --delta, --w10 (the rod's options refused)."""
    refuse_rod_options(args, "iwc")
    return _case(args, args.epsilon)


def print_iwc(args, fmu, name, case, predicted, outcome):
    """`painleve iwc`'s table or JSON for a BodyCase: the start, the theory there, the simulation."""
    interface = "Model Exchange" if args.interface == "ME" else "Co-Simulation"
    co = predicted.coefficients
    v0 = predicted.start_v0
    error = outcome.w_error
    phases = {k: getattr(outcome, k) for k in ("compression", "stick", "lift_off", "flight_back")}
    if args.json:
        print(to_json({"fmu": fmu, "model": name, "interface": args.interface, "start": predicted.start,
                       "coefficients": {k: float(getattr(co, k)) for k in ("a", "b", "p_plus", "p_minus", "q_plus",
                                                                         "q_minus", "S_w")},
                       "predicted": {"quadrant": predicted.quadrant, "theorem": predicted.theorem, "e": predicted.e,
                                     "w1_star": predicted.w1_star, "hypotheses": predicted.hypotheses},
                       "simulated": {"w": outcome.w, "v": outcome.v, "t_return": outcome.t_return,
                                     "iwc": outcome.iwc, "events": outcome.events, **phases,
                                     "state": outcome.state},
                       "errors": {"w_error": error}}))
        return 0
    print(f"IWC of {name}: {fmu} through {interface} (generic body path)")
    print("start on the floor: " + ", ".join(f"{k}={v:.6g}" for k, v in predicted.start.items()))
    print(f"coefficients there: a={float(co.a):.4g} b={float(co.b):.4g} p_+={float(co.p_plus):.4g} "
          f"p_-={float(co.p_minus):.4g} q_+={float(co.q_plus):.4g} q_-={float(co.q_minus):.4g} "
          f"S_w={float(co.S_w):.4g}; eps={predicted.epsilon:g} delta={predicted.delta:g}")
    print(f"quadrant: {predicted.quadrant}; " + (predicted.hypotheses or f"Theorem {predicted.theorem} applies")
          + (f"; w1* = {predicted.w1_star:.6g}" if predicted.theorem == 2 else ""))
    print(f"{'quantity':<22}{'simulated':<16}{'analytic (eps -> 0)':<22}difference")
    expected = "IWC" if predicted.theorem == 1 or case.w0 / case.epsilon < predicted.w1_star else "lift-off"
    print(f"{'outcome':<22}{'IWC' if outcome.iwc else 'lift-off':<16}{expected:<22}")
    if expected == "lift-off":
        print(f"{'w at return':<22}{_fmt(outcome.w):<16}{'O(eps)':<22}w/eps = {outcome.w / case.epsilon:.3g}")
    else:
        diff = f"{error:+.3e} ({error / predicted.e:+.3%} of e)" if not math.isnan(predicted.e) else ""
        print(f"{'w/v0 at return':<22}{_fmt(outcome.w / v0):<16}{_fmt(predicted.e) + ' (e)':<22}{diff}")
    print(f"{'v at return':<22}{_fmt(outcome.v):<16}{'0 + O(eps)':<22}")
    print(f"{'t_return':<22}{_fmt(outcome.t_return):<16}{'O(eps ln 1/eps)':<22}events: {outcome.events}")
    print("phases: " + ", ".join(f"{k} {_fmt(v)}" for k, v in phases.items()))
    return 0


def validate_case(args):
    """`painleve validate`'s BodyCase from --set, --guess, --v0, --delta (the rod's options refused)."""
    refuse_rod_options(args, "validate", also=(("sample", 24),))
    return _case(args, 1e-4)


def run_figures(args, fmu):
    from ..figures.body import paradox_figure
    if args.only:
        raise UsageError("painleve figures: --only chooses among the rod's figures; a body FMU has one, its "
                         "paradox region")
    if args.guess:
        raise UsageError("painleve figures: --guess picks a branch of a start solved onto the floor; the paradox "
                         "region solves none (give its fixed start values with --set)")
    given = dict(assignment(s) for s in args.set)
    for path in paradox_figure(fmu, args.out, given=given, n=args.points, dpi=args.dpi):
        print(path)
    return 0
