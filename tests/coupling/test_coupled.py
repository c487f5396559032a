# SPDX-License-Identifier: BSD-2-Clause
"""PainleveRodSI on a ShakerTable, coupled through an SSP archive (painleve.coupling.coupled) and run by
fmpy's SSP master and by libcosim and ecos (painleve.coupling.masters). Every assertion is a number the
physics or the master's scheme fixes, not one of the code's own outputs:

- the scheme: all three masters are Jacobi with a zero-order hold (their sources; docs/coupling.md),
  so the table holds in step k the value its source had at t_(k-1), which two tables connected
  through their drive force show exactly (F0 sin(2 pi f t_(k-1)));
- Newton's third law across the coupling: the impulse of F_N on the rod (its momentum balance,
  m (vy_cm(T) - vy_cm(0)) + m g T) equals the impulse the table holds (sum of h F_N) to O(h):
  a left Riemann sum of the rod's force, whose error is bounded by h times its total variation;
  and the table's momentum balance shows it received exactly that impulse;
- convergence: a zero-order-hold Jacobi scheme is first order in the communication step h,
  measured here on a soft contact (k = 2e5 N/m) in persistent slipping contact (smooth);
- a very heavy table (M = 1e6 kg, F0 = 0) is a fixed floor: the rod's IWC lifts off with
  w = e(delta, theta0) v0 (analytic.e, Theorem 1; the SI model's alpha, delta, theta0 and v0 in
  units of sqrt(g l)) within Theorem 1's O(eps ln 1/eps), as the rod alone on a fixed floor;
- the archive is valid (painleve.coupling.ssp_check), and the other masters give fmpy's results to
  within the communication step's own error.
"""
import math

import fmpy
import numpy as np
import pytest

from painleve.theory import analytic as an
from painleve.coupling import masters
from painleve.coupling.coupled import (RECORD, Setup, impulse_on_rod, impulse_on_table, run_coupled,
                              table_momentum_impulse, write_coupled_ssp)
from painleve.coupling.ssp import Component, Connection, write_ssp
from painleve.coupling.ssp_check import check_ssp

STATES = ("rod.x", "rod.v", "rod.y", "rod.w", "rod.theta", "rod.phi", "table.position", "table.velocity")

# A soft contact (eps ~ 1e-2) in persistent slipping contact: mu = 0.3 is below the Painleve
# threshold mu_P(3) = 4/3, the slip v - v_floor = 1 m/s stays positive over 0.1 s (friction
# takes at most mu g T = 0.3 m/s), and the table's acceleration (< 2 m/s^2) never exceeds g.
SOFT = Setup(rod=dict(k=2e5, c=450.0, mu=0.3, v=1.5, phi=0.0, theta=1.0), table=dict(belt_speed=0.5))
SOFT_STOP = 0.1
STEPS = (4e-4, 2e-4, 1e-4, 5e-5)

# The models' default IWC (theta0 = 1, v = 2 m/s, phi = 2 rad/s: Theorem 1, b < 0) on a table a
# million times the rod's mass, not driven.
HEAVY = Setup(table=dict(M=1e6, F0=0.0))


@pytest.fixture(scope="module")
def soft_runs(si_fmu_path, table_path):
    """fmpy's runs of the soft case at each communication step, the table loaded by the rod's forces
    at the communication points (the instantaneous coupling: test_momentum_coupling.py has the means)."""
    return {h: run_coupled(si_fmu_path, table_path, SOFT, stop_time=SOFT_STOP, step=h, coupling="instantaneous")
            for h in STEPS}


def on_grid(r, step):
    """The rows of a run at the communication points of the grid with this step."""
    stride = round(step / (r["time"][1] - r["time"][0]))
    return r[stride - 1::stride]


def gap(a, b, names=STATES):
    """The largest difference over the trajectory (a's grid, the coarser) of each variable."""
    step = a["time"][1] - a["time"][0]
    b = on_grid(b, step)
    np.testing.assert_allclose(a["time"], b["time"], rtol=0, atol=1e-12)
    return {n: float(np.max(np.abs(a[n] - b[n]))) for n in names}


# ------------------------------------------------------------------ the archive
@pytest.mark.parametrize("coupling, forces", [("mean", ("F_N_mean", "F_T_mean")), ("instantaneous", ("F_N", "F_T"))])
def test_the_coupled_archive_is_valid(coupling, forces, si_fmu_path, table_path, tmp_path):
    ssp = write_coupled_ssp(tmp_path / "coupled.ssp", si_fmu_path, table_path, SOFT, stop_time=SOFT_STOP,
                            coupling=coupling)
    assert check_ssp(ssp) == []
    # the five connections of the coupled study (docs/coupling.md), each from an output to an input;
    # the table's loads from the rod's step means or its forces at the communication points
    from fmpy.ssp.ssd import read_ssd
    assert {(c.startElement, c.startConnector, c.endElement, c.endConnector) for c in read_ssd(str(ssp)).system.connections} == {
        ("table", "position", "rod", "y_floor"), ("table", "velocity", "rod", "w_floor"),
        ("table", "belt_velocity", "rod", "v_floor"), ("rod", forces[0], "table", "F_N"),
        ("rod", forces[1], "table", "F_T")}


def test_the_bound_defaults_are_the_models_own_start_values(si_fmu_path, table_path):
    """The archive binds every default explicitly: they must be the model descriptions' starts."""
    from painleve.coupling.coupled import ROD_DEFAULTS, TABLE_DEFAULTS
    for fmu, defaults in ((si_fmu_path, ROD_DEFAULTS), (table_path, TABLE_DEFAULTS)):
        start = {v.name: v.start for v in fmpy.read_model_description(fmu).modelVariables}
        for name, value in defaults.items():
            assert float(start[name]) == pytest.approx(value, rel=1e-14), (fmu, name)


# ------------------------------------------------------------------ the masters' scheme
@pytest.mark.parametrize("master", masters.MASTERS)
def test_each_master_holds_the_value_its_source_had_at_the_start_of_the_step(master, table_path, tmp_path):
    """Two undriven-by-the-rod tables, each loaded by the other's drive force F0 sin(2 pi f t): a
    zero-order hold in a Jacobi scheme hands table B in step k exactly F0 sin(2 pi f t_(k-1))."""
    F0, f = 50.0, 5.0
    a = Component("A", table_path, {"F0": F0, "frequency": f}, inputs=("F_N",), outputs=("drive_force", "position"))
    b = Component("B", table_path, {"F0": -F0, "frequency": f}, inputs=("F_N",), outputs=("drive_force", "position"))
    ssp = write_ssp(tmp_path / "tables.ssp", "tables", [a, b],
                    [Connection(("A", "drive_force"), ("B", "F_N")), Connection(("B", "drive_force"), ("A", "F_N"))],
                    stop_time=0.2)
    assert check_ssp(ssp) == []
    h = 1e-3
    r = masters.run(master, ssp, 0.2, h, ["A.drive_force", "B.F_N", "A.F_N"])
    t_start = r["time"] - h
    np.testing.assert_allclose(r["B.F_N"], F0 * np.sin(2 * math.pi * f * t_start), rtol=0, atol=1e-9)
    np.testing.assert_allclose(r["A.F_N"], -F0 * np.sin(2 * math.pi * f * t_start), rtol=0, atol=1e-9)
    np.testing.assert_allclose(r["A.drive_force"], F0 * np.sin(2 * math.pi * f * r["time"]), rtol=0, atol=1e-9)


# ------------------------------------------------------------------ Newton's third law
def total_variation(r, name, start):
    values = np.concatenate(([start], r[name]))
    return float(np.sum(np.abs(np.diff(values))))


def test_action_equals_reaction_across_the_coupling_to_the_steps_order(soft_runs):
    """The table holds in each step the F_N the rod gave at the step's start (fmpy: 0 in the first
    step, where the rod's is 0 too). The impulse the rod received, from its momentum, and the one
    the table held then differ by a left Riemann sum's error, O(h): it halves with the step (the
    rod's force also jumps at each communication point, where the master moves its floor to the
    table's new position, so the samples' total variation does not bound it). And the table's
    momentum balance shows it took exactly the impulse it held."""
    differences = []
    for h, r in soft_runs.items():
        np.testing.assert_array_equal(r["table.F_N"][1:], r["rod.F_N"][:-1])
        assert r["table.F_N"][0] == 0 and abs(r["rod.F_N"][0]) > 0
        on_rod, on_table = impulse_on_rod(r, SOFT), impulse_on_table(r, h)
        assert on_rod > 0.5 * SOFT.rod_values()["m"] * 9.81 * SOFT_STOP      # the floor carries the rod
        assert abs(on_rod - on_table) < 2e-2 * on_table
        differences.append(on_rod - on_table)
        # the table's momentum: M dz' = int(-K z - C z' + drive) - impulse held; int K z by the
        # trapezoid rule, whose error is at most K T h^2 max|z''| / 12, and the solver's share
        # (the table's CVODE restarts at every step's new input: 1e-4 of the impulse allowed)
        received = table_momentum_impulse(r, SOFT)
        accel = np.max(np.abs(np.diff(r["table.velocity"]))) / h
        trapezoid = SOFT.table_values()["K"] * SOFT_STOP * h * h * accel / 12
        assert abs(received - on_table) <= trapezoid + 1e-4 * on_table, (h, received - on_table, trapezoid)
    # first order: each halving of h halves the difference (measured ratios 2.0 to 2.1)
    for coarse, fine in zip(differences, differences[1:]):
        assert 1.6 <= coarse / fine <= 2.6, differences


# ------------------------------------------------------------------ convergence
def test_the_coupled_run_converges_at_first_order_in_the_communication_step(soft_runs):
    """Successive differences d(h) = max |q_h - q_(h/2)| over the trajectory halve as h halves:
    the observed order log2(d(h)/d(h/2)) of a zero-order-hold Jacobi scheme is 1."""
    orders = {}
    for h, h2, h4 in zip(STEPS, STEPS[1:], STEPS[2:]):
        d1 = gap(soft_runs[h], soft_runs[h2])
        d2 = gap(soft_runs[h2], soft_runs[h4])
        for name in STATES:
            orders[(h, name)] = math.log2(d1[name] / d2[name])
    for (h, name), p in orders.items():
        assert 0.8 <= p <= 1.2, f"observed order {p:.3f} for {name} at h = {h:g} (expected 1)"
    # and the error of the finest run is small: the rod's angle to 1e-4 rad
    assert gap(soft_runs[STEPS[-2]], soft_runs[STEPS[-1]])["rod.theta"] < 1e-4


# ------------------------------------------------------------------ the heavy table is a floor
def lift_off_w(r, setup):
    """The rod's vertical velocity relative to the table at the end of contact (t_contact_end),
    carried back from the first communication point after it by the flight's acceleration
    w' = -g + l phi^2 sin(theta) (the centre of mass falls at g, phi is constant in flight)."""
    p = setup.rod_values()
    t_end = r["rod.t_contact_end"][-1]
    assert t_end > 0, "the contact never ended"
    k = np.flatnonzero(r["time"] >= t_end)[0]
    assert r["rod.F_N"][k] == 0
    relative = r["rod.w"][k] - r["table.velocity"][k]
    flight = -p["g"] + p["l"] * r["rod.phi"][k] ** 2 * math.sin(r["rod.theta"][k])
    return relative - flight * (r["time"][k] - t_end)


def paper_numbers(setup):
    """The SI rod's dimensionless numbers (docs/si_model.md's scaling, written out here): alpha = m l^2/J,
    epsilon = sqrt(m g/(k l)), delta = c/sqrt(m k), theta0, v0 = (v - belt)/sqrt(g l), phi0 = phi sqrt(l/g)."""
    p, t = setup.rod_values(), setup.table_values()
    m, l, g, k = p["m"], p["l"], p["g"], p["k"]
    return dict(alpha=m * l * l / p["J"], epsilon=math.sqrt(m * g / (k * l)), delta=p["c"] / math.sqrt(m * k),
                mu=p["mu"], theta0=p["theta"], v0=(p["v"] - t["belt_speed"]) / math.sqrt(g * l),
                phi0=p["phi"] * math.sqrt(l / g))


@pytest.mark.parametrize("master", masters.MASTERS)
def test_on_a_very_heavy_table_the_rod_lifts_off_with_w_equal_to_e_v0(master, si_fmu_path, table_path):
    d = paper_numbers(HEAVY)
    e = an.e(d["delta"], d["theta0"], alpha=d["alpha"], mu=d["mu"])
    assert -1 + d["phi0"] ** 2 * math.sin(d["theta0"]) < 0          # Theorem 1: b < 0
    r = run_coupled(si_fmu_path, table_path, HEAVY, stop_time=0.01, step=1e-4, master=master)
    p = HEAVY.rod_values()
    w = lift_off_w(r, HEAVY) / math.sqrt(p["g"] * p["l"])
    eps = d["epsilon"]
    assert abs(w / d["v0"] - e) < 3 * eps * math.log(1 / eps), (w / d["v0"], e)
    # the table took the rod's impulse (< m v = 2 N s) with M = 1e6 kg: below 2e-6 m/s
    assert np.max(np.abs(r["table.velocity"])) < 2e-6
    # the harness's scaling (painleve.coupling.si.case_of, used by painleve couple) gives the same numbers
    case = HEAVY.case()
    assert (case.alpha, case.epsilon, case.delta, case.theta0, case.v0, case.phi0) == pytest.approx(
        (d["alpha"], d["epsilon"], d["delta"], d["theta0"], d["v0"], d["phi0"]), rel=1e-12)


def test_on_a_very_heavy_table_the_rod_moves_as_on_a_fixed_floor(si_fmu_path, table_path):
    """fmpy's Co-Simulation of the rod alone (inputs 0: the floor fixed) on the same grid. The
    table takes the rod's impulse (< 1 N s) with M = 1e6 kg: it moves at < 1e-6 m/s, so the
    rod's states agree to that and the solver's tolerance."""
    h, stop = 1e-4, 0.01
    r = run_coupled(si_fmu_path, table_path, HEAVY, stop_time=stop, step=h)
    alone = fmpy.simulate_fmu(si_fmu_path, fmi_type="CoSimulation", stop_time=stop, output_interval=h,
                              output=["x", "v", "y", "w", "theta", "phi"])[1:]
    for name in ("x", "v", "y", "w", "theta", "phi"):
        scale = 1 + np.max(np.abs(alone[name]))
        assert np.max(np.abs(r[f"rod.{name}"] - alone[name])) < 1e-5 * scale, name


# ------------------------------------------------------------------ the other masters
@pytest.mark.parametrize("master", ["libcosim", "ecos"])
def test_the_other_masters_give_fmpys_results_to_the_steps_order(master, si_fmu_path, table_path, soft_runs):
    """Each state within the communication step's own error (fmpy's d(h) = |q_h - q_(h/2)|) of
    fmpy's run at the same h: the same scheme, so they agree far closer (docs/coupling.md)."""
    h = 1e-4
    theirs = run_coupled(si_fmu_path, table_path, SOFT, stop_time=SOFT_STOP, step=h, master=master,
                         coupling="instantaneous")
    ours = soft_runs[h]
    step_error = gap(soft_runs[2 * h], soft_runs[h])
    differences = gap(on_grid(theirs, 2 * h), ours)
    for name in STATES:
        assert differences[name] <= step_error[name], (name, differences[name], step_error[name])
        # closer still: the same scheme on the same FMUs; the initial outputs here are 0 (the rod
        # starts unloaded at y = 0, the table at rest), so fmpy's zero-initialized connectors are
        # the others' first exchange, and only round-off differs
        assert differences[name] <= 1e-9 * (1 + np.max(np.abs(ours[name]))), (name, differences[name])
    # what the table held and what the rod felt: Newton's third law through this master too (the
    # table's held F_N: ecos reads the rod's F_N back after the next inputs are set, see masters)
    tv = total_variation(theirs, "table.F_N", 0.0)
    assert abs(impulse_on_rod(theirs, SOFT) - impulse_on_table(theirs, h)) <= 2 * h * tv
    assert set(RECORD) <= set(theirs.dtype.names)
