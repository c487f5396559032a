"""ShakerTable.fmu (fmu_src/models/ShakerTable, issue #15's second FMU): a table top of mass M on a
spring K and a damper C, driven by F0 sin(2 pi f t) and loaded by the input F_N,

    M z'' + C z' + K z = F0 sin(W t) - F_N,   W = 2 pi f,

checked against the physics, not against its own output: the closed-form solution of the
forced damped oscillator (transient and steady state, piecewise in a load that jumps), the
equilibrium shift -F_N/K, the resonance amplitude F0/(C W_n), the energy balance with the work
of the drive, of the input and of the damper; and the FMI side: fmpy's validation, the
variable list of config.h against the model description, analytic directional derivatives
against central differences with exactly the dependencies the ModelStructure declares, NaN
and infinite inputs refused naming the input, the FMU state (inputs included) restored and
serialized."""
import re
import zipfile
from ctypes import POINTER, c_double

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu
from scipy.integrate import simpson

from conftest import ROOT

# The defaults of the spec (fmu_src/models/ShakerTable/modelDescription.xml start values).
DEFAULTS = dict(M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, belt_speed=0.0)
INTERFACES = ["ModelExchange", "CoSimulation"]
_P = POINTER(c_double)


@pytest.fixture(scope="module")
def table(table_path):
    """The FMU extracted once by the harness; raw fmpy instances from .instantiate."""
    from painleve.fmu.experiment import Experiment
    with Experiment(table_path) as experiment:
        yield experiment


# ------------------------------------------------------------------ the closed form
def closed_form(t, t0=0.0, z0=0.0, v0=0.0, F_N=0.0, M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, **_):
    """z(t), z'(t) of M z'' + C z' + K z = F0 sin(W t) - F_N from z(t0) = z0, z'(t0) = v0
    (underdamped: C^2 < 4 K M): the particular solution A sin Wt + B cos Wt - F_N/K plus the
    damped free oscillation e^(-s tau) (c1 cos wd tau + c2 sin wd tau), tau = t - t0."""
    t = np.asarray(t, dtype=float)
    W = 2 * np.pi * frequency
    k, c = K - M * W**2, C * W
    A, B = F0 * k / (k * k + c * c), -F0 * c / (k * k + c * c)

    def particular(s):
        return A * np.sin(W * s) + B * np.cos(W * s) - F_N / K, W * (A * np.cos(W * s) - B * np.sin(W * s))
    s, wd = C / (2 * M), np.sqrt(K / M - (C / (2 * M))**2)
    zp0, vp0 = particular(t0)
    c1 = z0 - zp0
    c2 = (v0 - vp0 + s * c1) / wd
    tau = t - t0
    decay = np.exp(-s * tau)
    zp, vp = particular(t)
    z = zp + decay * (c1 * np.cos(wd * tau) + c2 * np.sin(wd * tau))
    v = vp + decay * ((wd * c2 - s * c1) * np.cos(wd * tau) - (s * c2 + wd * c1) * np.sin(wd * tau))
    return z, v


def piecewise_closed_form(t, jumps, z0=0.0, v0=0.0, **params):
    """The closed form under a load F_N that is jumps[i][1] from jumps[i][0] on (jumps[0][0] the
    start): each piece starts from where the last one ended."""
    t = np.asarray(t, dtype=float)
    z, v = np.empty_like(t), np.empty_like(t)
    ends = [tj for tj, _ in jumps[1:]] + [np.inf]
    for (t0, F_N), t1 in zip(jumps, ends):
        inside = (t >= t0) & (t < t1) if np.isfinite(t1) else t >= t0
        z[inside], v[inside] = closed_form(t[inside], t0, z0, v0, F_N, **params)
        if np.isfinite(t1):
            (z0,), (v0,) = closed_form([t1], t0, z0, v0, F_N, **params)
    return z, v


def test_the_closed_form_solves_the_equation():
    # The reference itself, by its residual (central differences) and its initial values.
    params = dict(DEFAULTS, F_N=70.0)
    t = np.linspace(0.3, 1.7, 20001)
    z, v = closed_form(t, t0=0.3, z0=2e-3, v0=-0.03, **params)
    assert (z[0], v[0]) == pytest.approx((2e-3, -0.03), rel=1e-12)
    h = t[1] - t[0]
    acceleration = np.gradient(v, h)[1:-1]
    assert np.abs(np.gradient(z, h) - v)[1:-1].max() < 1e-4 * np.abs(v).max()
    forcing = params["F0"] * np.sin(2 * np.pi * params["frequency"] * t[1:-1]) - params["F_N"]
    residual = params["M"] * acceleration + params["C"] * v[1:-1] + params["K"] * z[1:-1] - forcing
    assert np.abs(residual).max() < 1e-4 * np.abs(forcing).max()


# ------------------------------------------------------------------ the FMU as a file
def test_fmpy_validation_finds_no_problem(table_path):
    assert validate_fmu(table_path) == []


def test_config_h_lists_the_variables_of_the_model_description(table_path):
    """Value references, names, causalities and ranges: config.h's list is the model
    description's, in its order (the C side's value references are the list's indices)."""
    text = (ROOT / "fmu_src" / "models" / "ShakerTable" / "config.h").read_text()
    bounds = dict(FORCE_BOUND=1e9, STATE_BOUND=1e6)

    def number(s):
        s = s.strip()
        return -bounds[s[1:]] if s.startswith("-") and s[1:] in bounds else bounds.get(s, None) or float(s)
    rows = re.findall(r'VARIABLE\((\w+), "([^"]+)", REAL, (\w+), [^,]+, ([^,]+), ([^)]+)\)', text)
    md = read_model_description(table_path)
    assert [name for _, name, *_ in rows] == [v.name for v in md.modelVariables]
    causality = dict(PARAMETER="parameter", INPUT="input", STATE="output")
    for vr, ((_, name, kind, lo, hi), v) in enumerate(zip(rows, md.modelVariables)):
        assert v.valueReference == vr, name
        assert v.type == "Real" and v.description, name
        if kind in causality:
            assert v.causality == causality[kind], name
            assert (float(v.min), float(v.max)) == (number(lo), number(hi)), name
        else:
            assert v.causality in ("output", "local") and v.initial == "calculated", name
    units = {v.name: v.unit for v in md.modelVariables}
    assert units == dict(M="kg", K="N/m", C="N.s/m", F0="N", frequency="Hz", belt_speed="m/s", F_N="N",
                              F_T="N", position="m", velocity="m/s", **{"der(position)": "m/s"},
                              **{"der(velocity)": "m/s2"}, belt_velocity="m/s", drive_force="N", energy="J",
                              belt_power="W", mount_force="N", mount_force_mean="N", drive_force_mean="N")
    assert md.numberOfEventIndicators == 0 and len(md.derivatives) == 2


def test_the_documentation_lists_every_variable_with_its_unit_in_si(table_path):
    md = read_model_description(table_path)
    with zipfile.ZipFile(table_path) as z:
        page = z.read("documentation/index.html").decode()
    for v in md.modelVariables:
        assert f"<td>{v.name}</td>" in page and f"<td>{v.unit}</td>" in page, v.name
    assert "SI units" in page and "Dimensionless" not in page and "Hogan" not in page


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_a_tool_builds_the_source_fmu_from_its_source_files(table_path, tmp_path, fmi_type):
    """<SourceFiles> and sources/ are complete: fmpy compiles them (with the README's CVODE
    options) into a binary that simulates like the CMake build."""
    from helpers.source_build import source_build, with_cvode
    unzipped = source_build(table_path, tmp_path, with_cvode())
    a, b = (simulate_fmu(f, fmi_type=fmi_type, start_values=dict(F_N=30.0), output=["position", "velocity"])
            for f in (table_path, unzipped))
    for name in ("position", "velocity"):
        np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-12 * np.abs(a[name]).max(), err_msg=name)
    z, _ = closed_form(b["time"], F_N=30.0, **DEFAULTS)
    assert np.abs(b["position"] - z).max() < 1e-4 * np.abs(z).max()


# ------------------------------------------------------------------ physics under fmpy's masters
START = dict(position=1e-3, velocity=-0.02)   # a transient on top of the forced motion


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_forced_damped_oscillator_follows_the_closed_form_and_converges_with_the_tolerance(table_path, fmi_type):
    errors = []
    for tolerance in (1e-6, 1e-8):
        r = simulate_fmu(table_path, fmi_type=fmi_type, start_values=START, output=["position", "velocity"],
                         output_interval=1e-3, relative_tolerance=tolerance)
        assert r["time"][-1] == pytest.approx(2.5)     # the DefaultExperiment: 5 time constants 2 M / C
        z, v = closed_form(r["time"], z0=START["position"], v0=START["velocity"], **DEFAULTS)
        # The transient is still visible at the start (amplitude 1.5x the steady one) and gone at the end.
        errors.append(max(np.abs(r["position"] - z).max() / np.abs(z).max(),
                          np.abs(r["velocity"] - v).max() / np.abs(v).max()))
    assert errors[1] < 100 * 1e-8, errors
    assert errors[1] < errors[0] / 10, errors


def sinusoid_fit(t, z, W):
    """(a, b, c) of the least-squares fit a sin Wt + b cos Wt + c."""
    basis = np.column_stack([np.sin(W * t), np.cos(W * t), np.ones_like(t)])
    return np.linalg.lstsq(basis, z, rcond=None)[0]


W_N = np.sqrt(DEFAULTS["K"] / DEFAULTS["M"])    # the natural angular frequency


@pytest.mark.parametrize("fmi_type", INTERFACES)
@pytest.mark.parametrize("frequency, F_N", [(5.0, 0.0), (W_N / (2 * np.pi), 0.0), (5.0, 150.0), (13.0, -60.0)])
def test_steady_state_amplitude_phase_and_equilibrium_shift(table_path, fmi_type, frequency, F_N):
    """After 30 time constants: z = X sin(W t - phase) - F_N/K with X = F0 / sqrt((K - M W^2)^2 + (C W)^2),
    tan(phase) = C W / (K - M W^2); at resonance X = F0 / (C W_n), phase = pi/2."""
    M, K, C, F0 = (DEFAULTS[k] for k in ("M", "K", "C", "F0"))
    W = 2 * np.pi * frequency
    r = simulate_fmu(table_path, fmi_type=fmi_type, start_time=0.0, stop_time=15.0, output_interval=1e-3,
                     relative_tolerance=1e-8, start_values=dict(frequency=frequency, F_N=F_N),
                     output=["position"])
    last = r["time"] >= 14.0
    a, b, c = sinusoid_fit(r["time"][last], r["position"][last], W)
    X, phase = np.hypot(a, b), np.arctan2(-b, a)
    assert X == pytest.approx(F0 / np.hypot(K - M * W**2, C * W), rel=1e-5)
    assert phase == pytest.approx(np.arctan2(C * W, K - M * W**2), abs=1e-5)
    if frequency == W_N / (2 * np.pi):
        assert X == pytest.approx(F0 / (C * W_N), rel=1e-5) and phase == pytest.approx(np.pi / 2, abs=1e-5)
    assert c == pytest.approx(-F_N / K, abs=1e-6 * X)


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_a_constant_load_alone_settles_at_minus_F_N_over_K(table_path, fmi_type):
    F_N = 250.0
    r = simulate_fmu(table_path, fmi_type=fmi_type, stop_time=15.0, output_interval=1e-3, relative_tolerance=1e-8,
                     start_values=dict(F0=0.0, F_N=F_N), output=["position", "velocity", "der(velocity)"])
    assert r["position"][-1] == pytest.approx(-F_N / DEFAULTS["K"], rel=1e-7)
    assert abs(r["velocity"][-1]) < 1e-8 and abs(r["der(velocity)"][-1]) < 1e-7 * F_N / DEFAULTS["M"]
    # On the way there, the step response of the closed form, its first overshoot the textbook's
    # exp(-pi zeta / sqrt(1 - zeta^2)) (90 % for zeta = C / (2 sqrt(K M)) = 0.032).
    z, _ = closed_form(r["time"], F_N=F_N, **dict(DEFAULTS, F0=0.0))
    assert np.abs(r["position"] - z).max() < 1e-5 * F_N / DEFAULTS["K"]
    zeta = DEFAULTS["C"] / (2 * np.sqrt(DEFAULTS["K"] * DEFAULTS["M"]))
    overshoot = np.exp(-np.pi * zeta / np.sqrt(1 - zeta**2))
    assert r["position"].min() == pytest.approx(-(1 + overshoot) * F_N / DEFAULTS["K"], rel=1e-3)


def energy_terms(r, params, F_N):
    """E(t) - E(0) and the work the drive and the load did minus what the damper took, by
    Simpson's rule on the outputs (F_N: the load at each output time, held over the interval
    after it where given as an array)."""
    M, K, C = params["M"], params["K"], params["C"]
    t, z, v = r["time"], r["position"], r["velocity"]
    E = 0.5 * M * v**2 + 0.5 * K * z**2
    drive = params["F0"] * np.sin(2 * np.pi * params["frequency"] * t)
    work = simpson(drive * v, x=t) - simpson(C * v**2, x=t)
    if np.ndim(F_N) == 0:
        work -= F_N * (z[-1] - z[0])
    else:   # a load held over each interval does -F_N,k (z_k+1 - z_k) there, exactly
        work -= np.sum(F_N[:-1] * np.diff(z))
    return E, work


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_energy_balance_with_the_drive_the_load_and_the_damper(table_path, fmi_type):
    params = dict(DEFAULTS, C=120.0)
    F_N = 180.0
    r = simulate_fmu(table_path, fmi_type=fmi_type, stop_time=1.0, output_interval=1e-4, relative_tolerance=1e-9,
                     start_values=dict(START, C=params["C"], F_N=F_N),
                     output=["position", "velocity", "energy", "drive_force"])
    E, work = energy_terms(r, params, F_N)
    assert r["energy"] == pytest.approx(E, rel=1e-12, abs=1e-15)
    assert r["drive_force"] == pytest.approx(params["F0"] * np.sin(2 * np.pi * params["frequency"] * r["time"]),
                                             rel=1e-12, abs=1e-12)
    damped = simpson(params["C"] * r["velocity"]**2, x=r["time"])
    assert damped > 0.1 * np.abs(E - E[0]).max()        # every term counts
    assert E[-1] - E[0] == pytest.approx(work, abs=1e-6 * damped)


def test_energy_balance_with_a_load_held_between_communication_points(table_path):
    """Co-Simulation holds an input over each step (canInterpolateInputs is false): a varying
    load does exactly -F_N(t_k) (z_k+1 - z_k) over the step from t_k."""
    params = dict(DEFAULTS)
    t = np.arange(0.0, 1.0 + 5e-5, 1e-4)
    load = 120.0 + 80.0 * np.sin(2 * np.pi * 3.0 * t)
    signal = np.array([(tk, fk, 0.0) for tk, fk in zip(t, load)], dtype=[("time", float), ("F_N", float), ("F_T", float)])
    r = simulate_fmu(table_path, fmi_type="CoSimulation", stop_time=1.0, output_interval=1e-4,
                     relative_tolerance=1e-9, input=signal, start_values=START, output=["position", "velocity"])
    assert np.array_equal(r["time"], t)
    E, work = energy_terms(r, params, load)
    damped = simpson(params["C"] * r["velocity"]**2, x=r["time"])
    assert E[-1] - E[0] == pytest.approx(work, abs=1e-5 * damped)
    # Against the closed form with the held load, step by step.
    z, v = piecewise_closed_form(t, list(zip(t[:-1], load[:-1])), z0=START["position"], v0=START["velocity"],
                                 **params)
    assert np.abs(r["position"] - z).max() < 1e-6 * np.abs(z).max()


JUMPS = [(0.0, 0.0), (0.4, 200.0), (1.1, -50.0), (1.53, 120.0)]    # (from time, F_N)


def jump_signal():
    rows = [(0.0, JUMPS[0][1], 0.0)]
    for (_, before), (t, after) in zip(JUMPS, JUMPS[1:]):
        rows += [(t, before, 0.0), (t, after, 0.0)]
    rows.append((2.0, JUMPS[-1][1], 0.0))
    return np.array(rows, dtype=[("time", float), ("F_N", float), ("F_T", float)])


@pytest.mark.parametrize("fmi_type", INTERFACES)
@pytest.mark.parametrize("output_interval", [1e-3, 0.07])
def test_a_load_that_jumps_mid_run_gives_the_piecewise_closed_form(table_path, fmi_type, output_interval):
    """fmpy's masters hand the jump over at its time (an input event); Co-Simulation's CVODE
    restarts there (the next step starts with an event update and a fresh integrator), so the
    load's jump is no error source even with long steps (0.07 s: a third of the drive's period)."""
    r = simulate_fmu(table_path, fmi_type=fmi_type, stop_time=2.0, output_interval=output_interval,
                     relative_tolerance=1e-8, input=jump_signal(), start_values=START,
                     output=["position", "velocity", "F_N"])
    for t_jump, _ in JUMPS[1:]:
        assert np.any(np.isclose(r["time"], t_jump, rtol=0, atol=1e-12)), f"no point at the jump {t_jump}"
    z, v = piecewise_closed_form(r["time"], JUMPS, z0=START["position"], v0=START["velocity"], **DEFAULTS)
    # At a jump's time fmpy records the value before (or both): compare away from them.
    away = np.all([np.abs(r["time"] - tj) > 1e-9 for tj, _ in JUMPS[1:]], axis=0)
    scale = np.abs(z).max()
    assert np.abs(r["position"] - z)[away].max() < 2e-6 * scale
    assert np.abs(r["velocity"] - v)[away].max() < 2e-6 * np.abs(v).max()
    # The loads matter: without them the table would be far from there.
    unloaded, _ = closed_form(r["time"], z0=START["position"], v0=START["velocity"], **DEFAULTS)
    assert np.abs(r["position"] - unloaded).max() > 0.3 * scale


def test_cs_input_set_mid_step_sequence_restarts_from_the_current_state(table):
    """A master that sets F_N between its own steps of 0.1 s (no input event of fmpy's)."""
    slave = table.instantiate(fmi_type="CoSimulation", instance_name="table")
    vr = table.vr
    slave.setupExperiment(tolerance=1e-8, startTime=0.0)
    slave.enterInitializationMode()
    slave.setReal([vr["position"], vr["velocity"]], [START["position"], START["velocity"]])
    slave.exitInitializationMode()
    loads = {0.0: 0.0, 0.3: 300.0, 0.6: 0.0, 1.2: -100.0}
    t, rows = 0.0, []
    for k in range(20):
        t = round(0.1 * k, 10)
        if t in loads:
            slave.setReal([vr["F_N"]], [loads[t]])
        slave.doStep(t, 0.1)
        rows.append((round(t + 0.1, 10), *slave.getReal([vr["position"], vr["velocity"]])))
    slave.terminate()
    slave.freeInstance()
    times, zs, vs = np.array(rows).T
    z, v = piecewise_closed_form(times, sorted(loads.items()), z0=START["position"], v0=START["velocity"], **DEFAULTS)
    assert np.abs(zs - z).max() < 2e-6 * np.abs(z).max()
    assert np.abs(vs - v).max() < 2e-6 * np.abs(v).max()


# ------------------------------------------------------------------ FMI: inputs, derivatives, state
@pytest.mark.parametrize("fmi_type", INTERFACES)
@pytest.mark.parametrize("name, value, when", [("F_N", float("nan"), "initialization"), ("F_T", float("inf"), "step"),
                                               ("F_N", float("-inf"), "step"), ("F_T", float("nan"), "step")])
def test_a_bad_input_is_an_error_naming_it(table, fmi_type, name, value, when):
    messages = []
    fmu = table.instantiate(fmi_type=fmi_type, instance_name="table", on_message=lambda *m: messages.append(m))
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    if when == "step":
        fmu.setReal([table.vr[name]], [12.5])    # a good value is taken, in every mode the standard allows
        fmu.exitInitializationMode()
        if fmi_type == "ModelExchange":
            fmu.newDiscreteStates()
            fmu.enterContinuousTimeMode()
        else:
            fmu.doStep(0.0, 0.01)
        fmu.setReal([table.vr[name]], [-3.0])
    with pytest.raises(FMICallException):
        fmu.setReal([table.vr[name]], [value])
    assert messages[-1][0] == 3 and f"{name} = {value:g} must be finite" in messages[-1][2], messages[-1]
    fmu.freeInstance()


def test_no_event_indicators_is_an_empty_array_and_any_other_size_is_an_error(table):
    messages = []
    fmu = table.instantiate(instance_name="table", on_message=lambda *m: messages.append(m))
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.newDiscreteStates()
    fmu.enterContinuousTimeMode()
    fmu.getEventIndicators(None, 0)              # an importer's empty array may be NULL
    z = np.zeros(1)
    with pytest.raises(FMICallException):
        fmu.getEventIndicators(z.ctypes.data_as(_P), 1)
    assert "size 1 given, ShakerTable has 0" in messages[-1][2]
    fmu.freeInstance()


def test_parameters_out_of_range_are_errors_naming_them(table):
    for name, value in [("M", 0.0), ("K", -1.0), ("C", -0.5), ("frequency", -2.0)]:
        messages = []
        fmu = table.instantiate(instance_name="table", on_message=lambda *m: messages.append(m))
        with pytest.raises(FMICallException):
            fmu.setReal([table.vr[name]], [value])
        assert messages[-1][2].startswith(f"fmi2SetReal: {name} = {value:g} is out of range"), messages[-1]
        fmu.freeInstance()


KNOWN_SCALES = dict(M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, belt_speed=1.0, F_N=100.0, F_T=100.0,
                    position=1e-3, velocity=0.05)
# A generic point: every partial that is not identically 0 is not 0 here (t0: sin, cos of W t0 not 0).
POINT = dict(M=7.0, K=3e4, C=55.0, F0=42.0, frequency=4.3, belt_speed=0.8, F_N=35.0, F_T=-12.0,
             position=1.3e-3, velocity=-0.031)
T0 = 0.37


def structure_of(md):
    return {name: {u.variable.name: {v.name for v in u.dependencies} for u in unknowns}
            for name, unknowns in dict(Outputs=md.outputs, Derivatives=md.derivatives,
                                       InitialUnknowns=md.initialUnknowns).items()}


def jacobian_check(fmu, vr, unknowns, knowns, set_known):
    """(directional derivatives, central differences), columns scaled by the knowns' scales."""
    def values():
        return np.array(fmu.getReal([vr[u] for u in unknowns]))
    D = np.column_stack([fmu.getDirectionalDerivative([vr[u] for u in unknowns], [vr[k]], [1.0]) for k in knowns])
    FD = np.zeros_like(D)
    for j, k in enumerate(knowns):
        h = 1e-6 * KNOWN_SCALES[k]
        set_known(k, POINT[k] + h)
        up = values()
        set_known(k, POINT[k] - h)
        down = values()
        set_known(k, POINT[k])
        FD[:, j] = (up - down) / (2 * h)
    return D, FD


def assert_exact(D, FD, unknowns, knowns, declared, where):
    scale = np.array([KNOWN_SCALES[k] for k in knowns])
    Ds, FDs = D * scale, FD * scale
    row = np.maximum(np.abs(FDs).max(axis=1, keepdims=True), 1e-300)
    wrong = [f"d {unknowns[i]}/d {knowns[j]}: {D[i, j]:.10g} vs {FD[i, j]:.10g}"
             for i, j in zip(*np.nonzero(np.abs(Ds - FDs) > 1e-6 * row))]
    assert not wrong, f"{where}: " + "; ".join(wrong)
    # Exactly the declared dependencies change the unknown (at a generic point).
    changes = np.abs(FDs) > 1e-9 * row
    wrong = [f"{u} on {k}: declared {k in declared.get(u, set())}, changes {changes[i, j]}"
             for i, u in enumerate(unknowns) for j, k in enumerate(knowns)
             if (k in declared.get(u, set())) != changes[i, j]]
    assert not wrong, f"{where}: " + "; ".join(wrong)


def test_directional_derivatives_in_continuous_time_mode_are_the_declared_dependencies(table):
    md = table.model_description
    structure = structure_of(md)
    vr = table.vr
    fmu = table.instantiate(instance_name="table")
    fmu.setupExperiment(startTime=T0)
    fmu.enterInitializationMode()
    fmu.setReal([vr[k] for k in POINT], list(POINT.values()))
    fmu.exitInitializationMode()
    fmu.newDiscreteStates()
    fmu.enterContinuousTimeMode()
    fmu.setTime(T0 + 0.21)     # time moves the drive, and nothing the knowns see
    unknowns = list(dict.fromkeys([*structure["Outputs"], *structure["Derivatives"]]))
    knowns = ["F_N", "F_T", "position", "velocity"]
    declared = {u: structure["Outputs"].get(u, set()) | structure["Derivatives"].get(u, set()) for u in unknowns}

    def set_known(k, value):
        if k in ("position", "velocity"):
            x = np.array(fmu.getReal([vr["position"], vr["velocity"]]))
            x[["position", "velocity"].index(k)] = value
            fmu.setContinuousStates(x.ctypes.data_as(_P), 2)
        else:
            fmu.setReal([vr[k]], [value])
    D, FD = jacobian_check(fmu, vr, unknowns, knowns, set_known)
    assert_exact(D, FD, unknowns, knowns, declared, "Continuous-Time Mode")
    # The acceleration's row by hand: -K/M, -C/M for the states, -1/M for the load, 0 for F_T.
    row = D[unknowns.index("der(velocity)")]
    assert row == pytest.approx([-1 / POINT["M"], 0, -POINT["K"] / POINT["M"], -POINT["C"] / POINT["M"]], rel=1e-14)
    fmu.freeInstance()


def test_directional_derivatives_in_initialization_mode_are_the_declared_initial_dependencies(table):
    md = table.model_description
    structure = structure_of(md)["InitialUnknowns"]
    vr = table.vr
    fmu = table.instantiate(instance_name="table")
    fmu.setupExperiment(startTime=T0)
    fmu.enterInitializationMode()
    fmu.setReal([vr[k] for k in POINT], list(POINT.values()))
    unknowns = list(structure)
    knowns = list(POINT)
    D, FD = jacobian_check(fmu, vr, unknowns, knowns, lambda k, value: fmu.setReal([vr[k]], [value]))
    assert_exact(D, FD, unknowns, knowns, structure, "Initialization Mode")
    fmu.freeInstance()


def test_fmu_state_with_its_inputs_is_restored_and_serialized(table):
    vr = table.vr
    out = [vr["position"], vr["velocity"], vr["energy"]]

    def slave():
        s = table.instantiate(fmi_type="CoSimulation", instance_name="table")
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.setReal([vr["F_N"], vr["C"]], [50.0, 70.0])
        s.exitInitializationMode()
        return s

    def run(s, t, until):
        while t < until - 1e-12:
            s.doStep(t, 0.05)
            t = round(t + 0.05, 10)
        return s.getReal(out)
    s = slave()
    run(s, 0.0, 0.3)
    state = s.getFMUstate()
    data = s.serializeFMUstate(state)
    first = run(s, 0.3, 0.6)
    s.setReal([vr["F_N"]], [900.0])        # an input changed after the state was taken ...
    s.setFMUstate(state)                   # ... is restored with it
    assert s.getReal([vr["F_N"]]) == [50.0]
    assert run(s, 0.3, 0.6) == first
    other = slave()
    restored = other.deSerializeFMUstate(data)
    other.setFMUstate(restored)
    assert other.getReal([vr["F_N"], vr["C"]]) == [50.0, 70.0]
    assert run(other, 0.3, 0.6) == first
    # And the restored run is the physics, not a copy of a wrong one.
    z, v = closed_form([0.6], F_N=50.0, **dict(DEFAULTS, C=70.0))
    assert first[:2] == pytest.approx([z[0], v[0]], rel=1e-4)
    for fmu, st in ((s, state), (other, restored)):
        fmu.freeFMUstate(st)
        fmu.freeInstance()
