# SPDX-License-Identifier: BSD-2-Clause
"""Co-Simulation in the same FMU: the embedded CVODE integrates the same model
and events as Model Exchange, for any master and any communication step."""
import pathlib
import re
import subprocess

import fmpy
import fmpy.util
import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from painleve.theory import analytic as an
from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from painleve.experiments.studies import convergence
from conftest import ROOT
from helpers.raw_instances import Rod, Slave

def test_both_interfaces_declared_and_valid(fmu_path):
    md = read_model_description(fmu_path)
    assert md.modelExchange is not None and md.coSimulation is not None
    assert validate_fmu(fmu_path) == []


def test_binary_needs_only_libc_and_libm(loaded):
    so = next((pathlib.Path(loaded.unzipdir) / "binaries" / "linux64").glob("*.so"))
    needed = re.findall(r"\(NEEDED\).*\[(.*)\]", subprocess.run(["readelf", "-d", so], capture_output=True,
                                                                 text=True, check=True).stdout)
    assert set(needed) <= {"libc.so.6", "libm.so.6"}, needed
    symbols = subprocess.run(["nm", "-D", "--defined-only", so], capture_output=True, text=True, check=True).stdout
    assert all(line.split()[-1].startswith("fmi2") for line in symbols.splitlines()), "only fmi2* may be exported"


# The IWC amplifies solver errors (it follows an unstable manifold), so "the same
# to solver tolerance" is checked as: differences below 1000 x the tolerance, at
# two tolerances 100 apart (they shrink with it).
@pytest.mark.parametrize("tolerance", [1e-8, 1e-10])
def test_default_experiment_through_cosimulation_is_the_same_iwc(fmu_path, tolerance):
    out = ["y", "w", "v", "phi", "mode", "contact"]
    me = fmpy.simulate_fmu(fmu_path, fmi_type="ModelExchange", output=out, relative_tolerance=tolerance)
    cs = fmpy.simulate_fmu(fmu_path, fmi_type="CoSimulation", output=out, relative_tolerance=tolerance)
    assert not cs["contact"][-1] and cs["y"][-1] > 0
    for name in ("y", "w", "v", "phi"):
        assert abs(cs[name][-1] - me[name][-1]) < 1000 * tolerance, name


@pytest.mark.parametrize("tolerance", [1e-8, 1e-10])
def test_one_step_per_millisecond_equals_a_single_step(loaded, tolerance):
    fine, coarse = Slave(loaded, tolerance, epsilon=1e-3), Slave(loaded, tolerance, epsilon=1e-3)
    for _ in range(100):
        fine.step(1e-3)
    coarse.step(0.1)
    assert np.max(np.abs(fine.states() - coarse.states())) < 1000 * tolerance
    assert fine.fmu.getRealStatus(2) == pytest.approx(0.1)        # fmi2LastSuccessfulTime
    assert not fine.fmu.getBooleanStatus(3)                        # fmi2Terminated


def test_events_inside_a_step_are_handled_unseen(loaded):
    # A single step over the whole IWC leaves the rod in flight, modes switched inside the step.
    rod = Slave(loaded, epsilon=1e-4)
    rod.step(2e-3)
    assert rod.fmu.getBoolean([rod.vr["contact"]]) == [False]
    assert rod.fmu.getReal([rod.vr["w"]])[0] == pytest.approx(an.e(1.0, 1.0), rel=0.01)


def test_wrong_communication_point_is_an_error(loaded):
    rod = Slave(loaded)
    with pytest.raises(FMICallException):
        rod.fmu.doStep(0.5, 1e-3)
    assert "is not the instance's time" in rod.messages[-1][2]


def test_a_fast_rod_is_not_taken_for_a_zeno_run(loaded):
    # A rod spinning at phi = 3e4 with eps = 0.1 dips its end below the floor about every 2e-4
    # time units (several events each): thousands of events, each at its own time. The guard
    # counts events at one instant only, so the run goes on; friction takes energy, nothing adds it.
    # (Steps of 0.25: a longer one spends the solver-step budget of one call; see the next test.)
    rod = Slave(loaded, theta=0.3, phi=3e4, y=0.5, epsilon=0.1, delta=0.0, mu=1.0)
    energy = [rod.fmu.getReal([rod.vr["energy"]])[0]]
    for _ in range(8):
        rod.step(0.25)
        energy.append(rod.fmu.getReal([rod.vr["energy"]])[0])
    switches, = rod.fmu.getInteger([rod.vr["switches"]])
    assert switches > 1000 and rod.fmu.getReal([rod.vr["t_switch"]])[0] > 1.9
    assert np.all(np.diff(energy) <= 1e-6 * energy[0]) and energy[-1] < energy[0]


def test_a_step_beyond_the_call_budget_is_discarded_where_it_stopped_and_the_run_goes_on(loaded):
    # The same spinning rod (a contact every 2e-4: 1e4 events and, under CVODE, 4e5 solver steps
    # per time unit) asked for one step of 2: the call stops when a budget is spent (the 200,000
    # solver steps under CVODE; the 20,000 events first under the explicit pair, whose steps
    # through each contact are fewer), answers fmi2Discard with one log line naming the budget,
    # and reports how far it got; the master goes on from there.
    rod = Slave(loaded, theta=0.3, phi=3e4, y=0.5, epsilon=0.1, delta=0.0, mu=1.0)
    energy0 = rod.fmu.getReal([rod.vr["energy"]])[0]
    with pytest.raises(FMICallException) as refused:
        rod.step(2.0)
    assert refused.value.status == fmpy.fmi2.fmi2Discard
    reached = rod.fmu.getRealStatus(fmpy.fmi2.fmi2LastSuccessfulTime)
    assert 0 < reached < 2.0
    budget_lines = [m for m in rod.messages
                    if "budget of 200000 solver steps per call" in m[2] or "budget of 20000 events per call" in m[2]]
    assert len(budget_lines) == 1 and f"{reached:.17g}" in budget_lines[0][2]
    energy = [rod.fmu.getReal([rod.vr["energy"]])[0]]
    assert energy[0] <= energy0 * (1 + 1e-6)
    rod.t = reached
    for _ in range(3):
        rod.step(0.1)
        energy.append(rod.fmu.getReal([rod.vr["energy"]])[0])
    assert np.all(np.diff(energy) <= 1e-6 * energy0)


@pytest.mark.parametrize("start_time", [0.0, 1e6])
def test_events_at_one_instant_end_as_a_zeno_run_and_the_instance_survives(loaded, start_time):
    # An importer that keeps entering event mode without advancing time: the guard ends it, at
    # t = 1e6 too, where the time still resolves the rod's contact (eps = 1e-3 >> 256 ulps of t).
    rod = Rod(loaded)
    rod.initialize(start_time)
    with pytest.raises(FMICallException):
        for _ in range(100):
            rod.fmu.enterEventMode()
            rod.fmu.newDiscreteStates()
            rod.fmu.enterContinuousTimeMode()
    assert "without progress in time (a Zeno run" in rod.messages[-1][2]
    rod.fmu.reset()
    rod.initialize()
    rod.euler_step(1e-5)
    assert rod.get("w")[0] < 0          # the default IWC starts: the end is pushed into the floor


@pytest.mark.parametrize("params", [dict(mu=3.0, theta0=1.0, delta=1.0), dict(mu=3.0, theta0=0.8, delta=0.0),
                                    dict(alpha=2.0, mu=3.0, theta0=1.1, delta=2.0)])
def test_theorem1_through_cosimulation_converges_like_model_exchange(fmu_path, params):
    epsilons = [e for e in (1e-3, 1e-4, 1e-5, 1e-6) if e * (1 + params["delta"]) ** 3 <= 2e-2]
    with Experiment(fmu_path, fmi_type="CoSimulation") as cs, Experiment(fmu_path) as me:
        by_cs, by_me = (convergence(x, Case(**params), epsilons) for x in (cs, me))
    for a, b in zip(by_cs.outcomes, by_me.outcomes):
        assert a.iwc and b.iwc
        # both solvers run at rtol = eps/100 or tighter: they agree far below the eps error
        assert abs(a.w - b.w) < 0.1 * abs(b.w_error) + 1e-9
        assert abs(a.phi - b.phi) < 0.1 * abs(b.phi_error) + 1e-9
    for name in ("w", "phi", "v"):
        assert by_cs.rate(name) > 0.6, by_cs.table()


@pytest.mark.parametrize("factor, iwc", [(1.2, True), (0.8, False)])
def test_theorem2_through_cosimulation_same_outcome(fmu_path, factor, iwc):
    video = dict(theta0=0.9463, phi0=1.6654, v0=1.0, delta=1.0, epsilon=1e-4)
    w10 = factor * an.predict(Case(**video)).w1_star
    with Experiment(fmu_path, fmi_type="CoSimulation") as cs, Experiment(fmu_path) as me:
        a, b = cs.run(Case(w10=w10, **video)), me.run(Case(w10=w10, **video))
    assert a.iwc == b.iwc == iwc
    assert a.w == pytest.approx(b.w, rel=1e-3)


def test_without_sundials_the_fmu_is_model_exchange_only(tmp_path):
    build = tmp_path / "build"
    configure = subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DPAINLEVE_COSIMULATION=OFF",
                                f"-DPython3_EXECUTABLE={__import__('sys').executable}"],
                               capture_output=True, text=True, check=True)
    assert "Co-Simulation left out" in configure.stderr
    subprocess.run(["cmake", "--build", build], capture_output=True, check=True)
    fmu = build / "PainleveRod.fmu"
    md = read_model_description(fmu)
    assert md.coSimulation is None and md.modelExchange is not None
    assert validate_fmu(fmu) == []


def test_without_a_tolerance_cosimulation_uses_the_default_experiments(loaded):
    # One source of truth: the DefaultExperiment's tolerance is what a master passes and what the
    # FMU uses when none is passed. A different tolerance gives a (slightly) different run.
    default = float(loaded.model_description.defaultExperiment.tolerance)
    runs = {}
    for tolerance in (None, default, default / 100):
        rod = Slave(loaded, tolerance=tolerance)
        for _ in range(10):
            rod.step(0.01)
        runs[tolerance] = rod.states()
    assert np.array_equal(runs[None], runs[default])
    assert not np.array_equal(runs[default], runs[default / 100])
    np.testing.assert_allclose(runs[default / 100], runs[default], rtol=1e-4)


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
def test_a_flat_fast_spin_runs_to_the_end_at_the_default_tolerance(fmu_path, fmi_type):
    # Launched flat (theta = 0, w = 0) spinning at phi = 3e3: v changes sign every half turn. In flight
    # no friction acts, so those sign changes switch nothing and are no events (ten of them in 0.01
    # would be; an old guard of 100 events within eps^2 stopped Model Exchange on them). The spin's
    # energy, 6e6, is kept to the solver's error (BDF's phase error over five fast turns).
    r = fmpy.simulate_fmu(fmu_path, fmi_type=fmi_type, start_values=dict(theta=0.0, phi=3e3, y=0.0, w=0.0, v=0.0),
                          stop_time=0.01, output=["switches", "energy"],
                          output_interval=fmpy.util.auto_interval(0.01))
    # (output_interval: fmpy's automatic grid, 1e-5, its default before the DefaultExperiment had a
    # stepSize; with 1e-4 as the communication step this Co-Simulation run ends as a Zeno run near
    # t = 2e-12, see the README)
    assert r["time"][-1] == pytest.approx(0.01) and r["switches"][-1] < 10
    assert r["energy"][-1] <= r["energy"][0] * (1 + 1e-5)


def test_a_faster_flat_spin_on_the_contact_boundary_runs_on_and_only_the_solver_moves_its_energy(fmu_path):
    # At phi = 1e4 the end rests on y = 0 with b < 0 for t < 1/phi^3 = 1e-12 while F_N = 0: contact and
    # flight both push the state onto h = 0, which event-driven modes used to chatter across until the
    # Zeno guard ended the run. The grazing decisions (docs/bounded_calls.md) now move the state off the
    # boundary past the solver's error, so the run goes on to the end. Nothing does work on the rod
    # (friction and the damper take energy), so the energy may move only by the solver's error, which
    # falls with the tolerance; where the flights are in closed form (no solver error) and the contacts
    # only take energy, only by rounding at either tolerance (a few ulps of it).
    rises = []
    for tolerance in (1e-8, 1e-10):
        r = fmpy.simulate_fmu(fmu_path, fmi_type="CoSimulation", relative_tolerance=tolerance, output_interval=1e-5,
                              start_values=dict(theta=0.0, phi=1e4, y=0.0, w=0.0, v=0.0), stop_time=0.01,
                              output=["energy"])
        assert r["time"][-1] == pytest.approx(0.01)
        rises.append(np.max(np.diff(r["energy"])) / r["energy"][0])
    assert rises[1] < 1e-8 and (rises[1] < rises[0] / 5 or max(rises) < 64 * np.finfo(float).eps), rises


def test_a_stiffly_damped_soft_contact_runs_to_the_end_alike_in_both_interfaces(fmu_path):
    # delta = 1000, eps = 0.3 (far outside the asymptotics, where stick and slip were seen to
    # ping-pong at a fold): compression, stick, slip, flight, the same in both interfaces.
    runs = [fmpy.simulate_fmu(fmu_path, fmi_type=t, start_values=dict(delta=1000.0, epsilon=0.3), stop_time=2.0,
                              relative_tolerance=1e-8, output=["switches", "energy"])
            for t in ("ModelExchange", "CoSimulation")]
    assert runs[0]["switches"][-1] == runs[1]["switches"][-1] >= 3
    for r in runs:
        assert np.max(np.diff(r["energy"])) <= 1e-8 * r["energy"][0] and r["time"][-1] == pytest.approx(2.0)
