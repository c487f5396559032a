# SPDX-License-Identifier: BSD-2-Clause
"""ShakerTable.fmu (fmu_src/models/ShakerTable, the coupled study's second FMU): a table top of mass M on a
spring K and a damper C, driven by F0 sin(2 pi f t) and loaded by the input F_N,

    M z'' + C z' + K z = F0 sin(W t) - F_N,   W = 2 pi f,

checked against the physics, not against its own output: the closed-form solution of the
forced damped oscillator (transient and steady state, piecewise in a load that jumps;
tests/helpers/shaker_table.py), the equilibrium shift -F_N/K, the resonance amplitude
F0/(C W_n), the energy balance with the work of the drive, of the input and of the damper.
The FMI side is in test_shaker_table_fmi.py."""
import numpy as np
import pytest
from fmpy import simulate_fmu
from scipy.integrate import simpson

from helpers.shaker_table import DEFAULTS, INTERFACES, START, closed_form, piecewise_closed_form


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


# ------------------------------------------------------------------ physics under fmpy's masters
@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_forced_damped_oscillator_follows_the_closed_form_and_converges_with_the_tolerance(table_path, fmi_type):
    errors = []
    # Co-Simulation's explicit pair at communication steps of 1e-3 takes the master's
    # step, whose error (2.6e-9) is below both tolerances: at 1e-2 its own step control decides.
    interval = 1e-2 if fmi_type == "CoSimulation" else 1e-3
    for tolerance in (1e-6, 1e-8):
        r = simulate_fmu(table_path, fmi_type=fmi_type, start_values=START, output=["position", "velocity"],
                         output_interval=interval, relative_tolerance=tolerance)
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
