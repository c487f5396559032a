# SPDX-License-Identifier: BSD-2-Clause
"""The internals of fmpy 0.3.32 (pinned in requirements.txt) that the Model
Exchange loops (me_fast_loop, si_experiment) and the Co-Simulation loop's direct calls
(cs_calls) use, and nothing else of fmpy's private code does:

- FMU2Model._functions: the FMU's C functions as fmpy typed them, so that
  CVode's right-hand side calls fmi2SetTime ... fmi2GetDerivatives directly
  instead of through fmpy's Python wrappers (a status check and a call logger
  in Python for each of three calls per right-hand side cost more than the model; the same
  for a Co-Simulation case's 11 calls);
- the serial N_Vector's content struct, to reach a vector's data without
  fmpy's two casts per access (the callbacks' hottest line);
- fmpy's handle on its CVODE library, for CVodeGetNumSteps and CVodeSetStopTime (which
  fmpy does not bind): the SI rod's loop (si_experiment) stops CVode exactly at an
  input's jump, so that no right-hand side sees the input after it.

tests/fmu/test_me_fast_loop.py fails, naming what moved, if an fmpy update
changes any of them."""
from ctypes import POINTER, c_double, c_int, c_long, c_void_p

from fmpy.sundials.libraries import sundials_cvode
from fmpy.sundials.nvector_serial import _N_VectorContent_Serial

FUNCTIONS = ("fmi2SetTime", "fmi2SetContinuousStates", "fmi2GetDerivatives", "fmi2GetEventIndicators")

cvode_get_num_steps = sundials_cvode.CVodeGetNumSteps     # fmpy binds it without types
cvode_get_num_steps.argtypes, cvode_get_num_steps.restype = [c_void_p, POINTER(c_long)], c_int
cvode_set_stop_time = sundials_cvode.CVodeSetStopTime
cvode_set_stop_time.argtypes, cvode_set_stop_time.restype = [c_void_p, c_double], c_int


def c_functions(instance):
    """(fmi2SetTime, fmi2SetContinuousStates, fmi2GetDerivatives, fmi2GetEventIndicators) of an
    instantiated fmpy FMU2Model, as ctypes functions taking the component first."""
    return fmi2_functions(instance, FUNCTIONS)


def fmi2_functions(instance, names):
    """The FMI 2.0 C functions `names` of an instantiated fmpy FMU2Model or FMU2Slave, as fmpy typed
    them (argtypes, restype), taking the component first."""
    return tuple(instance._functions[name] for name in names)


def vector_data(vector):
    """NV_DATA_S of a serial N_Vector: its double* data."""
    return _N_VectorContent_Serial.from_address(vector.contents.content).data
