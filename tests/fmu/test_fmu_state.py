# SPDX-License-Identifier: BSD-2-Clause
"""FMU state: saved during stick, restored, serialized into a new instance, the
run continues bit for bit; bad bytes are refused with a message."""
import struct
from ctypes import POINTER, c_double

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from helpers.raw_instances import Rod

_P = POINTER(c_double)


def run(rod, steps, h=1e-6):
    out = []
    for _ in range(steps):
        rod.euler_step(h)
        out.append(np.concatenate(([rod.t], rod.x)))
    return np.array(out)


def into_stick(loaded):
    rod = Rod(loaded)
    rod.initialize(epsilon=1e-4)
    while rod.fmu.getInteger([rod.vr["mode"]])[0] != 0:
        rod.euler_step(1e-6)
    run(rod, 20)
    assert rod.fmu.getInteger([rod.vr["mode"]])[0] == 0, "the save point must be during stick"
    return rod


def resume(rod, t):
    """What an importer does after restoring: read the states and indicators again."""
    rod.t = t
    rod.fmu.getContinuousStates(rod.x.ctypes.data_as(_P), rod.nx)
    rod.fmu.getEventIndicators(rod.z.ctypes.data_as(_P), rod.nz)


def test_restore_during_stick_reproduces_the_run_bit_for_bit(loaded):
    rod = into_stick(loaded)
    t, state = rod.t, rod.fmu.getFMUstate()
    first = run(rod, 1500)          # on through the end of stick and lift-off
    assert rod.fmu.getBoolean([rod.vr["contact"]]) == [False]
    rod.fmu.setFMUstate(state)
    resume(rod, t)
    assert np.array_equal(run(rod, 1500), first)
    rod.fmu.freeFMUstate(state)
    rod.free()


def test_serialized_state_continues_identically_in_a_new_instance(loaded):
    rod = into_stick(loaded)
    t, state = rod.t, rod.fmu.getFMUstate()
    data = rod.fmu.serializeFMUstate(state)
    first = run(rod, 1500)
    rod.fmu.freeFMUstate(state)
    rod.free()
    fresh = Rod(loaded, "fresh")
    restored = fresh.fmu.deSerializeFMUstate(data)
    fresh.fmu.setFMUstate(restored)
    fresh.z, fresh.x = np.zeros(fresh.nz), np.zeros(fresh.nx)
    resume(fresh, t)
    assert np.array_equal(run(fresh, 1500), first)
    fresh.free()


def corrupt(data, how):
    b = bytearray(data)
    if how == "truncated":
        return bytes(b[: len(b) // 2])
    if how == "flipped byte":
        b[len(b) // 2] ^= 0x40
        return bytes(b)
    if how == "other version":
        b[8:12] = struct.pack("<I", 99)
    if how == "other model":
        b[17] = ord("0") if b[17] != ord("0") else ord("1")
    b[-4:] = struct.pack("<I", fnv1a(bytes(b[:-4])))
    return bytes(b)


def fnv1a(data):
    h = 2166136261
    for byte in data:
        h = ((h ^ byte) * 16777619) & 0xFFFFFFFF
    return h


@pytest.mark.parametrize("how, words", [("truncated", "truncated"), ("flipped byte", "corrupted"),
                                        ("other version", "version 99"), ("other model", "state of model")])
def test_bad_bytes_are_refused_with_a_message(loaded, how, words):
    rod = Rod(loaded)
    rod.initialize()
    data = rod.fmu.serializeFMUstate(rod.fmu.getFMUstate())
    fresh = Rod(loaded, "fresh")
    with pytest.raises(FMICallException):
        fresh.fmu.deSerializeFMUstate(corrupt(data, how))
    assert words in fresh.messages[-1][2], fresh.messages[-1]
    rod.free()
    fresh.free()


def test_cosimulation_state_restores_identically(loaded):
    from helpers.raw_instances import Slave
    rod = Slave(loaded, epsilon=1e-4)
    rod.step(2.5e-4)                      # inside the IWC
    state = rod.fmu.getFMUstate()
    t0 = rod.t
    for _ in range(10):
        rod.step(1e-4)
    first = rod.states()
    rod.fmu.setFMUstate(state)
    rod.t = t0
    for _ in range(10):
        rod.step(1e-4)
    assert np.array_equal(rod.states(), first)
