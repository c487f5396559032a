# SPDX-License-Identifier: BSD-2-Clause
"""Validation of any body FMU (`painleve validate --fmu TwoLinkArm.fmu`), every run through fmu.body
(validate_fmu): at the user's configuration (a case), the start found on the floor, the paradox there
(p_plus < 0, Theorem 1 or 2's hypotheses), and, through each interface asked for, the IWC converging
to the e of the FMU's own coefficients as eps falls (Theorem 1: w/v0 -> e); with no case, on the rod's
model, the rod's own suite (validation.suite: its cases in closed form)."""
from dataclasses import replace

from ..fmu.body import Body, BodyError
from ..fmu.body_case import predict, run_body
from ..fmu.experiment import FMI_TYPES
from .report import Check
from .suite import interfaces_of, validate

EPSILONS = (1e-4, 1e-5, 1e-6)
FINAL = 0.01        # |w/v0 - e| <= FINAL e at the smallest eps (the rod's thin wedge: a few % at 1e-5)


def validate_fmu(fmu, case=None, *, interfaces=None, sample=24, law=None):
    """`painleve validate`'s checks of a body FMU through `interfaces` ("ME", "CS"; default: every one the
    FMU declares), each case run by fmu.body.Body: with `case` (an IWCCase, a BodyCase from the user's
    start values) validate_body; without, the rod's suite (validation.suite.validate: its static contract,
    default experiment and Theorem 1 and 2 cases with `sample` random ones, under the compliance law
    `law`), which only the rod's model has."""
    if case is None:
        return validate(fmu, interfaces=interfaces, sample=sample, law=law)
    return validate_body(fmu, case, interfaces=tuple(interfaces or interfaces_of(fmu)))


def validate_body(fmu, case, epsilons=EPSILONS, interfaces=("ME",)):
    checks = []
    for i, interface in enumerate(interfaces):
        with Body(fmu, fmi_type=FMI_TYPES[interface]) as body:
            if i == 0:
                first = _start_checks(body, case, epsilons[0], checks)
                if first is None:
                    return checks
            checks += _convergence_checks(body, case, epsilons, interface, first.e)
    return checks


def _start_checks(body, case, eps, checks):
    """The checks of the start at the first eps, appended to `checks`; its prediction if a theorem covers it."""
    try:
        first = predict(body, replace(case, epsilon=eps))
    except BodyError as err:
        checks.append(Check("body/start/found", "a start on the floor (y = 0, v = v0, w = w0)", str(err), "found",
                            False))
        return None
    co = first.coefficients
    checks.append(Check("body/start/found", "a start on the floor (y = 0, v = v0, w = w0)",
                        ", ".join(f"{k} = {v:.6g}" for k, v in first.start.items()), "found", True))
    checks.append(Check("body/start/paradox", "the start is in the Painleve paradox and a theorem covers it",
                        f"p_plus = {float(co.p_plus):.4g}, b = {float(co.b):.4g} ({first.quadrant}); "
                        f"{first.hypotheses or f'Theorem {first.theorem}'}",
                        "p_plus < 0 and the hypotheses of Theorem 1 or 2", not first.hypotheses))
    return None if first.hypotheses else first


def _convergence_checks(body, case, epsilons, interface, e):
    checks, errors = [], []
    for eps in epsilons:
        predicted, outcome = run_body(body, replace(case, epsilon=eps))
        v0 = predicted.start_v0
        err = outcome.w_error
        errors.append(abs(err))
        checks.append(Check(f"body/{interface}/eps{eps:g}/iwc", "w/v0 at the return to y = 0 against e (eq eGeneral)",
                            f"w/v0 = {outcome.w / v0:.6g}, e = {predicted.e:.6g}, error {err:+.3e} "
                            f"({err / predicted.e:+.2%}), stuck: {outcome.iwc}",
                            "the IWC happens (the contact point sticks)", outcome.iwc,
                            numbers=dict(epsilon=eps, w_over_v0=outcome.w / v0, e=predicted.e)))
    falls = all(b <= a for a, b in zip(errors, errors[1:])) or errors[-1] < errors[0] / 10
    checks.append(Check(f"body/{interface}/all/convergence", "the error falls with eps and is small at the smallest",
                        " -> ".join(f"{x:.2e}" for x in errors) + f" (e = {e:.6g})",
                        f"falling, and <= {FINAL:.0%} of e at eps = {epsilons[-1]:g}",
                        falls and errors[-1] <= FINAL * e, numbers=dict(errors=errors)))
    return checks
