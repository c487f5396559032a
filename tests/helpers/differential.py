# SPDX-License-Identifier: BSD-2-Clause
"""The differential test's machinery (tests/differential/, bench/differential.py): random legal
cases of every model, the FMUs run by fmpy directly (its FMI 2.0 / 3.0 classes in Co-Simulation,
fmpy.simulate_fmu's CVode in Model Exchange; none of the harness's runners), and independent
references written in the tests:

* PainleveRod: the harness's event-driven solve_ivp reference (painleve.experiments.reference,
  DOP853), from the rod's start on the floor to its return to y = 0 after the contact;
* PainleveRodSI: the same reference through the SI model's scaling to the rod (docs/si_model.md §7:
  alpha = m l^2/J, epsilon = sqrt(m g/(k l)), delta = c/sqrt(m k), time by sqrt(l/g), velocities
  by sqrt(g l), phi by sqrt(l/g));
* TwoLinkArm: the event-driven Filippov arm of helpers.arm_filippov (DOP853), from the tip on the
  floor with w = 0 and slip speed v0 to the return to y = 0;
* ShakerTable: its closed form (helpers.shaker_table).

A case is compared where the reference's contact is over: the FMU is run to the reference's return
time and its state there is compared with the reference's, each quantity in its scale (velocities by
the start's speed v0, angles in radians, angular rates by v0 over the length or their size if
larger; the table's position and velocity by its motion's amplitude). In flight after a damped
lift-off nothing switches, so where the importer's solver put the lift-off moves this state only by
the solver's error."""
import collections
import functools
import math
import pathlib
import shutil
import tempfile
import time

import numpy as np

from . import arm_filippov as AF
from . import shaker_table as ST
from .arm_lagrange import Arm, coefficients

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODELS = ("PainleveRod", "PainleveRodSI", "TwoLinkArm", "ShakerTable")
VERSIONS = ("2.0", "3.0")
K_BOUND = 100               # a run at relative tolerance tol may differ from the reference by K tol
DEFAULT_BOUND = 1e-4        # ... and by this at the FMU's default tolerance
SENSITIVITY_STEP = 1e-10    # the start angle's move that finds cases near a separatrix
SENSITIVITY_LIMIT = 1e-7    # ... by moving the reference's answer more than this
REF_RTOL = 1e-11            # the references' DOP853 tolerance (their answers move < 1e-9 to 1e-12)
REFINED = collections.Counter()     # Model Exchange runs run again on a finer grid, by model name (Loaded.me)


def fmu_path(model, version):
    return str(ROOT / "build" / ("fmi3" if version == "3.0" else "") / f"{model}.fmu")


# ------------------------------------------------------------------------------------- the FMUs
class Loaded:
    """One FMU extracted once: its model description and the value references of its variables."""

    def __init__(self, path):
        from fmpy import extract, read_model_description
        self.path = path
        self.md = read_model_description(path)
        self.version = self.md.fmiVersion
        self.dir = extract(path, unzipdir=tempfile.mkdtemp(prefix="differential-"))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}

    def close(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def cs(self, start, stop_time, outputs, tolerance=None, steps=1, every_step=None):
        """Co-Simulation from t = 0 to stop_time in `steps` equal communication steps, the FMU's
        relative tolerance `tolerance` (None: not given, the FMU's default). Returns the outputs at
        the end; raises fmpy's FMICallException on a status worse than a warning. every_step(t, get)
        is called after each step."""
        from fmpy.fmi2 import FMU2Slave
        from fmpy.fmi3 import FMU3Slave
        ident = self.md.coSimulation.modelIdentifier
        fmi3 = self.version.startswith("3")
        cls = FMU3Slave if fmi3 else FMU2Slave
        fmu = cls(guid=self.md.guid, unzipDirectory=self.dir, modelIdentifier=ident, instanceName="differential")
        vrs = [self.vr[n] for n in start]
        values = [float(v) for v in start.values()]
        try:
            fmu.instantiate()
            try:
                if fmi3:
                    fmu.setFloat64(vrs, values)
                    fmu.enterInitializationMode(tolerance=tolerance, startTime=0.0, stopTime=stop_time)
                else:
                    fmu.setReal(vrs, values)
                    fmu.setupExperiment(tolerance=tolerance, startTime=0.0, stopTime=stop_time)
                    fmu.enterInitializationMode()
                fmu.exitInitializationMode()
                get = (lambda names: fmu.getFloat64([self.vr[n] for n in names])) if fmi3 else \
                    (lambda names: fmu.getReal([self.vr[n] for n in names]))
                h = stop_time / steps
                for i in range(steps):
                    t = i * h
                    size = stop_time - t if i == steps - 1 else h      # the last step ends at stop_time exactly
                    fmu.doStep(currentCommunicationPoint=t, communicationStepSize=size)
                    if every_step:
                        every_step((i + 1) * h, get)
                out = dict(zip(outputs, get(outputs)))
                fmu.terminate()
            finally:
                fmu.freeInstance()
        finally:
            fmu.freeLibrary()
        return out

    def me(self, start, stop_time, outputs, rtol, intervals=500):
        """Model Exchange under fmpy.simulate_fmu's CVode at relative tolerance rtol, output grid of
        `intervals` equal steps (500: fmpy's default). Returns the outputs at stop_time.

        fmpy's CVode takes at most 500 steps from one output point to the next, and says mxstep
        past them. A stiff transient resolved to a tight tolerance needs more: the contact's
        lightly damped ringing at a stick entry takes about 600 steps at rtol 1e-9, where BDF of
        order 4 and 5 is unstable and CVode cuts its steps. Such a run is run again, as an fmpy
        user would, on a grid 10 times finer (counted in REFINED)."""
        from fmpy import simulate_fmu
        for grid in (intervals, 10 * intervals):
            try:
                res = simulate_fmu(self.dir, model_description=self.md, fmi_type="ModelExchange", solver="CVode",
                                   relative_tolerance=rtol, start_time=0.0, stop_time=stop_time,
                                   output_interval=stop_time / grid, start_values=dict(start), output=list(outputs),
                                   validate=False)
                break
            except RuntimeError as e:
                if "mxstep" not in str(e) or grid != intervals:
                    raise
                REFINED[self.md.modelName] += 1
        row = res[-1]
        # fmpy ends a run at the first time it takes as the stop time: math.isclose, within 1e-9 of it
        assert math.isclose(res["time"][-1], stop_time), (res["time"][-1], stop_time)
        return {n: float(row[n]) for n in outputs}


# ------------------------------------------------------------------------------------- the cases
def _log_uniform(rng, lo, hi):
    return float(10 ** rng.uniform(math.log10(lo), math.log10(hi)))


class Case:
    """One physical case: the model, the FMU's start values, where to compare (t_end), the reference
    (a callable giving the compared quantities and their scales at t_end), and the sensitivity probe
    (the reference of the case with its start angle moved by SENSITIVITY_STEP; None if the model
    has no separatrix), and the phases the run covers whose errors add (at least 1): the rod's
    contacts, each an IWC that amplifies what it is entered with, and the table's periods, over
    each of which an integrator's phase error grows; the bound is per phase (bound_of)."""

    def __init__(self, model, name, start, t_end, quantities, reference, perturbed=None, phases=1.0):
        self.model, self.name, self.start, self.t_end = model, name, start, t_end
        self.quantities, self.reference, self.perturbed = quantities, reference, perturbed
        self.phases = max(1.0, phases)

    def __repr__(self):
        return f"{self.model}[{self.name}]"


# PainleveRod and PainleveRodSI ---------------------------------------------------------------------
def rod_parameters(rng):
    """A rod in the Painleve wedge: alpha, mu > mu_P, theta0 inside (theta_1, theta_2), phi0 and w10
    for Theorem 1 (b < 0) or, one case in four, Theorem 2 (b > 0, w10 either side of w1*)."""
    from painleve.theory import analytic as an
    from painleve.experiments.case import Case as RodCase
    while True:
        alpha = float(rng.uniform(1.0, 8.0))
        mu_p = 2 * math.sqrt(1 + alpha) / alpha
        mu = float(mu_p * rng.uniform(1.15, 3.0))
        t1, t2 = an.theta_1(alpha=alpha, mu=mu), an.theta_2(alpha=alpha, mu=mu)
        theta0 = float(t1 + (t2 - t1) * rng.uniform(0.1, 0.9))
        phi_b = 1 / math.sqrt(math.sin(theta0))          # b = 0 there
        theorem2 = rng.uniform() < 0.25
        phi0 = float(phi_b * (rng.uniform(1.05, 1.5) if theorem2 else rng.uniform(0.0, 0.95)))
        delta = float(rng.uniform(0.2, 3.0))
        eps = _log_uniform(rng, 1e-5, 1e-3)
        v0 = float(rng.uniform(0.5, 2.0))
        w10 = float(-rng.uniform(0.0, 1.0))
        case = RodCase(theta0=theta0, phi0=phi0, v0=v0, delta=delta, epsilon=eps, w10=w10, alpha=alpha, mu=mu)
        if theorem2:
            w1s = float(an.predict(case).w1_star)
            case = RodCase(theta0=theta0, phi0=phi0, v0=v0, delta=delta, epsilon=eps,
                           w10=float(w1s * rng.uniform(0.3, 1.7)), alpha=alpha, mu=mu)
        try:
            case.check()
        except Exception:
            continue
        return case


@functools.lru_cache(maxsize=None)
def rod_reference(alpha, mu, delta, epsilon, v0, w0, theta0, phi0, t_end=None):
    """The rod's state (t, v, w, theta, phi, scaled) at its return to y = 0 after the first contact
    (t_end None) or at t_end, through whatever flights and contacts come, by the harness's reference."""
    from painleve.experiments.reference import Rod, simulate
    rod = Rod(alpha=alpha, mu=mu, delta=delta, epsilon=epsilon)
    horizon = 50 * epsilon * math.log(1 / epsilon) * (1 + delta) + 1.0
    run = simulate(rod, [0.0, v0, 0.0, w0, theta0, phi0], t_end or horizon, method="DOP853", rtol=REF_RTOL,
                   stop_at_return=t_end is None, record=True)
    if t_end is None and not run.returned:
        raise RuntimeError(f"the reference rod did not return by t = {horizon}")
    # A hop above the floor that lies inside one step after a damped lift-off is not seen (y crosses 0
    # twice); the run then re-enters contact where the force bracket turns positive, above the floor.
    for mode, _, t1, name in run.segments:
        if name == "re-contact" and run.x[2][np.searchsorted(run.t, t1)] > 0:
            raise RuntimeError(f"the reference missed a hop above the floor before t = {t1}")
    x = run.x_stop
    contacts = 1 + sum(name in ("touch-down", "re-contact") for *_, name in run.segments)
    return dict(t=run.t_stop, v=x[1], w=x[3], theta=x[4], phi=x[5], modes=run.modes, contacts=contacts)


REDRAWN = dict(TwoLinkArm=0, PainleveRod=0, PainleveRodSI=0)   # draws replaced (the reference could not compare)


def _rod_times(rng, key, c, model):
    """Where a rod case is compared (scaled time): at the return after the first contact, or in half
    the cases up to 1.5 time units later, through the flight and what follows (another touch-down,
    slip, stick: Co-Simulation's hand-overs between its flight and contact solvers). A later time
    whose reference fails (the modes chatter where the rod comes to lie on the floor) falls back to
    the return, counted in REDRAWN. Returns (t_end, the later time or None, the contacts up to t_end)."""
    returned = rod_reference(*key, c.theta0, c.phi0)
    if rng.uniform() < 0.5:
        return returned["t"], None, returned["contacts"]
    t_end = returned["t"] + float(rng.uniform(0.05, 1.5))
    try:
        later = rod_reference(*key, c.theta0, c.phi0, t_end)
    except Exception:
        REDRAWN[model] += 1
        return returned["t"], None, returned["contacts"]
    return t_end, t_end, later["contacts"]


def rod_case(rng, index):
    c = rod_parameters(rng)
    key = (c.alpha, c.mu, c.delta, c.epsilon, c.v0, c.epsilon * c.w10)
    t_end, later, contacts = _rod_times(rng, key, c, "PainleveRod")
    scales = dict(v=c.v0, w=c.v0, theta=1.0, phi=c.v0)

    def reference(theta0=c.theta0):
        r = rod_reference(*key, theta0, c.phi0, later)
        return {n: r[n] for n in scales}, scales

    start = dict(alpha=c.alpha, mu=c.mu, delta=c.delta, epsilon=c.epsilon, x=0.0, v=c.v0, y=0.0,
                 w=c.epsilon * c.w10, theta=c.theta0, phi=c.phi0)

    def perturbed():
        return reference(c.theta0 + SENSITIVITY_STEP)[0]
    return Case("PainleveRod", f"{index}", start, t_end, ("v", "w", "theta", "phi"),
                lambda: reference(), perturbed, phases=contacts)


def si_case(rng, index):
    """An SI rod whose scaled form is a random rod case: m, l, g random, J, k, c from alpha, eps, delta."""
    c = rod_parameters(rng)
    m, l, g = _log_uniform(rng, 0.05, 5.0), _log_uniform(rng, 0.05, 2.0), _log_uniform(rng, 1.0, 100.0)
    J, k = m * l * l / c.alpha, m * g / (l * c.epsilon ** 2)
    cd = c.delta * math.sqrt(m * k)
    # the scaled parameters as the FMU computes them from the SI ones (rounding included)
    alpha, eps, delta = m * l * l / J, math.sqrt(m * g / (k * l)), cd / math.sqrt(m * k)
    T, U = math.sqrt(l / g), math.sqrt(g * l)
    key = (alpha, c.mu, delta, eps, c.v0, eps * c.w10)
    t_end, later, contacts = _rod_times(rng, key, c, "PainleveRodSI")
    scales = dict(v=c.v0, w=c.v0, theta=1.0, phi=c.v0)

    def reference(theta0=c.theta0):
        r = rod_reference(*key, theta0, c.phi0, later)
        return {n: r[n] for n in scales}, scales

    start = dict(m=m, l=l, J=J, g=g, k=k, c=cd, mu=c.mu, x=0.0, v=c.v0 * U, y=0.0, w=eps * c.w10 * U,
                 theta=c.theta0, phi=c.phi0 / T)
    case = Case("PainleveRodSI", f"{index}", start, t_end * T, ("v", "w", "theta", "phi"),
                lambda: reference(), lambda: reference(c.theta0 + SENSITIVITY_STEP)[0], phases=contacts)
    case.to_scaled = lambda out: dict(v=out["v"] / U, w=out["w"] / U, theta=out["theta"], phi=out["phi"] * T)
    return case


# TwoLinkArm ------------------------------------------------------------------------------------------
def arm_parameters(rng, v0=1.0):
    """A random arm with its tip on the floor (y = 0), w = 0 and slip speed v0, in Theorem 1's
    quadrant (p_+ < 0, b < 0, q_+ < 0 < q_-): masses, lengths, inertias, angles and mu drawn until
    the coefficients (helpers.arm_lagrange) say so; eps in 1e-5..1e-3 gives k, delta gives c."""
    from painleve.theory import general as G
    while True:
        m1, m2 = _log_uniform(rng, 0.2, 3.0), _log_uniform(rng, 0.2, 3.0)
        l1, l2 = float(rng.uniform(0.2, 1.2)), float(rng.uniform(0.2, 1.2))
        J1, J2 = m1 * l1 ** 2 * float(rng.uniform(0.02, 0.15)), m2 * l2 ** 2 * float(rng.uniform(0.02, 0.15))
        th = np.array([rng.uniform(-math.pi, 0.0), rng.uniform(-math.pi, 0.0)])
        H = float(-(l1 * math.sin(th[0]) + l2 * math.sin(th[1])))
        mu = float(rng.uniform(0.4, 3.0))
        arm = Arm(H=H, m1=m1, l1=l1, J1=J1, m2=m2, l2=l2, J2=J2, g=9.81, mu=mu)
        Jac = np.array([[-l1 * math.sin(th[0]), -l2 * math.sin(th[1])], [l1 * math.cos(th[0]), l2 * math.cos(th[1])]])
        if H <= 0.05 * (l1 + l2) or abs(np.linalg.det(Jac)) < 0.05 * l1 * l2:
            continue
        om = np.linalg.solve(Jac, [v0, 0.0])
        co = G.Coefficients.of(coefficients(arm, th, om))
        try:
            G.check(co, 1, delta=1.0, v0=v0)
        except Exception:
            continue
        if float(co.p_plus) > -0.02:
            continue
        eps = _log_uniform(rng, 1e-5, 1e-3)
        delta = float(rng.uniform(0.3, 2.0))
        M, L = m1 + m2, l1 + l2
        k = M * 9.81 / (L * eps ** 2)
        return dict(m1=m1, m2=m2, l1=l1, l2=l2, J1=J1, J2=J2, g=9.81, mu=mu, H=H, k=k,
                    c=delta * math.sqrt(M * k)), th, om


@functools.lru_cache(maxsize=None)
def _arm_reference(params_items, th, om):
    run = AF.simulate(dict(params_items), np.array(th), np.array(om), rtol=REF_RTOL)
    if run.t_contact_end is None or not run.t_contact_end > 0 or run.events[-1] != "return":
        raise RuntimeError(f"the reference arm did not return: {run.events}")
    return run


def arm_reference(params, th, om):
    return _arm_reference(tuple(sorted(params.items())), tuple(map(float, th)), tuple(map(float, om)))


def arm_on_floor(params, theta1, theta2, v0=1.0, w0=0.0):
    """The arm with H chosen so the tip is at y = 0 at (theta1, theta2) and omega so its velocity is (v0, w0)."""
    p = dict(params, H=-(params["l1"] * math.sin(theta1) + params["l2"] * math.sin(theta2)))
    th = np.array([theta1, theta2])
    return p, th, AF.tip_velocity_rates(p, th, v0, w0)


ARM_OUT = ("v", "w", "theta1", "theta2", "omega1", "omega2")


def arm_quantities(run):
    return dict(v=run.v, w=run.w, theta1=run.th[0], theta2=run.th[1], omega1=run.om[0], omega2=run.om[1])


def arm_case(rng, index, v0=1.0):
    """A random arm IWC; a draw whose reference does not leave the floor for good (a re-contact
    that ends in lasting contact: no return to compare at) is drawn again, and counted in REDRAWN."""
    while True:
        params, th, om = arm_parameters(rng, v0)
        try:
            run = arm_reference(params, th, om)
            break
        except (RuntimeError, AF.ArmReferenceError):
            REDRAWN["TwoLinkArm"] += 1
    # the rates' scale: v0 over the length, or their size where the links swing faster (a solver
    # holds a rate to tol of its size)
    rate = max(v0 / (params["l1"] + params["l2"]), *np.abs(om), *np.abs(run.om))
    scales = dict(v=v0, w=v0, theta1=1.0, theta2=1.0, omega1=rate, omega2=rate)

    def perturbed():
        p, th2, om2 = arm_on_floor(params, th[0] + SENSITIVITY_STEP, th[1], v0)
        r = AF.simulate(p, th2, om2, t_end=run.t, stop_at_return=False, rtol=REF_RTOL)
        return arm_quantities(r)

    start = dict(params, theta1=th[0], theta2=th[1], omega1=om[0], omega2=om[1])
    return Case("TwoLinkArm", f"{index}", start, run.t, ARM_OUT, lambda: (arm_quantities(run), scales), perturbed)


# ShakerTable -------------------------------------------------------------------------------------------
def table_case(rng, index):
    """A random forced, underdamped table (M, K, C, F0, f) from a random start; no load."""
    M, K = _log_uniform(rng, 1.0, 50.0), _log_uniform(rng, 1e3, 1e5)
    zeta = _log_uniform(rng, 0.005, 0.5)
    C = 2 * zeta * math.sqrt(K * M)
    F0, f = float(rng.uniform(1.0, 100.0)), _log_uniform(rng, 0.5, 20.0)
    wn = math.sqrt(K / M)
    amp = F0 / K
    z0, vz0 = float(rng.uniform(-3, 3) * amp), float(rng.uniform(-3, 3) * amp * wn)
    # at most 5 periods of the faster of the free and the forced oscillation
    fastest = max(wn, 2 * math.pi * f)
    t_end = float(rng.uniform(0.2, 1.0)) * min(2.5, 5 * 2 * math.pi / fastest)
    p = dict(M=M, K=K, C=C, F0=F0, frequency=f)
    scales = dict(position=4 * amp + abs(z0) + abs(vz0) / wn)
    scales["velocity"] = scales["position"] * fastest

    def reference():
        (z,), (vz,) = ST.closed_form([t_end], 0.0, z0, vz0, 0.0, **p)
        return dict(position=z, velocity=vz), scales
    start = dict(p, position=z0, velocity=vz0)
    return Case("ShakerTable", f"{index}", start, t_end, ("position", "velocity"), reference,
                phases=t_end * fastest / (2 * math.pi))


MAKERS = dict(PainleveRod=rod_case, PainleveRodSI=si_case, TwoLinkArm=arm_case, ShakerTable=table_case)


def cases(model, n, seed):
    rng = np.random.default_rng([seed, MODELS.index(model)])
    return [MAKERS[model](rng, i) for i in range(n)]


def scaled_difference(a, b, scales):
    return max(abs(a[n] - b[n]) / scales[n] for n in scales)


def sensitive(case):
    """The reference's move under SENSITIVITY_STEP of the start angle exceeds SENSITIVITY_LIMIT
    (or the perturbed reference fails): the case sits near a separatrix and is left out."""
    if case.perturbed is None:
        return False
    ref, scales = case.reference()
    try:
        moved = case.perturbed()
    except Exception:
        return True
    return scaled_difference(ref, moved, scales) > SENSITIVITY_LIMIT


# ------------------------------------------------------------------------------------- the runs
class Outcome:
    """One FMU run against its reference: error (a message) or the scaled difference and the bound."""

    def __init__(self, case, version, interface, tol, bound, diff=None, error=None, seconds=0.0, values=None):
        self.case, self.version, self.interface, self.tol, self.bound = case, version, interface, tol, bound
        self.diff, self.error, self.seconds, self.values = diff, error, seconds, values

    @property
    def failed(self):
        return self.error is not None or not (self.diff <= self.bound)

    def __repr__(self):
        what = f"error {self.error}" if self.error else f"diff {self.diff:.3g} > bound {self.bound:.3g}"
        tol = "default" if self.tol is None else f"{self.tol:.3g}"
        return f"{self.case!r} FMI {self.version} {self.interface} tol {tol}: {what}"


def bound_of(tol, phases=1.0):
    return (DEFAULT_BOUND if tol is None else K_BOUND * tol) * phases


def run_case(loaded, case, interface, tol, steps=1, intervals=500):
    """Run case on loaded (CS at tol, None: the default; or ME at rtol tol) and compare."""
    t0 = time.perf_counter()
    try:
        if interface == "CS":
            out = loaded.cs(case.start, case.t_end, case.quantities, tolerance=tol, steps=steps)
        else:
            out = loaded.me(case.start, case.t_end, case.quantities, rtol=tol, intervals=intervals)
    except Exception as e:      # an error status (fmpy's FMICallException) or a failed CVode run
        return Outcome(case, loaded.version, interface, tol, bound_of(tol, case.phases),
                       error=f"{type(e).__name__}: {e}", seconds=time.perf_counter() - t0)
    if hasattr(case, "to_scaled"):
        out = case.to_scaled(out)
    ref, scales = case.reference()
    diff = scaled_difference(out, ref, scales)
    return Outcome(case, loaded.version, interface, tol, bound_of(tol, case.phases), diff=diff,
                   seconds=time.perf_counter() - t0, values=out)


def tolerances(case, rng):
    """The case's tolerances: CS loose in 1e-7.5..1e-5, CS tight 30 to 1000 times tighter (>= 1e-10),
    ME in 1e-9..1e-4."""
    loose = _log_uniform(rng, 10 ** -7.5, 1e-5)
    tight = max(loose / _log_uniform(rng, 30, 1000), 1e-10)
    return loose, tight, _log_uniform(rng, 1e-9, 1e-4)


def plan(model, n, seed):
    """[(case, [(interface, tol, steps)])] for n cases of model: CS at the default tolerance, CS at a
    loose and a tight tolerance, ME at a random one (the same for both FMI versions)."""
    rng = np.random.default_rng([seed, MODELS.index(model), 1])
    out = []
    for case in cases(model, n, seed):
        loose, tight, me = tolerances(case, rng)
        steps = int(rng.choice([1, 3, 10, 60]))
        out.append((case, [("CS", None, steps), ("CS", loose, steps), ("CS", tight, steps), ("ME", me, 1)]))
    return out
