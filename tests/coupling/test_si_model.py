# SPDX-License-Identifier: BSD-2-Clause
"""PainleveRodSI with the floor fixed and no loads is PainleveRod in SI units (docs/si_model.md
§7): the two FMUs' trajectories, put in the same units by the paper's scaling, agree to the
solver's tolerance through Model Exchange and Co-Simulation, and the SI model passes the
checks of Theorems 1 and 2 that PainleveRod passes (acceptance.py's rules)."""
import numpy as np
import pytest
from fmpy import simulate_fmu

from painleve.experiments import acceptance
from painleve.theory import analytic as an
from painleve.coupling import si
from painleve.experiments.case import Case, horizon
from painleve.fmu.experiment import Experiment
from painleve.coupling.si_experiment import SIExperiment
from helpers.si_fmu import on_grid

STATES = ["x", "v", "y", "w", "theta", "phi"]
COMPARED = STATES + ["F_N", "F_T", "energy", "mode", "contact"]
RTOL = 1e-10       # CVode's relative tolerance for the comparisons

# Cases that go through compression, stick, lift-off and flight (Theorem 1), a lift-off without
# sticking (Theorem 2 above w1*), and rods of other sizes, masses and gravities.
VIDEO = dict(theta0=0.9463, phi0=1.6654, v0=1.0, delta=1.0)
CASES = [(Case(epsilon=1e-3), dict(m=1.0, l=0.5, g=9.81)),
         (Case(theta0=1.2, phi0=0.3, v0=1.5, delta=0.0, epsilon=1e-4, alpha=2.0), dict(m=2.5, l=0.2, g=3.7)),
         (Case(theta0=0.8, phi0=0.9, delta=3.0, epsilon=1e-4), dict(m=0.05, l=1.5, g=9.81)),
         (Case(epsilon=1e-3, w10=0.5 * an.predict(Case(**VIDEO)).w1_star, **VIDEO), dict(m=1.0, l=0.5, g=9.81))]


def paper_units(case, body, fmi_type, *, paper_fmu, si_fmu):
    """Both FMUs' runs of `case` on one grid of the paper's time (2 eps), in the paper's units."""
    interval, stop = 2 * case.epsilon, 1.5 * horizon(case)
    rod, state = si.si_of(case, **body)
    with SIExperiment(si_fmu, fmi_type=fmi_type) as ex:
        r_si = ex.simulate(rod, state, stop_time=stop * rod.time_scale, output_interval=interval * rod.time_scale,
                           relative_tolerance=RTOL, output=COMPARED)
    paper = si.to_paper(rod, r_si)
    paper_energy = r_si["energy"] / rod.energy_scale
    with Experiment(paper_fmu, fmi_type=fmi_type) as ex:
        if fmi_type == "ModelExchange":
            r = ex.simulate_from(case.start_values(), stop_time=stop, output_interval=interval,
                                 relative_tolerance=RTOL, output=COMPARED)
        else:
            with ex.fresh_run(case) as instance:
                r = simulate_fmu(ex.unzipdir, model_description=ex.model_description, fmu_instance=instance,
                                 fmi_type=fmi_type, start_values=case.start_values(), output=COMPARED,
                                 stop_time=stop, output_interval=interval, relative_tolerance=RTOL, validate=False)
    keep = np.isclose(paper["time"], np.round(paper["time"] / interval) * interval, rtol=1e-9, atol=0)
    keep &= np.append(paper["time"][1:] != paper["time"][:-1], True)
    return on_grid(r, interval), paper[keep], paper_energy[keep]


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
@pytest.mark.parametrize("case, body", CASES)
def test_the_si_model_is_painleverod_under_the_scaling(fmu_path, si_fmu_path, case, body, fmi_type):
    expected, got, got_energy = paper_units(case, body, fmi_type, paper_fmu=fmu_path, si_fmu=si_fmu_path)
    assert len(got) == len(expected) and np.allclose(got["time"], expected["time"], rtol=1e-12, atol=0)
    assert np.any(expected["contact"]) and not expected["contact"][-1]     # the runs touch and leave the floor
    # The discrete states agree on every grid point.
    assert np.array_equal(got["contact"], expected["contact"])
    assert np.array_equal(got["mode"], expected["mode"])
    # The continuous ones to the solver's tolerance. Co-Simulation runs the same embedded CVODE on
    # the same scaled equations (the SI nominals are PainleveRod's scaled): equal to rounding, ~1e-11
    # of each variable's range. Model Exchange runs two loops on fmpy's CVode (simulate_fmu for
    # PainleveRod, the SI loop that applies inputs in each right-hand side): ~1e-7 of the range
    # (rtol 1e-10 amplified along the compression's unstable direction). A wrong scale is O(1).
    tol = 1e-6 if fmi_type == "ModelExchange" else 1e-9
    scale = dict(x=1.0, v=1.0, y=case.epsilon ** 2, w=case.epsilon, theta=1.0, phi=1.0, F_N=1.0, F_T=1.0)
    for name, s in scale.items():
        span = max(s, float(np.max(np.abs(expected[name]))))
        assert np.max(np.abs(got[name] - expected[name])) <= tol * span, name
    assert np.max(np.abs(got_energy - expected["energy"])) <= tol * np.max(np.abs(expected["energy"]))


WIDE, THIN = dict(alpha=3.0, mu=3.0, theta0=1.0), dict(alpha=3.0, mu=1.4, theta0=1.06)


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
@pytest.mark.parametrize("params, delta", [(WIDE, 0.5), (WIDE, 2.0), (THIN, 1.0)])
def test_the_si_model_passes_theorem1(si_fmu_path, params, delta, fmi_type):
    # the rule of tests/fmu/test_theorems_on_fmu.py: IWC, w -> e v0 and phi -> its jump, within 1% at the
    # smallest eps and falling with eps; here on a 2 kg, 0.8 m rod on a raised belt running backwards
    # (the states are absolute: at eps = 1e-6 the gap, 4e-13 m, is 1e-11 of the floor's height)
    epsilons = acceptance.in_regime([1e-4, 1e-5, 1e-6], delta)
    floor = si.Floor(y0=0.05, v=-0.7)
    with SIExperiment(si_fmu_path, fmi_type=fmi_type) as ex:
        outcomes = [ex.run_case(Case(phi0=0.5, v0=1.0, delta=delta, epsilon=eps, **params), m=2.0, l=0.4, floor=floor)
                    for eps in epsilons]
    assert an.quadrant(params["theta0"], 0.5, alpha=3.0, mu=params["mu"]) == "inconsistent"
    assert not acceptance.theorem1_failures(outcomes), [(o.case.epsilon, o.w_error, o.phi_error) for o in outcomes]


@pytest.mark.parametrize("factor", [1.5, 1 / 1.5])
def test_the_si_model_passes_theorem2_on_both_sides_of_w1_star(si_fmu_path, factor):
    w1s = an.predict(Case(**VIDEO)).w1_star
    with SIExperiment(si_fmu_path) as ex:
        outcomes = [ex.run_case(Case(epsilon=eps, w10=factor * w1s, **VIDEO)) for eps in (1e-4, 1e-5)]
    if factor > 1:    # w10 below w1*: IWC with w -> e v0
        assert not acceptance.theorem1_failures(outcomes), [o.w_error for o in outcomes]
    else:             # above: lift-off, w = O(eps)
        assert not acceptance.lift_off_failures(outcomes), [o.w for o in outcomes]


def test_the_default_si_rod_leaves_the_floor_at_e_times_its_slip(si_fmu_path):
    # The FMU's own defaults (1 kg, 1 m rod, k = 2e7 N/m, c = 4500 N s/m, v = 2 m/s, phi = 2 rad/s):
    # si.predict says w = e(1.0062, 1) v = 0.2174 m/s and phi = 4.348 rad/s, to O(eps ln 1/eps)
    rod, state = si.SIRod(), si.SIState()
    predicted = si.predict(rod, state)
    with SIExperiment(si_fmu_path) as ex:
        r = ex.simulate(rod, state, stop_time=5 * predicted.duration, output_interval=predicted.duration / 50)
    touched = np.flatnonzero(r["contact"])
    back = touched[-1] + 1 + np.flatnonzero(r["gap"][touched[-1] + 1:] >= 0)[0]   # first row back above the floor
    assert r["w"][back] == pytest.approx(predicted.w, rel=0.01)
    assert r["phi"][back] == pytest.approx(predicted.phi, rel=0.01)
