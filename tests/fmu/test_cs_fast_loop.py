# SPDX-License-Identifier: BSD-2-Clause
"""The harness's Co-Simulation fast loop: one long first doStep, the outcome read off the FMU's
record of its switches and the free flight run back in closed form, gives the stepped loop's
outcome within the tolerance, and the lift-off w of a tight independent Model Exchange run."""
import math
from dataclasses import replace

import numpy as np
import pytest

from painleve.experiments.case import Case
from painleve.experiments.outcome import flight_back_to_floor
from painleve.fmu import cs_fast_loop
from painleve.fmu.experiment import Experiment
from painleve.theory import analytic as an


def free_flight(theta, phi, v, w, s):
    """The rigid rod's free flight from y = 0 over time s, in 80-bit floats: the centre of mass
    (x - cos, y + sin) falls freely, the rod spins uniformly; sin(th + ph s) - sin(th) evaluated
    as 2 cos(th + ph s/2) sin(ph s/2), so the height's error is 1e-19 of its own terms, not of
    sin(th) (which would put 1e-19 / w into the time: 1e-12 at w = 1e-7)."""
    th, ph, s = np.longdouble(theta), np.longdouble(phi), np.longdouble(s)
    half = ph * s / 2
    d_sin, d_cos = 2 * np.cos(th + half) * np.sin(half), -2 * np.sin(th + half) * np.sin(half)
    y = (np.longdouble(w) + ph * np.cos(th)) * s - s * s / 2 - d_sin
    return dict(y=float(y), w=float(np.longdouble(w) - s - ph * d_cos), v=float(np.longdouble(v) - ph * d_sin),
                theta=float(th + ph * s), phi=float(ph))


# w = 1e-7 is a Theorem 2 lift-off's at eps = 1e-6: the O(1) terms of the height cancel to 1e-16,
# which the run back must not turn into 1e-16 / w of time (a relative 1e-3 in w).
# What rounding is left is 1e-16 of the flight's own terms (~phi s) over w: s up to a few hundred w.
@pytest.mark.parametrize("w, s", [(1e-7, 2e-6), (1e-7, 2e-5), (1e-4, 2e-6), (1e-4, 1e-3), (0.5, 1e-3), (0.5, 0.2)])
def test_flight_back_to_floor_inverts_the_free_flight(w, s):
    theta, phi, v = 1.0, 1.7, 0.3         # phi^2 sin(theta) > 1: the end rises faster and faster
    back_s, back = flight_back_to_floor(free_flight(theta, phi, v, w, s))
    assert back_s == pytest.approx(-s, rel=1e-9)
    assert back["w"] == pytest.approx(w, rel=1e-8)
    assert back["v"] == pytest.approx(v, rel=1e-12, abs=1e-14)
    assert back["theta"] == pytest.approx(theta, rel=1e-14)


def cases():
    wide = Case(theta0=1.0, phi0=0.5, delta=1.0)
    video = Case(theta0=0.9463, phi0=1.6654, delta=1.0)         # Theorem 2: lifts off above w1*
    w1 = an.predict(video).w1_star
    return [replace(wide, epsilon=eps) for eps in (1e-2, 1e-4, 1e-6)] + \
        [replace(wide, delta=0.0, epsilon=1e-3)] + \
        [replace(video, w10=f * w1, epsilon=eps) for f in (1.5, 0.5) for eps in (1e-3, 1e-6)]


@pytest.fixture(scope="module")
def experiments(fmu_path):
    with Experiment(fmu_path, fmi_type="CoSimulation") as cs, \
            Experiment(fmu_path, relative_tolerance=1e-11) as me:
        yield cs, me


@pytest.mark.parametrize("case", cases(), ids=lambda c: f"th{c.theta0}-d{c.delta}-w{c.w10:.3g}-eps{c.epsilon:g}")
def test_one_long_step_gives_the_stepped_outcome(experiments, case):
    cs, me = experiments
    rtol = cs.settings(case)["relative_tolerance"]
    long = cs_fast_loop.run_stepped(cs, case, first=cs_fast_loop.first_step(case))
    stepped = cs_fast_loop.run_stepped(cs, case)
    assert long is not None, "the record tells an IWC or a lift-off after the first step"
    assert long.iwc == stepped.iwc == an.predict(case).iwc
    # within the tolerance's meaning: a few rtol (global error of a locally controlled integrator)
    assert long.w == pytest.approx(stepped.w, rel=20 * rtol)
    assert long.phi == pytest.approx(stepped.phi, rel=20 * rtol)
    for phase in ("t_return", "compression", "stick", "lift_off", "flight_back"):
        a, b = getattr(long, phase), getattr(stepped, phase)
        assert (math.isnan(a) and math.isnan(b)) or abs(a - b) <= 20 * rtol * case.epsilon, phase
    # and the lift-off velocity of a tight Model Exchange run (CVODE at 1e-11, the FMU's events exact)
    reference = me.run(case)
    assert long.w == pytest.approx(reference.w, rel=max(50 * rtol, 1e-7))
    assert cs.run(case).w == long.w          # the harness's path is the long step
