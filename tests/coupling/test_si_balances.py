# SPDX-License-Identifier: BSD-2-Clause
"""The SI rod against the laws of mechanics, with its inputs (docs/si_model.md §8-10), none
of which uses the model's equations: Galilean invariance (a floor at constant velocity gives
the motion relative to it that a fixed floor gives), the centre of mass's momentum and the
rod's angular momentum (free flight in closed form; the contact's impulses), and the energy
balance with the inputs' work (exact for c = mu = 0, dissipative otherwise)."""
import math

import numpy as np
import pytest

from painleve.coupling import si
from painleve.coupling.si_experiment import SIExperiment
from helpers.si_fmu import contact_impulses, energy, input_work, on_grid

RTOL = 1e-10
FMI_TYPES = ["ModelExchange", "CoSimulation"]
OUTPUTS = ["x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy", "x_cm", "y_cm", "vx_cm", "vy_cm", "gap",
           "slip", "mode", "contact"]

# A rod on a softer floor (eps = 0.0099, delta = 0.1, mu below the Painleve wedge's mu_P = 4/3)
# dropped slipping and spinning: it bounces, slips both ways and sticks, over 0.4 s.
BOUNCING = (si.SIRod(k=2e5, c=45.0, mu=0.6), si.SIState(x=0.1, v=1.0, y=0.03, w=-0.5, theta=0.8, phi=-3.0), 0.4)
# The FMU's defaults: an IWC (compression, stick, lift-off) in 0.5 ms, then flight.
IWC = (si.SIRod(), si.SIState(), 0.004)
LOADS = si.Loads(F_x=2.0, F_y=-3.0, tau=0.4)


def run(path, fmi_type, rod, state, stop, *, floor=si.Floor(), loads=si.Loads(), points=2000, output=OUTPUTS,
        rtol=RTOL):
    interval = stop / points
    with SIExperiment(path, fmi_type=fmi_type) as ex:
        r = ex.simulate(rod, state, floor=floor, loads=loads, stop_time=stop, output_interval=interval,
                        relative_tolerance=rtol, output=output)
    return r, interval


def moved(state, floor):
    """The start on the moving floor that corresponds to `state` on the fixed one (§8)."""
    return si.SIState(x=state.x, v=state.v + floor.v, y=state.y + floor.y0, w=state.w + floor.w, theta=state.theta,
                      phi=state.phi)


def relative_motion_error(path, fmi_type, rod, state, stop, floor, loads, rtol):
    """max |moving - fixed| / range of each relative variable, run at relative tolerance rtol,
    and the two runs' grid rows (same times, on the grid)."""
    fixed, interval = run(path, fmi_type, rod, state, stop, loads=loads, rtol=rtol)
    moving, _ = run(path, fmi_type, rod, moved(state, floor), stop, floor=floor, loads=loads, rtol=rtol)
    a, b = on_grid(fixed, interval), on_grid(moving, interval)
    assert len(a) == len(b) and np.array_equal(a["time"], b["time"])
    t = a["time"]
    relative = dict(x=b["x"] - floor.v * t, v=b["v"] - floor.v, y=b["y"] - floor.y0 - floor.w * t,
                    w=b["w"] - floor.w, theta=b["theta"], phi=b["phi"], gap=b["gap"], slip=b["slip"],
                    F_N=b["F_N"], F_T=b["F_T"], x_cm=b["x_cm"] - floor.v * t, vx_cm=b["vx_cm"] - floor.v,
                    y_cm=b["y_cm"] - floor.y0 - floor.w * t, vy_cm=b["vy_cm"] - floor.w)
    return {n: float(np.max(np.abs(got - a[n])) / np.max(np.abs(a[n]))) for n, got in relative.items()}, a, b


@pytest.mark.parametrize("fmi_type", FMI_TYPES)
@pytest.mark.parametrize("loads", [si.Loads(), LOADS])
@pytest.mark.parametrize("rod, state, stop", [BOUNCING, IWC])
def test_a_floor_at_constant_velocity_gives_the_fixed_floors_relative_motion(si_fmu_path, fmi_type, rod, state,
                                                                             stop, loads):
    # Model Exchange: the loop gives CVode the inputs at each right-hand side's time. Co-Simulation:
    # the master sets y_floor = y0 + W t_k at each communication point and the FMU moves the floor
    # on at w_floor = W between them (a held floor would be a staircase, and the runs would differ
    # by O(W h), not by the solver's error).
    floor = si.Floor(y0=0.02, w=0.3, v=1.2)
    coarse, _, _ = relative_motion_error(si_fmu_path, fmi_type, rod, state, stop, floor, loads, 1e-8)
    fine, a, b = relative_motion_error(si_fmu_path, fmi_type, rod, state, stop, floor, loads, 1e-10)
    # the slip's mode in contact (in flight no friction acts: its label follows v only at events)
    contact = a["contact"].astype(bool)
    assert np.any(contact) and np.array_equal(a["contact"], b["contact"])
    assert np.array_equal(a["mode"][contact], b["mode"][contact])
    # The runs differ by CVode's errors only (the moving floor's states are larger, y by y0 + W t and
    # v by U, and so are the errors their relative tolerance allows): the difference is small and
    # falls with the tolerance (measured: up to 2e-6 of a variable's range at rtol 1e-10 in Model
    # Exchange, 1.1e-5 in Co-Simulation, whose CVODE restarts at every communication point of the
    # moving floor; 10 to 100 times more at 1e-8), down to rounding. A physical difference would not fall.
    limit = 1e-5 if fmi_type == "ModelExchange" else 4e-5
    for name in fine:
        assert fine[name] <= limit, (name, fine[name])
        assert fine[name] <= coarse[name] / 5 or fine[name] <= 1e-8, (name, coarse[name], fine[name])


def balance(rod, r, floor, loads):
    """E(t) - E(0) - the inputs' work from 0 to t."""
    E = energy(rod, r)
    return E - E[0] - input_work(rod, r, floor, loads)


@pytest.mark.parametrize("fmi_type", FMI_TYPES)
def test_the_energy_output_is_the_mechanical_energy_plus_the_springs(si_fmu_path, fmi_type):
    rod, state, stop = BOUNCING
    r, _ = run(si_fmu_path, fmi_type, rod, state, stop, floor=si.Floor(v=1.0), loads=LOADS)
    assert np.any(r["F_N"] > 0)
    assert np.allclose(r["energy"], energy(rod, r), rtol=1e-12, atol=1e-12 * rod.energy_scale)


@pytest.mark.parametrize("fmi_type", FMI_TYPES)
def test_without_damping_and_friction_the_energy_changes_by_the_inputs_work(si_fmu_path, fmi_type):
    rod, state, stop = BOUNCING
    rod = si.SIRod(k=rod.k, c=0.0, mu=0.0)
    floor = si.Floor(y0=0.01, w=-0.2 if fmi_type == "ModelExchange" else 0.0, v=0.8)
    r, _ = run(si_fmu_path, fmi_type, rod, moved(state, floor), stop, floor=floor, loads=LOADS)
    D = balance(rod, r, floor, LOADS)
    work = input_work(rod, r, floor, LOADS)
    assert np.sum(np.diff(r["contact"].astype(int)) == 1) >= 2          # several bounces
    assert np.max(np.abs(work)) > 0.1 * rod.energy_scale                # the inputs do work
    assert np.max(np.abs(D)) <= 1e-6 * (rod.energy_scale + np.max(np.abs(work)))


@pytest.mark.parametrize("fmi_type", FMI_TYPES)
@pytest.mark.parametrize("rod, state, stop", [BOUNCING, IWC])
def test_with_damping_and_friction_the_energy_beyond_the_inputs_work_never_increases(si_fmu_path, fmi_type, rod,
                                                                                     state, stop):
    floor = si.Floor(y0=0.01, w=0.15 if fmi_type == "ModelExchange" else 0.0, v=-0.5)
    r, _ = run(si_fmu_path, fmi_type, rod, moved(state, floor), stop, floor=floor, loads=LOADS)
    D = balance(rod, r, floor, LOADS)
    noise = 1e-7 * (rod.energy_scale + np.max(np.abs(input_work(rod, r, floor, LOADS))))
    assert np.all(np.diff(D) <= noise)
    assert D[-1] < -0.01 * rod.energy_scale               # and the contact did dissipate


@pytest.mark.parametrize("fmi_type", FMI_TYPES)
def test_in_flight_the_centre_of_mass_and_the_angle_follow_the_loads(si_fmu_path, fmi_type):
    rod, loads, stop = si.SIRod(), LOADS, 0.3
    state = si.SIState(x=0.2, v=-1.0, y=2.0, w=1.5, theta=0.7, phi=4.0)
    r, _ = run(si_fmu_path, fmi_type, rod, state, stop, loads=loads, points=300,
               output=OUTPUTS + ["der(v)", "der(w)", "der(phi)"])
    assert not np.any(r["contact"]) and np.all(r["F_N"] == 0) and np.all(r["F_T"] == 0)
    t, m, l, J, g = r["time"], rod.m, rod.l, rod.J, rod.g
    s0, c0 = math.sin(state.theta), math.cos(state.theta)
    X0, Y0 = state.x - l * c0, state.y + l * s0                              # the centre of mass (§1)
    U0, V0 = state.v + l * s0 * state.phi, state.w + l * c0 * state.phi
    ax, ay, eps_ = loads.F_x / m, loads.F_y / m - g, loads.tau / J            # §9: constant accelerations
    theta, phi = state.theta + state.phi * t + eps_ * t ** 2 / 2, state.phi + eps_ * t
    X, Y, U, V = X0 + U0 * t + ax * t ** 2 / 2, Y0 + V0 * t + ay * t ** 2 / 2, U0 + ax * t, V0 + ay * t
    s, c = np.sin(theta), np.cos(theta)
    exact = {"x_cm": X, "y_cm": Y, "vx_cm": U, "vy_cm": V, "theta": theta, "phi": phi,
             "x": X + l * c, "y": Y - l * s, "v": U - l * s * phi, "w": V - l * c * phi,
             "der(v)": ax - l * s * eps_ - l * c * phi ** 2, "der(w)": ay - l * c * eps_ + l * s * phi ** 2,
             "der(phi)": np.full_like(t, eps_)}
    for name, value in exact.items():
        assert np.allclose(r[name], value, rtol=1e-7, atol=1e-7 * np.max(np.abs(value))), name


def trapezoid(t, f):
    return np.concatenate(([0.0], np.cumsum(np.diff(t) * (f[1:] + f[:-1]) / 2)))


def test_the_contact_forces_impulses_are_the_momentum_the_rod_receives(si_fmu_path):
    # Model Exchange records each event (the forces' kinks), so the trapezoidal rule on a grid of
    # 1/100 of a contact's duration (~5 ms here) is accurate to ~1e-4 of the impulse.
    rod, state, stop = BOUNCING
    floor = si.Floor(y0=0.01, w=0.1, v=0.4)
    r, _ = run(si_fmu_path, "ModelExchange", rod, moved(state, floor), stop, floor=floor, loads=LOADS, points=8000)
    I_N, I_T = contact_impulses(rod, r, LOADS)
    t = r["time"]
    assert np.max(I_N) > 0.1 * rod.m * math.sqrt(rod.g * rod.l)     # the contact matters
    assert np.allclose(trapezoid(t, r["F_N"]), I_N, rtol=0, atol=1e-3 * np.max(np.abs(I_N)))
    assert np.allclose(trapezoid(t, r["F_T"]), I_T, rtol=0, atol=1e-3 * np.max(np.abs(I_N)))
    # the angular momentum about the centre of mass: J (phi - phi0) = tau t - l int (cos F_N - sin F_T)
    moment = rod.l * (np.cos(r["theta"]) * r["F_N"] - np.sin(r["theta"]) * r["F_T"])
    turned = rod.J * (r["phi"] - r["phi"][0]) - LOADS.tau * t
    assert np.allclose(-trapezoid(t, moment), turned, rtol=0, atol=1e-3 * np.max(np.abs(turned)))
