# SPDX-License-Identifier: BSD-2-Clause
"""Co-Simulation's explicit pair (fmu_src/fmi/explicit_rk.c): the
Dormand-Prince 5(4) pair integrates flights and short contacts, locates events on
its dense output, and hands a sustained contact to CVODE. Checked against the
free flight's closed form, against Model Exchange under fmpy's CVode (another
integrator), and by the log line a hand-over writes."""
import math

import fmpy
import pytest

HAND_OVER = "a sustained stiff phase: CVODE integrates on"
STATES = ("x", "v", "y", "w", "theta", "phi")


def slave(loaded, tolerance, **start):
    messages = []
    fmu = loaded.instantiate(fmi_type="CoSimulation", logging_on=True, on_message=lambda *m: messages.append(m))
    fmu.setupExperiment(tolerance=tolerance, startTime=0.0)
    fmu.setReal([loaded.vr[k] for k in start], list(start.values()))
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, messages


def logged(messages):
    return " | ".join(str(m[-1]) for m in messages)


def flight(state, s):
    """The free flight from `state` after time s (the rod's centre of mass falls freely, the rod
    spins uniformly: y is the lower end's height, w its vertical velocity, l = m = g = 1)."""
    x, v, y, w, th, ph = (state[k] for k in STATES)
    vx, vy = v + ph * math.sin(th), w + ph * math.cos(th)   # the centre's velocity
    th1 = th + ph * s
    return dict(x=x - math.cos(th) + vx * s + math.cos(th1), v=vx - ph * math.sin(th1),
                y=y + math.sin(th) + vy * s - s * s / 2 - math.sin(th1), w=vy - s - ph * math.cos(th1),
                theta=th1, phi=ph)


@pytest.mark.parametrize("tolerance", [1e-6, 1e-9])
def test_a_free_flight_follows_its_closed_form_to_the_tolerance(loaded, tolerance):
    start = dict(x=0.0, v=0.3, y=0.5, w=0.8, theta=1.0, phi=2.5)
    fmu, messages = slave(loaded, tolerance, epsilon=1e-3, **start)
    for k in range(4):                     # communication points on the way
        fmu.doStep(k * 0.1, 0.1)
    end = dict(zip(STATES, fmu.getReal([loaded.vr[k] for k in STATES])))
    exact = flight(start, 0.4)
    assert exact["y"] > 0 and all(flight(start, k * 0.01)["y"] > 0 for k in range(41))   # no landing
    for k in STATES:
        assert abs(end[k] - exact[k]) <= 10 * tolerance * max(1.0, abs(exact[k])), (k, end[k], exact[k])
    assert HAND_OVER not in logged(messages)
    fmu.terminate()
    fmu.freeInstance()


RECORD = ("t_contact_begin", "t_stick_begin", "t_stick_end", "t_contact_end")


@pytest.mark.parametrize("eps", [1e-3, 1e-5])
def test_the_events_of_an_iwc_are_model_exchanges_in_the_same_order(fmu_path, eps):
    # The default experiment's IWC (Theorem 1 at theta0 = 1): the FMU's own record of its
    # switches, through Co-Simulation (the explicit pair's roots on its dense output) and
    # through Model Exchange (fmpy's CVode finding the same indicators' roots).
    stop = 150 * eps
    out = list(RECORD) + ["switches", "sticks", "w"]
    runs = [fmpy.simulate_fmu(fmu_path, fmi_type=kind, relative_tolerance=1e-9, stop_time=stop,
                              output_interval=stop / 10, start_values=dict(epsilon=eps), output=out)[-1]
            for kind in ("ModelExchange", "CoSimulation")]
    me, cs = runs
    assert cs["switches"] == me["switches"] == 3 and cs["sticks"] == me["sticks"] == 1
    assert 0 == cs["t_contact_begin"] < cs["t_stick_begin"] < cs["t_stick_end"] < cs["t_contact_end"] < stop
    for name in RECORD:     # each event where the other integrator puts it, to its own accuracy
        assert abs(cs[name] - me[name]) <= 1e-4 * eps, (name, cs[name], me[name])


def test_a_sustained_contact_goes_to_cvode_and_an_iwc_does_not(loaded, fmu_path):
    # At rest on the floor at theta = 1 with mu = 3 the rod sticks and tips over: a contact of
    # O(1) time whose spring (time scale eps) holds every explicit step.
    fmu, messages = slave(loaded, 1e-6, epsilon=1e-6, v=0.0, w=0.0, theta=1.0, phi=0.0)
    fmu.doStep(0.0, 0.01)
    assert HAND_OVER in logged(messages)
    cs = dict(zip(STATES, fmu.getReal([loaded.vr[k] for k in STATES])))
    fmu.terminate()
    fmu.freeInstance()
    me = fmpy.simulate_fmu(fmu_path, fmi_type="ModelExchange", relative_tolerance=1e-9, stop_time=0.01,
                           output_interval=2e-5, start_values=dict(epsilon=1e-6, v=0.0, w=0.0, theta=1.0, phi=0.0),
                           output=list(STATES))[-1]
    assert cs["theta"] == pytest.approx(me["theta"], abs=1e-6) and cs["phi"] == pytest.approx(me["phi"], abs=1e-5)
    assert cs["theta"] < 1.0 and cs["phi"] < 0     # tipping over: theta falls
    iwc, messages = slave(loaded, 1e-6, epsilon=1e-6)
    iwc.doStep(0.0, 150e-6)
    assert "contact 1 -> 0" in logged(messages) and HAND_OVER not in logged(messages)
    iwc.terminate()
    iwc.freeInstance()


# bench/bounded_calls.py's case 210 (seed 1): an SI rod in a contact damped by c = 4.8e9 N s/m.
CASE_210 = dict(m=1, l=0.5, J=0.0833333333333333, g=9.81, k=3461058.4049120061, c=4753199200.16998,
                mu=6.483406140932706, x=1.1493530796278491e-06, v=2, y=-9.9638739918554971e-06, w=0, theta=1, phi=2,
                y_floor=0.0045908966285420913, w_floor=2.7015003459329656e-05, v_floor=-0.060724187272739087,
                F_x=-0.00057695975749177128, F_y=0.34885816248280105, tau=0)


def test_a_stiff_contact_stays_with_cvode_and_its_force_does_not_chatter(si_fmu_path):
    # The contact holds (F_N > 0 throughout: the rod sticks, then slips backward), but its force is
    # the damping times w: the explicit pair's errors, within the tolerance in w, made the force
    # indicator cross 0 again and again (20,000 spurious lift-offs, fmi2Discard) until the
    # trajectory stayed with CVODE once handed over. Now: two switches, the contact never ends.
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(si_fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(si_fmu_path), modelIdentifier=md.coSimulation.modelIdentifier)
    fmu.instantiate()
    fmu.setupExperiment(tolerance=4.0610954205445336e-06, startTime=-13.095944350373685)
    fmu.setReal([vr[k] for k in CASE_210], list(CASE_210.values()))
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.doStep(-13.095944350373685, 0.00020849322450497177)    # raises on fmi2Discard
    assert fmu.getBoolean([vr["contact"]]) == [True]
    assert fmu.getInteger([vr["switches"]])[0] == 2
    fmu.terminate()
    fmu.freeInstance()
