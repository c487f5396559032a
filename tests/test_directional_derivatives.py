"""fmi2GetDirectionalDerivative against central finite differences of the derivatives, in every mode."""
from ctypes import POINTER, c_double

import numpy as np
import pytest

from painleve.experiment import STATES
from raw_instances import Rod

DERS = [f"der({s})" for s in STATES]
_P = POINTER(c_double)


def derivatives(rod, x):
    rod.fmu.setContinuousStates(np.ascontiguousarray(x).ctypes.data_as(_P), 6)
    dx = np.zeros(6)
    rod.fmu.getDerivatives(dx.ctypes.data_as(_P), 6)
    return dx


def jacobian_fd(rod, x0, nominal):
    J = np.zeros((6, 6))
    for j in range(6):
        h = 1e-6 * max(abs(x0[j]), nominal[j])
        xp, xm = x0.copy(), x0.copy()
        xp[j] += h
        xm[j] -= h
        J[:, j] = (derivatives(rod, xp) - derivatives(rod, xm)) / (2 * h)
    derivatives(rod, x0)
    return J


def jacobian_fmu(rod):
    known = [rod.vr[s] for s in STATES]
    unknown = [rod.vr[d] for d in DERS]
    return np.array([rod.fmu.getDirectionalDerivative(unknown, known, list(np.eye(6)[j])) for j in range(6)]).T


# States that put the rod in each mode: (start values, expected (contact, mode)).
MODES = {
    "flight": (dict(y=0.5, w=0.3, theta=0.7, phi=1.3, v=0.4), (False, 1)),
    "slip forward": (dict(y=-2e-7, w=-1e-4, theta=0.3, phi=0.4, v=0.2, mu=1.0), (True, 1)),
    "slip backward": (dict(y=-2e-7, w=-1e-4, theta=0.3, phi=0.4, v=-0.2, mu=1.0), (True, -1)),
    "stick": (dict(y=-2e-7, w=-1e-4, theta=0.3, phi=0.4, v=0.0, mu=1.0), (True, 0)),
}


@pytest.mark.parametrize("name", MODES)
def test_directional_derivatives_match_central_differences(loaded, name):
    start, expected_mode = MODES[name]
    rod = Rod(loaded)
    rod.initialize(**start)
    assert (bool(rod.fmu.getBoolean([rod.vr["contact"]])[0]), rod.fmu.getInteger([rod.vr["mode"]])[0]) == expected_mode
    nominal = np.zeros(6)
    rod.fmu.getNominalsOfContinuousStates(nominal.ctypes.data_as(_P), 6)
    J, J_fd = jacobian_fmu(rod), jacobian_fd(rod, rod.x.copy(), nominal)
    scale = np.abs(J_fd).max(axis=1, keepdims=True) + 1e-300
    np.testing.assert_allclose(J / scale, J_fd / scale, rtol=0, atol=1e-6)
    rod.free()
