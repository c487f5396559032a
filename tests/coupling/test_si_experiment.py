# SPDX-License-Identifier: BSD-2-Clause
"""The harness's SI loop (painleve.coupling.si_experiment) against fmpy's own: with constant inputs its
Model Exchange loop is fmpy's simulate_fmu, and a belt switched on (an input that jumps) is
handed over at its instant in both interfaces, the same way."""
import math

import numpy as np
import pytest
from fmpy import simulate_fmu

from painleve.coupling import si
from painleve.coupling.si_experiment import OUTPUTS, SIExperiment
from helpers.si_fmu import on_grid

ROD = si.SIRod(k=2e5, c=45.0, mu=0.6)
STATE = si.SIState(x=0.1, v=1.0, y=0.03, w=-0.5, theta=0.8, phi=-3.0)   # dropped: bounces, slips, sticks


def test_with_constant_inputs_the_model_exchange_loop_is_simulate_fmu(si_fmu_path):
    floor, loads = si.Floor(y0=0.01, v=0.5), si.Loads(F_x=2.0, F_y=-3.0, tau=0.4)
    stop, interval, rtol = 0.4, 2e-4, 1e-10
    state = si.SIState(x=STATE.x, v=STATE.v + floor.v, y=STATE.y + floor.y0, w=STATE.w, theta=STATE.theta,
                       phi=STATE.phi)
    with SIExperiment(si_fmu_path) as ex:
        ours = ex.simulate(ROD, state, floor=floor, loads=loads, stop_time=stop, output_interval=interval,
                           relative_tolerance=rtol)
        values = {**floor.inputs(0.0), **loads.inputs()}
        table = np.array([(0.0, *values.values()), (stop, *values.values())],
                         dtype=[("time", float)] + [(n, float) for n in values])
        with ex.fresh_run("simulate_fmu") as instance:
            theirs = simulate_fmu(ex.unzipdir, model_description=ex.model_description, fmu_instance=instance,
                                  start_values={**ROD.parameters(), **state.start_values()}, input=table,
                                  output=list(OUTPUTS), stop_time=stop, output_interval=interval,
                                  relative_tolerance=rtol, validate=False)
    a, b = on_grid(ours, interval), on_grid(theirs, interval)
    assert len(a) == len(b) and np.array_equal(a["mode"], b["mode"]) and np.array_equal(a["contact"], b["contact"])
    assert len(set(a["mode"])) == 3          # slips both ways and sticks
    # both are fmpy's CVode at rtol 1e-10 stopping at the same points; they differ in the stops'
    # details only (fmpy's simulate_fmu does not stop CVode at the grid points, it interpolates):
    # a contact's start placed 3e-9 s apart moves F_N by its slope times that (measured: 1.1e-6 of
    # its peak, the states 8e-7 and less)
    for name in ("x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy"):
        assert np.max(np.abs(a[name] - b[name])) <= 2e-6 * np.max(np.abs(b[name])), name


def test_a_belt_switched_on_is_handed_over_at_its_instant(si_fmu_path):
    # A rod put down at rest sticks; at t = 0.05 s the belt starts at U = 0.3 m/s. The rod's own
    # velocity does not jump, its slip does (by -U), and it slips backward from then on.
    rod, state, U, t_on = si.SIRod(k=2e5, c=900.0, mu=0.8), si.SIState(v=0.0, theta=0.6, phi=0.0), 0.3, 0.05

    def inputs(t):
        return dict(v_floor=U if t >= t_on else 0.0)
    runs = {}
    for fmi_type in ("ModelExchange", "CoSimulation"):
        with SIExperiment(si_fmu_path, fmi_type=fmi_type) as ex:
            runs[fmi_type] = ex.simulate(rod, state, inputs=inputs, jumps=(t_on,), stop_time=0.1,
                                         output_interval=1e-3, relative_tolerance=1e-10)
    me, cs = runs["ModelExchange"], runs["CoSimulation"]
    before, after = np.flatnonzero(me["time"] == t_on)            # the event's two rows
    assert (me["mode"][before], me["mode"][after]) == (0, -1)
    assert me["v"][after] == me["v"][before] == 0.0               # held at the belt's old speed exactly
    assert me["slip"][after] == -U
    settled = (me["time"] > 1e-3) & (me["time"] < t_on)       # (at t = 0, F_N = 0: it sticks at the first event)
    assert np.all(me["mode"][settled] == 0) and np.all(me["contact"])
    # Co-Simulation hands the jump over at the start of the next step (its outputs at t_on itself
    # still show the stick): the grids are compared away from that instant.
    a, b = on_grid(me, 1e-3), cs
    assert len(a) == len(b)
    a, b = a[a["time"] != t_on], b[b["time"] != t_on]
    assert np.array_equal(a["mode"], b["mode"])
    for name in ("v", "w", "y", "theta", "phi", "F_N", "F_T", "slip"):
        assert np.max(np.abs(a[name] - b[name])) <= 1e-6 * np.max(np.abs(b[name])), name
    assert math.isclose(b["slip"][-1] - b["v"][-1], -U, rel_tol=1e-12)     # slip = v - v_floor


def test_another_models_fmu_is_refused_saying_why(fmu_path):
    with pytest.raises(ValueError, match="is not PainleveRodSI: it has no variables y_floor"):
        SIExperiment(fmu_path)
