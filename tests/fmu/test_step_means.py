# SPDX-License-Identifier: BSD-2-Clause
"""PainleveRod's step means F_N_mean, F_T_mean (PainleveRodSI's are in
tests/coupling/test_momentum_coupling.py): in Co-Simulation the contact forces averaged over the
last communication step, in Model Exchange the forces themselves. The reference is the forces'
own integral, a trapezoid sum of F_N, F_T sampled every 1e-5 time units on the same trajectory
(the FMU has no inputs: CVODE runs on through the communication points)."""
import fmpy
import numpy as np
import pytest


@pytest.mark.parametrize("which", ["fmu_path", "fmu3_path"])
def test_a_step_mean_is_the_impulse_of_the_step_over_the_step(which, request):
    """The default IWC (eps = 1e-3: a contact of some 0.01 time units) inside the first step of
    0.05; flight in the second. F_N is continuous: the mean equals the trapezoid integral to the
    solver's error; F_T jumps where a stick begins and ends, where a trapezoid errs by up to
    dt/2 times the jump: dt max|F_T| bounds it."""
    fmu = request.getfixturevalue(which)
    H, dt = 0.05, 1e-5
    coarse = fmpy.simulate_fmu(fmu, fmi_type="CoSimulation", stop_time=2 * H, output_interval=H,
                               output=["F_N_mean", "F_T_mean", "F_N"])
    fine = fmpy.simulate_fmu(fmu, fmi_type="CoSimulation", stop_time=2 * H, output_interval=dt, output=["F_N", "F_T"])
    n = round(H / dt)
    for name, bound in (("F_N", None), ("F_T", dt * np.max(np.abs(fine["F_T"])))):
        first = np.trapezoid(fine[name][:n + 1], fine["time"][:n + 1])
        assert abs(first) > 0.1 and np.trapezoid(fine[name][n:], fine["time"][n:]) == 0
        tolerance = 3e-5 * abs(first) if bound is None else bound   # measured 4.4e-6
        assert abs(coarse[f"{name}_mean"][1] * H - first) <= tolerance, (name, coarse[f"{name}_mean"][1] * H, first)
    assert coarse["F_N_mean"][0] == 0 and coarse["F_N"][1] == 0


def test_in_model_exchange_a_step_mean_is_the_force_itself(fmu_path):
    r = fmpy.simulate_fmu(fmu_path, fmi_type="ModelExchange", stop_time=0.05, output_interval=1e-4,
                          output=["F_N", "F_T", "F_N_mean", "F_T_mean"])
    assert np.max(r["F_N"]) > 1
    np.testing.assert_array_equal(r["F_N_mean"], r["F_N"])
    np.testing.assert_array_equal(r["F_T_mean"], r["F_T"])
