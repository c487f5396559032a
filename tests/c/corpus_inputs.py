# SPDX-License-Identifier: BSD-2-Clause
"""The regression inputs of tests/c/corpus that replay a finding as a readable call
sequence: each is written here in the byte format of fuzz_fmi.c (FMI 2.0) or
fuzz_fmi3.c (FMI 3.0) (see fuzz_bytes.h), so that the file can be remade and
read. Values are raw IEEE bit patterns (exact), instances are slot 0. Inputs
kept as libFuzzer wrote them (regress-bounded-found-*, fuzz_bounded's format)
are not listed here.

    python tests/c/corpus_inputs.py            rewrite the files below in tests/c/corpus
    python tests/c/corpus_inputs.py --check    fail if a file differs from what is written here
"""
import pathlib
import struct
import sys

CORPUS = pathlib.Path(__file__).resolve().parent / "corpus"


def raw(x):
    """take_double's raw branch: a selector >= 192, then the 8 bytes big-endian."""
    return bytes([0xC0]) + struct.pack(">d", x)


class Fmi2:
    """fuzz_fmi.c's opcodes (N_OPS = 36) on instance slot 0."""
    INSTANTIATE, SET_REAL, SETUP, ENTER_INIT, EXIT_INIT, DO_STEP = 0, 6, 21, 22, 23, 30

    def __init__(self, co_simulation=True):
        # name "rod", the model's GUID, type (3: Co-Simulation, 0: Model Exchange), flags 0 (a logger)
        self.b = bytes([self.INSTANTIATE, 0, 0, 3 if co_simulation else 0, 0])

    def setup(self, tolerance, start):
        self.b += bytes([self.SETUP, 1]) + raw(tolerance) + raw(start) + raw(0.0)
        return self

    def set_real(self, values):
        """values: (value reference, value) pairs, 8 to a call (CAP); the count byte is their number."""
        if len(values) > 8:
            return self.set_real(values[:8]).set_real(values[8:])
        self.b += bytes([self.SET_REAL, len(values)])
        for vr, x in list(values) + [(0, 0.0)] * (8 - len(values)):
            self.b += bytes([vr]) + raw(x) + bytes([0])
        return self

    def initialize(self):
        self.b += bytes([self.ENTER_INIT, 0, self.EXIT_INIT, 0])
        return self

    def do_step(self, h):
        """fmi2DoStep(the instance's time, h, noSetFMUStatePriorToCurrentPoint = true)."""
        self.b += bytes([self.DO_STEP, 1]) + raw(h)
        return self


class Fmi3:
    """fuzz_fmi3.c's opcodes (N_OPS = 25) on instance slot 0."""
    INSTANTIATE_CS, ENTER_INIT, EXIT_INIT, SET_FLOAT64, DO_STEP = 1, 4, 5, 6, 18

    def __init__(self):
        # name "rod", the model's instantiation token, flags 0 (a logger, no event mode, no early return)
        self.b = bytes([self.INSTANTIATE_CS, 0, 0, 0])

    def set_float64(self, values):
        if len(values) > 8:
            return self.set_float64(values[:8]).set_float64(values[8:])
        self.b += bytes([self.SET_FLOAT64, len(values), 0])
        for vr, x in list(values) + [(0, 0.0)] * (8 - len(values)):
            self.b += bytes([vr]) + raw(x)
        return self

    def enter_init(self, tolerance, start):
        self.b += bytes([self.ENTER_INIT, 1]) + raw(tolerance) + raw(start) + raw(0.0)
        return self

    def exit_init(self):
        self.b += bytes([self.EXIT_INIT])
        return self

    def do_step(self, h):
        """fmi3DoStep(the instance's time, h)."""
        self.b += bytes([self.DO_STEP, 1]) + raw(h)
        return self


class Bounded:
    """fuzz_bounded.c's input: one run. Tolerance and start time raw; parameters, states and inputs kept
    at their start values (a 0 byte each) unless `values` gives bytes for some (in the XML's order);
    each step a byte k: h = span * 10^(-k/8)."""

    def __init__(self, co_simulation, tolerance=None, start=0.0, kept=0, steps=()):
        flags = (1 if co_simulation else 0) | (2 if tolerance is not None else 0)
        self.b = (bytes([flags, 0xFA]) + raw(tolerance if tolerance is not None else 0.0) + bytes([0xFA]) + raw(start)
                  + bytes(kept) + bytes(steps))


# PainleveRod's value references (modelDescription.xml; FMI 3.0 numbers them alike).
ROD = dict(alpha=0, mu=1, delta=2, epsilon=3, x=4, v=5, y=6, w=7, theta=8, phi=9, kappa=24)
# PainleveRodSI's (fmu_src/models/PainleveRodSI/modelDescription.xml).
SI = dict(m=0, l=1, J=2, g=3, k=4, c=5, mu=6, y_floor=10, w_floor=11, v_floor=12, F_x=13, F_y=14, tau=15, x=16, v=17, y=18, w=19, theta=20, phi=21)


def rod_values(**values):
    return [(ROD[k], v) for k, v in values.items()]


def si_values(**values):
    return [(SI[k], v) for k, v in values.items()]


# A hang: tolerance = startTime = 48.125, steps of 0.02 and 0.069: the second never returned.
HANG_TOL = HANG_START = 48.125
# A hang: a random legal PainleveRod FMI 2.0 Co-Simulation case at tolerance 1.56e-6 (steps of 0.257).
HANG_ROD = rod_values(alpha=19.93, epsilon=4.87e-6, kappa=3.19, y=-0.1138, w=0.863, phi=1.220)
# A hang: a random legal PainleveRodSI case at tolerance 0.157 (the rod then rides the rising floor, and a step
# across t = 2.12 never returns); the fuzz target's budget of integrated time is 0.2 s, so the input starts from
# the state a step to t = 2 gives (the floor there at y_floor, 2e-9 m below the end point).
HANG_SI = si_values(m=1.30, l=4.30, J=0.0662, c=2801, w_floor=0.918, F_x=0.184, F_y=0.0925, y_floor=1.836,
                       x=22.655100914489168, v=7.048054929223361, y=1.83599999795985, w=0.9179999877867877,
                       theta=5.9989693168944, phi=-2.82071953447854)

INPUTS = {
    # Read by every target (any bytes are an input of each); the rod's own targets are the ones they replay.
    "regress3-tolerance-48.125-second-step-hangs":
        Fmi3().enter_init(HANG_TOL, HANG_START).exit_init().do_step(0.02).do_step(0.069).b,
    "regress-tolerance-48.125-second-step-hangs":
        Fmi2().setup(HANG_TOL, HANG_START).initialize().do_step(0.02).do_step(0.069).b,
    "regress-stiff-deep-start-step-hangs":
        Fmi2().setup(1.56e-6, 0.0).set_real(HANG_ROD).initialize().do_step(0.257).do_step(0.257).b,
    "regress3-stiff-deep-start-step-hangs":
        Fmi3().enter_init(1.56e-6, 0.0).set_float64(HANG_ROD).exit_init().do_step(0.1).do_step(0.1).b,
    "regress-si-loose-tolerance-step-hangs":
        Fmi2().setup(0.157, 0.0).set_real(HANG_SI).initialize().do_step(0.1).do_step(0.1).b,
    # tests/fmu/test_bounded_calls.py's case 363 (seed 1): mu at its max 1e6, tolerance 1.67e-4, start 48.125.
    "regress3-bounded-case-363-mu-1e6-step-hangs":
        Fmi3().enter_init(0.00016730382132527658, 48.125)
        .set_float64(rod_values(alpha=10.0600042616934, mu=1e6, delta=0.7782685507711189, epsilon=0.00485469810196373))
        .exit_init().do_step(0.014665020780266711).do_step(0.00014801558883998113).do_step(0.011469033800320013)
        .do_step(0.002528558456644627).do_step(0.02043836028790396).b,
    # fuzz_bounded's first finding: tolerance 48.125, start 1, alpha = mu = 400.06, delta = 2.94e-4, x = -882.8:
    # doStep(1, 2) never returned.
    "regress-bounded-tolerance-48.125-mu-400-step-hangs":
        Fmi2().setup(48.125, 1.0).set_real(rod_values(alpha=400.05642964899721, mu=400.05642964899721,
                                                      delta=0.00029427271762092817, x=-882.8125))
        .initialize().do_step(2.0).b,
    # fuzz_bounded_PainleveRodSI's finding: a rod of 0.35 mm and 0.7 g at g = 0.0068, tolerance 8.7e-6, start
    # time -1606.3125, every state and input -789: single doSteps of 0.2 s and 0.11 s ran 9 and 21 s under the
    # sanitizers (11 s in the release build).
    "regress-si-bounded-tiny-rod-slow-steps":
        Fmi2().setup(8.7332616238284373e-06, -1606.3125)
        .set_real(si_values(m=0.00069783058485986635, l=0.00034891529242993318, J=5.8152548738322171e-05,
                            g=0.0068457180374752891, k=13956.611697197328, c=3.1402376318693985,
                            mu=0.0020934917545795992, y_floor=-789.0625, w_floor=-789.0625, v_floor=-789.0625,
                            F_x=-789.0625, F_y=-789.0625, tau=-789.0625, x=-789.0625, v=-787.0625, y=-789.0625,
                            w=-789.0625, theta=-788.0625, phi=-787.0625))
        .initialize().do_step(0.2).do_step(0.11246826503806982).b,
    # fuzz_bounded's seeds: PainleveRod's 12 parameters, states and inputs kept (6 + 6 bytes; the other
    # models read the step bytes as some of theirs), then steps.
    "seed-bounded-cosim": Bounded(True, 1e-6, 0.0, 12, [24] * 8 + [16] * 4).b,
    "seed-bounded-model-exchange": Bounded(False, 1e-6, 0.0, 12, [24] * 50).b,
    "seed-bounded-tolerance-48.125": Bounded(True, 48.125, 48.125, 12, [8, 4]).b,
}


def main(argv):
    stale = []
    for name, data in INPUTS.items():
        path = CORPUS / name
        if "--check" in argv:
            if not path.exists() or path.read_bytes() != data:
                stale.append(name)
        else:
            path.write_bytes(data)
    if stale:
        sys.exit(f"tests/c/corpus differs from tests/c/corpus_inputs.py: {stale}")


if __name__ == "__main__":
    main(sys.argv[1:])
