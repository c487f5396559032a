# SPDX-License-Identifier: BSD-2-Clause
"""The coupling that conserves momentum: PainleveRodSI's step-averaged contact forces
F_N_mean, F_T_mean and ShakerTable's mount_force_mean, drive_force_mean, and the SSP system built on
them (painleve.coupling.coupled, coupling="mean"). What the physics fixes, asserted here:

- a step mean is the force's time average over the step: the rod's against a trapezoid sum of its
  instantaneous force sampled 200 times a step, the table's mount against -K int z - C dz from its
  sampled position, its drive against F0 (cos w t0 - cos w t1)/(w h), to the solver's tolerance;
- in Model Exchange, where there is no step, a step mean is the force itself;
- the FMU state carries the means;
- Newton's third law through the master: the table holds in step k exactly the rod's mean over
  step k - 1, so the system's vertical momentum (rod + table) changes by the external impulses
  (gravity, the table's mount and drive) plus the impulse still in flight, to rounding, at any
  step and with every master; the instantaneous coupling misses what falls between the samples;
- energy: elastic, frictionless contact on an undamped, undriven table conserves the system's
  energy; the coupled run's error shrinks with the step (the master's hold adds energy, the
  mean coupling's one-step delay twice the instantaneous one's half step).
The stiff default case runs the whole default run, 0.45 s (painleve couple's).
"""
import math

import fmpy
import numpy as np
import pytest

from painleve.coupling import masters
from painleve.coupling.coupled import (COUPLINGS, Setup, impulse_on_rod, initial_energy, momentum_balance, run_coupled,
                                       total_energy)

STIFF_STOP = 0.45
SOFT = Setup(rod=dict(k=2e5, c=450.0, mu=0.3, v=1.5, phi=0.0, theta=1.0), table=dict(belt_speed=0.5))
# elastic, frictionless contact on an undamped, undriven table: nothing dissipates, nothing drives
CONSERVATIVE = Setup(rod=dict(k=2e5, c=0.0, mu=0.0), table=dict(C=0.0, F0=0.0))


def cs_run(fmu, step, stop, output, start_values=None):
    return fmpy.simulate_fmu(fmu, fmi_type="CoSimulation", stop_time=stop, output_interval=step, output=output,
                             start_values=start_values or {})


def step_averages(fine, name, per_step):
    """Trapezoid means of a sampled quantity over each coarse step (per_step fine samples a step)."""
    t, q = fine["time"], fine[name]
    n = (len(t) - 1) // per_step
    return np.array([np.trapezoid(q[k * per_step:(k + 1) * per_step + 1], t[k * per_step:(k + 1) * per_step + 1])
                     for k in range(n)]) / (t[per_step] - t[0])


# ------------------------------------------------------------------ the FMUs' step means
@pytest.mark.parametrize("which", ["si_fmu_path", "si_fmu3_path"])        # FMI 2.0 and 3.0
def test_the_rods_step_means_are_its_contact_forces_averaged_over_each_step(which, request):
    """The default IWC on a fixed floor: the contact lasts about 0.5 ms, inside the first step of
    1 ms, and the rod is in flight in the second. Each step's mean times h equals the trapezoid
    integral of F_N, F_T sampled every 1e-7 s (the same trajectory: the inputs never change, so
    CVODE runs on through the communication points). F_N is continuous: the two agree to the
    solver's error (1e-6 of the impulse). F_T jumps where a stick begins and ends (mu F_N to the
    sticking force), where a trapezoid errs by up to dt/2 times the jump: dt max|F_T| bounds it."""
    si_fmu_path = request.getfixturevalue(which)
    H, dt = 1e-3, 1e-7
    coarse = cs_run(si_fmu_path, H, 2 * H, ["F_N_mean", "F_T_mean", "F_N"])
    fine = cs_run(si_fmu_path, dt, 2 * H, ["F_N", "F_T"])
    n = round(H / dt)
    for name, bound in (("F_N", None), ("F_T", dt * np.max(np.abs(fine["F_T"])))):
        first = np.trapezoid(fine[name][:n + 1], fine["time"][:n + 1])
        second = np.trapezoid(fine[name][n:], fine["time"][n:])
        assert abs(first) > 0.5                       # the IWC's impulse, in the first step
        assert second == 0                            # in flight the whole second step
        tolerance = 1e-6 * abs(first) if bound is None else bound
        assert abs(coarse[f"{name}_mean"][1] * H - first) <= tolerance, (name, coarse[f"{name}_mean"][1] * H, first)
        # in flight the mean is the solver's error in the rod's momentum over the step
        assert abs(coarse[f"{name}_mean"][2] * H) <= 1e-9 * abs(first)
    # the contact was over before the first communication point: the samples of F_N miss it all
    assert coarse["F_N"][1] == 0 and coarse["F_N_mean"][1] > 500
    assert coarse["F_N_mean"][0] == 0         # before the first step: nothing delivered


@pytest.mark.parametrize("which", ["table_path", "table3_path"])
def test_the_tables_step_means_are_its_mount_and_drive_impulses_over_each_step(which, request):
    """The table shaken at 5 Hz: mount_force_mean h = -K int z - C (z(t1) - z(t0)) (trapezoid on 100
    samples a step), drive_force_mean h = F0 (cos w t0 - cos w t1)/w exactly."""
    table_path = request.getfixturevalue(which)
    H, per_step, stop = 1e-3, 100, 0.2
    K, C, F0, f = 4e4, 40.0, 50.0, 5.0
    coarse = cs_run(table_path, H, stop, ["mount_force_mean", "drive_force_mean"])
    fine = cs_run(table_path, H / per_step, stop, ["position", "velocity"])
    z = fine["position"]
    n = (len(z) - 1) // per_step
    spring = step_averages(fine, "position", per_step)
    damper = (z[per_step::per_step][:n] - z[:-1:per_step][:n]) / H
    expected = -K * spring - C * damper
    got = coarse["mount_force_mean"][1:n + 1]
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-4 * np.max(np.abs(expected)))
    t0 = coarse["time"][:-1]
    omega = 2 * math.pi * f
    drive = F0 * (np.cos(omega * t0) - np.cos(omega * (t0 + H))) / (omega * H)
    np.testing.assert_allclose(coarse["drive_force_mean"][1:], drive, rtol=0, atol=1e-9 * F0)


@pytest.mark.parametrize("rod, table", [("si_fmu_path", "table_path"), ("si_fmu3_path", "table3_path")])
def test_in_model_exchange_a_step_mean_is_the_force_itself(rod, table, request):
    si_fmu_path, table_path = request.getfixturevalue(rod), request.getfixturevalue(table)
    rod = fmpy.simulate_fmu(si_fmu_path, fmi_type="ModelExchange", stop_time=0.002, output_interval=1e-5,
                            output=["F_N", "F_T", "F_N_mean", "F_T_mean"])
    assert np.max(rod["F_N"]) > 100
    np.testing.assert_array_equal(rod["F_N_mean"], rod["F_N"])
    np.testing.assert_array_equal(rod["F_T_mean"], rod["F_T"])
    table = fmpy.simulate_fmu(table_path, fmi_type="ModelExchange", stop_time=0.05, output_interval=1e-3,
                              output=["position", "velocity", "mount_force_mean", "drive_force", "drive_force_mean"])
    np.testing.assert_allclose(table["mount_force_mean"], -4e4 * table["position"] - 40.0 * table["velocity"],
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(table["drive_force_mean"], table["drive_force"])


def test_the_fmu_state_carries_the_step_means(si_fmu_path):
    """Take the state after the IWC's step, step on, restore: the mean is the IWC step's again, and
    the next step gives the same mean as the first time (serialized and back, too)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(si_fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    rod = FMU2Slave(guid=md.guid, unzipDirectory=extract(si_fmu_path), modelIdentifier="PainleveRodSI",
                    instanceName="rod")
    rod.instantiate()
    rod.setupExperiment(startTime=0)
    rod.enterInitializationMode()
    rod.exitInitializationMode()
    rod.doStep(0, 1e-3)
    mean = rod.getReal([vr["F_N_mean"], vr["F_T_mean"]])
    assert mean[0] > 100
    state = rod.serializeFMUstate(rod.getFMUstate())
    rod.doStep(1e-3, 1e-3)
    after = rod.getReal([vr["F_N_mean"], vr["F_T_mean"]])
    assert after != mean
    rod.setFMUstate(rod.deSerializeFMUstate(state))
    assert rod.getReal([vr["F_N_mean"], vr["F_T_mean"]]) == mean
    rod.doStep(1e-3, 1e-3)
    assert rod.getReal([vr["F_N_mean"], vr["F_T_mean"]]) == after
    rod.terminate()
    rod.freeInstance()


# ------------------------------------------------------------------ the coupled system
@pytest.mark.parametrize("h", [1e-3, 1e-4])
@pytest.mark.parametrize("master", masters.MASTERS)
def test_the_mean_coupling_conserves_momentum_at_any_step_with_every_master(master, h, si_fmu_path, table_path):
    """The models' defaults (the IWC, flights, landings on the shaking table): the table holds in
    step k the rod's mean over step k - 1 (0 in the first), so the vertical momentum of rod and
    table changes by the external impulses plus the one in flight, to rounding."""
    s = Setup()
    r = run_coupled(si_fmu_path, table_path, s, stop_time=STIFF_STOP, step=h, master=master)
    np.testing.assert_allclose(r["table.F_N"][1:], r["rod.F_N_mean"][:-1], rtol=1e-15, atol=0)
    assert r["table.F_N"][0] == 0
    b = momentum_balance(r, s, h)
    assert b.contact == pytest.approx(impulse_on_rod(r, s), rel=1e-12)   # the rod's means are its momentum's
    assert b.contact > 0.5                      # the IWC's impulse alone is 0.85 N s
    assert abs(b.residual) <= 1e-9 * b.contact, b


@pytest.mark.parametrize("coupling", list(COUPLINGS))
def test_on_a_soft_contact_only_the_instantaneous_couplings_momentum_error_is_first_order(coupling, si_fmu_path,
                                                                                        table_path):
    """k = 2e5 N/m in persistent slipping contact: the samples of F_N are a left Riemann sum, whose
    error halves with h; the means hand over every impulse at every h."""
    residuals = []
    for h in (4e-4, 2e-4, 1e-4):
        r = run_coupled(si_fmu_path, table_path, SOFT, stop_time=0.1, step=h, coupling=coupling)
        b = momentum_balance(r, SOFT, h, coupling)
        residuals.append(b.residual / b.contact)
    if coupling == "mean":
        assert max(abs(x) for x in residuals) <= 1e-12, residuals
    else:
        for coarse, fine in zip(residuals, residuals[1:]):
            assert 1.6 <= coarse / fine <= 2.6, residuals


@pytest.mark.parametrize("coupling", list(COUPLINGS))
def test_a_conservative_system_loses_its_energy_error_as_the_step_shrinks(coupling, si_fmu_path, table_path):
    """Nothing dissipates and nothing drives: the energy of rod plus table is constant in the
    continuous system. The coupled run's error at t = 0.3 s (some 40 bounces) falls by more than
    5 for each tenfold smaller step; at the coarser step the master adds energy (the hold's delay:
    an elastic contact whose force lags the motion does work on it)."""
    errors = []
    for h in (1e-3, 1e-4):
        r = run_coupled(si_fmu_path, table_path, CONSERVATIVE, stop_time=0.3, step=h, coupling=coupling)
        errors.append(total_energy(r)[-1] - initial_energy(CONSERVATIVE))
    E0 = initial_energy(CONSERVATIVE)
    assert errors[0] > 0 and abs(errors[0]) < 1e-2 * E0, errors
    assert abs(errors[1]) < abs(errors[0]) / 5, errors
