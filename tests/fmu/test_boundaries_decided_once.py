# SPDX-License-Identifier: BSD-2-Clause
"""Contact boundaries that the motion goes on along are decided once (fmu_src/contact/contact.c's
in_contact, contact_events.c, contact_record.c).

Two legal call sequences, recorded from random runs (tests/fmu/data/chatter_cases.json: their
start values, tolerance and every communication step), ended in Discard after 20,000 events
within one step: a TwoLinkArm whose tip sinks into a floor with strong Hunt-Crossley damping
(beta = 4.4) and an SI rod on a moving floor, each at F_N = 0 with the free motion's h' > 0,
where contact and flight swapped at every step of the integrator. Replayed in FMI 2.0 and 3.0,
every step returns OK, and the whole run takes a few events per contact: the F_N = 0 boundary is
met a handful of times (contacts that end), not thousands."""
import json
import pathlib
import re

import pytest
from fmpy import extract, read_model_description
from fmpy.simulation import instantiate_fmu

from conftest import built_fmu

CASES = json.loads((pathlib.Path(__file__).parent / "data" / "chatter_cases.json").read_text())["cases"]
# Events of one run at the F_N = 0 boundary: one per contact that ends there, against 20,000
# within one step when the boundary chattered; and all events of a run: the few switches of each
# of its contacts (entry, stick, slip, lift-off, the return), a few dozen contacts at most.
MOST_FORCE_EVENTS = 20
MOST_EVENTS = 300


def replay(case, fmi):
    path = built_fmu(f"{case['model']}.fmu") if fmi == 2 else built_fmu("fmi3", f"{case['model']}.fmu")
    md = read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    events, counted = [], []

    def log(*args):
        if args[-2] == b"logEvents":
            events.append(args[-1].decode())
        elif args[-2] == b"logStatistics":   # every event update of a step, logged or not
            counted.append(int(re.search(r"events (\d+)", args[-1].decode()).group(1)))

    fmu = instantiate_fmu(extract(path), md, "CoSimulation", debug_logging=True, logger=log)
    names = list(case["start_values"])
    values = [case["start_values"][n] for n in names]
    if fmi == 3:
        fmu.setFloat64([vr[n] for n in names], values)
        fmu.enterInitializationMode(tolerance=case["tolerance"], startTime=case["start_time"])
    else:
        fmu.setupExperiment(tolerance=case["tolerance"], startTime=case["start_time"])
        fmu.setReal([vr[n] for n in names], values)
        fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    t, completed = case["start_time"], 0
    try:
        for h in case["steps"]:
            fmu.doStep(t, h)   # fmpy raises on any status but OK (and Warning)
            t += h
            completed += 1
    finally:
        fmu.freeInstance()
    return completed, events, sum(counted)


@pytest.mark.parametrize("fmi", [2, 3])
@pytest.mark.parametrize("case", CASES, ids=[c["model"] for c in CASES])
def test_a_run_along_the_force_boundary_completes_and_decides_it_a_few_times(case, fmi):
    completed, events, n_events = replay(case, fmi)
    assert completed == len(case["steps"])
    at_force_boundary = [e for e in events if re.search(r"indicator [^;]*F_N = 0", e)]
    assert len(at_force_boundary) <= MOST_FORCE_EVENTS, at_force_boundary[:5]
    assert 0 < n_events <= MOST_EVENTS
