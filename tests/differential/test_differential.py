# SPDX-License-Identifier: BSD-2-Clause
"""Differential test: every model's FMU, FMI 2.0 and 3.0, Co-Simulation and Model Exchange, on
seeded random legal cases, against references written in the tests (helpers.differential: the
harness's event-driven rod reference, the SI rod through its scaling to it, the event-driven
Filippov arm of helpers.arm_filippov, the table's closed form). The FMUs are run by fmpy directly.

What fails a run:
* any status worse than a warning (fmpy raises) or a failed CVode run, in a legal case (Model
  Exchange runs on fmpy's default output grid, and once more on a 10 times finer one where fmpy's
  CVode runs out of its 500 steps between output points: differential.Loaded.me);
* a scaled difference from the reference (each quantity in its scale: velocities by v0, angles in
  radians, angular rates by v0 over the length or their size if larger;
  differential.scaled_difference) above the bound K tol at relative tolerance tol (K = 100: a solver
  keeps each step's error below tol, and the global error over the few hundred steps of a contact is
  a modest multiple of that), or 1e-4 at the FMU's default tolerance (1e-6); that per phase whose
  errors add: per contact a rod's run covers (each an IWC that amplifies the error it is entered
  with), per period of the table (over each an integrator's phase error grows).

A tolerance that changes nothing: each case runs in Co-Simulation at a loose tolerance (1e-7.5 to
1e-5) and at a tight one 30 to 1000 times smaller (down to 1e-10), both held to their own bound. A
solver that ignores the tolerance, or whose error does not follow it, passes the loose bound and
misses the tight one; a solver whose error is already below the tight bound passes both. The references
are accurate to 1e-9 or better (DOP853 at 1e-11; their own change between 1e-11 and 1e-12 is below
1e-10), far inside the tightest bound 1e-8.

Left out: cases whose reference moves by more than 1e-7 (scaled) when the start angle moves by
1e-10 (near a separatrix or a grazing contact, where no importer can be held to its tolerance).
test_left_out_cases_are_few counts them and fails if they are more than a tenth of the cases, so
the test cannot become vacuous.

Where: the rod (and the SI rod) at its return to y = 0 after the first contact, or in half the cases
up to 1.5 time units later through the flight and the contacts after it (the hand-overs of
Co-Simulation's solvers); the arm at its return; the table after at most 5 periods. A draw whose
reference cannot give that point (an arm tip or a rod that stays on the floor, a reference that
misses a hop) is drawn again (the arm) or compared at its return instead (the rod), and counted
(differential.REDRAWN, printed by bench/differential.py).

Each case is run by both FMI versions and all four interface settings. bench/differential.py runs
thousands of cases off CI."""
import collections

import pytest

from helpers import differential as D

SEED = 20261127
N_CASES = dict(PainleveRod=60, PainleveRodSI=60, TwoLinkArm=60, ShakerTable=60)
SETTINGS = ("CS default", "CS loose", "CS tight", "ME")
MAX_LEFT_OUT = 0.1


@pytest.fixture(scope="module")
def plans():
    """{model: [(case, runs, left out)]}: the seeded cases, their runs, and the sensitivity verdict."""
    return {m: [(case, runs, D.sensitive(case)) for case, runs in D.plan(m, N_CASES[m], SEED)] for m in D.MODELS}


@pytest.fixture(scope="module")
def outcomes(plans):
    """{(model, version, setting): [Outcome]} for every case that is not left out."""
    out = collections.defaultdict(list)
    for model in D.MODELS:
        for version in D.VERSIONS:
            loaded = D.Loaded(D.fmu_path(model, version))
            try:
                for case, runs, left_out in plans[model]:
                    if left_out:
                        continue
                    for setting, (interface, tol, steps) in zip(SETTINGS, runs):
                        out[model, version, setting].append(D.run_case(loaded, case, interface, tol, steps))
            finally:
                loaded.close()
    return out


def report(outcomes):
    failed = [o for o in outcomes if o.failed]
    worst = sorted(failed, key=lambda o: -(float("inf") if o.error else o.diff / o.bound))[:5]
    return f"{len(failed)} of {len(outcomes)} runs fail; worst: " + "; ".join(map(repr, worst))


@pytest.mark.parametrize("setting", SETTINGS)
@pytest.mark.parametrize("version", D.VERSIONS)
@pytest.mark.parametrize("model", D.MODELS)
def test_fmu_agrees_with_the_reference(outcomes, model, version, setting):
    runs = outcomes[model, version, setting]
    assert len(runs) >= (1 - MAX_LEFT_OUT) * N_CASES[model]
    assert not any(o.failed for o in runs), report(runs)


@pytest.mark.parametrize("model", D.MODELS)
def test_left_out_cases_are_few(plans, model):
    """Near-separatrix cases are left out, and counted; they must stay a small fraction."""
    left_out = sum(s for _, _, s in plans[model])
    print(f"{model}: {left_out} of {len(plans[model])} cases left out (reference moves > "
          f"{D.SENSITIVITY_LIMIT:g} under a start-angle move of {D.SENSITIVITY_STEP:g})")
    assert left_out <= MAX_LEFT_OUT * len(plans[model])
