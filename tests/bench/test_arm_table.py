# SPDX-License-Identifier: BSD-2-Clause
"""bench/arm_table.py's claim, checked where the reference is cheap: TwoLinkArm through one
fmi2DoStep to the independent numpy arm's return (DOP853 at 1e-12) has the reference's w there
within 1e-6 v0 at the FMU's default tolerance and at the harness's, out of contact, after the
impact's three switches (slip to stick, stick to slip, lift-off)."""
import sys

import pytest

from conftest import ROOT
from painleve.fmu.experiment import Experiment

sys.path.insert(0, str(ROOT / "bench"))
import arm_table  # noqa: E402


@pytest.mark.parametrize("eps", [1e-2, 1e-3, 1e-5])
def test_the_arm_in_one_do_step_lands_on_the_numpy_arm(arm_path, eps):
    with Experiment(arm_path, fmi_type="CoSimulation") as ex:
        for theta1, v0, delta in arm_table.CASES:
            t_ref, w_ref = arm_table.reference(theta1, v0, eps, delta)
            values = arm_table.start(theta1, v0, eps, delta)[2]
            for rtol in sorted({1e-6, min(1e-6, eps / 100)}):
                _, w, switches, contact = arm_table.run_once(ex, values, rtol, t_ref)
                assert not contact and switches == 3
                assert abs(w - w_ref) < 1e-6 * v0, (theta1, delta, rtol)
                assert 0.05 < w_ref / v0 < 0.2         # an IWC: w of the order e v0, far from 0 and from v0


def test_the_arm_at_its_equal_accuracy_rtol_is_within_1e_6_relative_of_the_numpy_arm(arm_path):
    # bench/arm_table.py --equal picks, per eps, the loosest rtol of the ladder at which every case's w
    # at the reference's return is within 1e-6 relative of the numpy arm; re-run there, each case is.
    eps = 1e-3
    refs = [arm_table.reference(theta1, v0, eps, delta) for theta1, v0, delta in arm_table.CASES]
    with Experiment(arm_path, fmi_type="CoSimulation") as ex:
        rtol, err = arm_table.equal_accuracy(ex, eps, refs)
        assert rtol in arm_table.LADDER and err <= 1e-6
        for (theta1, v0, delta), (t_ref, w_ref) in zip(arm_table.CASES, refs):
            _, w, _, contact = arm_table.run_once(ex, arm_table.start(theta1, v0, eps, delta)[2], rtol, t_ref)
            assert not contact and abs(w - w_ref) <= 1e-6 * abs(w_ref), (theta1, delta)
