# SPDX-License-Identifier: BSD-2-Clause
"""fmi2GetDirectionalDerivative against central finite differences of
the FMU's own values, and modelDescription.xml's ModelStructure against what the
FMU computes.

- Continuous-Time Mode (Outputs, Derivatives; knowns: the states): the FMU's modes
  are frozen there, so a difference through fmi2SetContinuousStates stays on the
  current mode's branch; one state deep inside each mode.
- Initialization Mode (InitialUnknowns; knowns: parameters and the initial="exact"
  states): the FMU decides the mode from the state whenever it is read, so the
  states sit away from every switching surface and the steps are far too small
  to cross one.
- Exactness: a declared dependency is one whose unknown changes with the known,
  an undeclared one is one whose unknown never does. In Continuous-Time Mode
  (modes frozen) that is the partial derivative, nonzero in some mode or
  identically 0. In Initialization Mode the mode is an auxiliary variable
  decided from the knowns ("directly or indirectly via auxiliary variables",
  FMI 2.0.4 §2.2.8), so a known that changes the unknown only by switching the
  mode (v for der(v): q_+ F_N or q_- F_N; delta for energy: the spring counts
  only in contact) is a dependency too: such changes are found with large
  perturbations around states near the switching surfaces.
"""
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from helpers.raw_instances import Rod, _P

STATES = ["x", "v", "y", "w", "theta", "phi"]
PARAMETERS = ["alpha", "mu", "delta", "epsilon", "kappa", "beta"]
# A nonlinear compliance law, so that the partials by kappa and beta are measured
# (their central differences need kappa, beta > 0: both are refused below 0); the linear law
# kappa = beta = 0 is one point of it, covered by tests/c/rod_partials_check.c.
DEFAULTS = dict(alpha=3.0, mu=3.0, delta=1.0, epsilon=1e-3, kappa=0.5, beta=0.5)
FMI2_ERROR = 3
REL_TOL = 1e-6

# States deep inside one mode (start values, the (contact, mode) they give).
SMOOTH = {
    "flight": (dict(y=0.5, w=0.3, theta=0.7, phi=1.3, v=0.4), (False, 1)),
    # After a damped lift-off: y < 0 without force (g < 0); the spring holds no energy.
    "flight below y = 0": (dict(y=-2e-7, w=0.5, theta=0.7, phi=1.3, v=-0.4), (False, -1)),
    "slip forward": (dict(y=-2e-7, w=-1e-4, theta=0.3, phi=0.4, v=0.2, mu=1.0), (True, 1)),
    "slip backward": (dict(y=-2e-7, w=-1e-4, theta=0.3, phi=0.4, v=-0.2, mu=1.0), (True, -1)),
    "stick": (dict(y=-2e-7, w=-1e-4, theta=0.3, phi=0.4, v=0.0, mu=1.0), (True, 0)),
}
# States next to switching surfaces, where a large perturbation of one known switches the
# mode: the witnesses of the dependencies that act only through the mode decision.
NEAR_SURFACES = {
    # y = 0, w = 0: contact is decided by the sign of b = -1 + phi^2 sin theta (here -6e-4).
    "at rest on y = 0": dict(y=0.0, w=0.0, theta=1.0, phi=1.09, v=0.0, mu=1.0),
    # g = -y/eps - delta w = 1e-4: delta 2 or 10 lifts the rod off (and lets the spring go).
    "compressed and rising": dict(y=-2e-7, w=1e-4, theta=0.3, phi=0.4, v=0.2, mu=1.0),
    # The same at rest: sticks (F_N = 0.1 inside the cone); delta 10 lifts it off, flying with s = sign(a) = -1.
    "compressed and rising, at rest": dict(y=-2e-7, w=1e-4, theta=0.3, phi=0.4, v=0.0, mu=1.0),
    # h = d + kappa d^2 - delta w (1 + beta d) = 1e-8 at d = -y/eps = 2e-4: kappa 0 or beta 1 lift the
    # rod off; at rest with a = 0 (phi = 0) it sticks in contact (q_+ F < 0 < q_- F), flies with s = +1.
    "at rest at the lift-off edge": dict(y=-2e-7, w=1.9999e-4, theta=0.3, phi=0.0, v=0.0, mu=1.0),
    # a = 0: stick while alpha (sin cos - mu sin^2) < mu, i.e. alpha < 4.97; alpha 6 or 9 slips.
    "at rest, alpha at the stick cone's edge": dict(y=-1e-6, w=0.0, theta=1.0, phi=0.0, v=0.0, mu=0.5),
}


NOT_REAL = set()     # Integer and Boolean variables: no directional derivative in FMI 2.0
DISCRETE = set()     # frozen between events: no unknowns in Continuous-Time Mode


@pytest.fixture(scope="module")
def structure(loaded):
    """{list name: {unknown name: set of known names}} from the ModelStructure."""
    md = loaded.model_description
    NOT_REAL.update(v.name for v in md.modelVariables if v.type != "Real")
    DISCRETE.update(v.name for v in md.modelVariables if v.variability == "discrete")
    lists = dict(Outputs=md.outputs, Derivatives=md.derivatives, InitialUnknowns=md.initialUnknowns)
    for name, unknowns in lists.items():
        for u in unknowns:
            assert u.dependencies is not None, f"{name}: {u.variable.name} declares no dependencies (= all knowns)"
    return {name: {u.variable.name: {v.name for v in u.dependencies} for u in unknowns}
            for name, unknowns in lists.items()}


def real_unknowns(structure, *lists):
    names = [n for lst in lists for n in structure[lst] if n not in NOT_REAL]
    return list(dict.fromkeys(names))


def scale_of(name, value, epsilon):
    """The known's own scale: y ~ eps^2, w ~ eps in contact (the FMU's nominals), else 1; parameters their size."""
    nominal = dict(y=epsilon**2, w=epsilon).get(name, 1.0 if name in STATES else 1e-2)
    return max(abs(value), nominal)


class Instance:
    """One Rod, either in Continuous-Time Mode (after initialization) or left in Initialization Mode."""

    def __init__(self, loaded, start, initialization):
        self.rod, self.start = Rod(loaded), {**DEFAULTS, **start}
        self.vr, self.initialization = self.rod.vr, initialization
        if initialization:
            self.rod.fmu.setupExperiment(startTime=0.0)
            self.rod.fmu.enterInitializationMode()
            self.rod.set(**self.start)
        else:
            self.rod.initialize(**self.start)

    def mode(self):
        return (bool(self.rod.fmu.getBoolean([self.vr["contact"]])[0]), self.rod.fmu.getInteger([self.vr["mode"]])[0])

    def known(self, name):
        return self.rod.get(name)[0]

    def set_known(self, name, value):
        if self.initialization:
            self.rod.set(**{name: value})
        else:
            assert name in STATES, "in Continuous-Time Mode only the states are knowns"
            x = np.array(self.rod.get(*STATES))
            x[STATES.index(name)] = value
            self.rod.fmu.setContinuousStates(x.ctypes.data_as(_P), len(x))

    def values(self, names):
        return np.array(self.rod.fmu.getReal([self.vr[n] for n in names]))

    def directional(self, unknowns, knowns, seed):
        return np.array(self.rod.fmu.getDirectionalDerivative([self.vr[n] for n in unknowns],
                                                              [self.vr[n] for n in knowns], list(seed)))

    def free(self):
        self.rod.free()


def jacobians(inst, unknowns, knowns):
    """(fmi2GetDirectionalDerivative, central differences, values, scales n): columns in the
    knowns' scales n_j, J[i, j] = n_j d unknown_i / d known_j."""
    eps = inst.known("epsilon")
    k0 = np.array([inst.known(k) for k in knowns])
    n = np.array([scale_of(k, v, eps) for k, v in zip(knowns, k0)])
    f0 = inst.values(unknowns)
    D = np.column_stack([inst.directional(unknowns, [k], [1.0]) for k in knowns]) * n
    FD = np.zeros_like(D)
    for j, k in enumerate(knowns):
        h = 1e-5 * n[j]
        inst.set_known(k, k0[j] + h)
        fp = inst.values(unknowns)
        inst.set_known(k, k0[j] - h)
        fm = inst.values(unknowns)
        inst.set_known(k, k0[j])
        FD[:, j] = n[j] * (fp - fm) / (2 * h)
    assert np.array_equal(inst.values(unknowns), f0)
    # One seed with every known at once is the same linear combination.
    seed = np.linspace(1.0, 2.0, len(knowns))
    np.testing.assert_allclose(inst.directional(unknowns, knowns, seed), D @ (seed / n), rtol=1e-12,
                               atol=1e-12 * np.abs(D / n).max())
    return D, FD, f0


def assert_close(D, FD, f0, unknowns, knowns, where):
    """Each entry within REL_TOL of the difference, with a floor 1000 times the differences'
    round-off (about 1e-11 of the unknown's value, steps being 1e-5 of the known's scale)."""
    scale = np.maximum(np.abs(f0), np.abs(FD).max(axis=1))[:, None]
    bad = ~(np.abs(D - FD) <= REL_TOL * np.abs(FD) + 1e-8 * scale)
    wrong = [f"d {unknowns[i]}/d {knowns[j]}: {D[i, j]:.10g} vs {FD[i, j]:.10g}" for i, j in zip(*np.nonzero(bad))]
    assert not wrong, f"{where}: " + "; ".join(wrong)


# --------------------------------------------------------------- Continuous-Time Mode
@pytest.fixture(scope="module")
def continuous_time(loaded, structure):
    """Per mode of SMOOTH: (D, FD, values) of Outputs and Derivatives by the states."""
    unknowns = [u for u in real_unknowns(structure, "Outputs", "Derivatives") if u not in DISCRETE]
    out = {}
    for name, (start, expected) in SMOOTH.items():
        inst = Instance(loaded, start, initialization=False)
        assert inst.mode() == expected, name
        out[name] = jacobians(inst, unknowns, STATES)
        inst.free()
    return unknowns, out


@pytest.mark.parametrize("mode", SMOOTH)
def test_continuous_time_directional_derivatives_match_central_differences(continuous_time, mode):
    unknowns, results = continuous_time
    assert_close(*results[mode], unknowns, STATES, f"Continuous-Time Mode, {mode}")


def test_outputs_and_derivatives_declare_exactly_the_states_they_change_with(continuous_time, structure):
    unknowns, results = continuous_time
    changes = np.any([FD != 0 for _, FD, _ in results.values()], axis=0)
    wrong = []
    for i, u in enumerate(unknowns):
        declared = structure["Outputs"].get(u, set()) | structure["Derivatives"].get(u, set())
        assert declared <= set(STATES), f"{u}: Outputs and Derivatives depend on states only (no inputs here)"
        for j, k in enumerate(STATES):
            if (k in declared) != changes[i, j]:
                wrong.append(f"{u} on {k}: declared {k in declared}, changes {changes[i, j]}")
    assert not wrong, "; ".join(wrong)


def test_discrete_outputs_are_frozen_between_events_and_declare_no_dependency(loaded, structure):
    # FMI 2.0.4 §3.1: in Continuous-Time Mode relations are frozen; mode and contact change only
    # in Event Mode, by fmi2NewDiscreteStates, where the environment cannot set the states.
    # So they do not depend on the knowns of Outputs (the states): dependencies="".
    assert structure["Outputs"]["mode"] == set() and structure["Outputs"]["contact"] == set()
    for name, (start, expected) in SMOOTH.items():
        inst = Instance(loaded, start, initialization=False)
        x0 = np.array(inst.rod.get(*STATES))
        for j, k in enumerate(STATES):
            for value in x0[j] + np.array([-1.0, -1e-3, -1e-6, 1e-6, 1e-3, 1.0]):   # across every surface
                inst.set_known(k, value)
                assert inst.mode() == expected, f"{name}: {k} = {value} switched the mode between events"
            inst.set_known(k, x0[j])
        inst.free()


# --------------------------------------------------------------- Initialization Mode
INIT_KNOWNS = PARAMETERS + STATES


@pytest.mark.parametrize("mode", SMOOTH)
def test_initialization_directional_derivatives_match_central_differences(loaded, structure, mode):
    start, expected = SMOOTH[mode]
    unknowns = real_unknowns(structure, "InitialUnknowns")
    # Sticking needs v = 0 exactly: any step in v slips, so v's column of the stick branch is
    # measured in Continuous-Time Mode only (above), where the mode is frozen.
    knowns = [k for k in INIT_KNOWNS if not (mode == "stick" and k == "v")]
    inst = Instance(loaded, start, initialization=True)
    assert inst.mode() == expected
    D, FD, f0 = jacobians(inst, unknowns, knowns)
    assert inst.mode() == expected
    inst.free()
    assert_close(D, FD, f0, unknowns, knowns, f"Initialization Mode, {mode}")


def probe_values(name, value, epsilon):
    """Large perturbations of one known, across the switching surfaces near the states above."""
    if name in PARAMETERS:
        factors = dict(alpha=(0.5, 2, 3), epsilon=(0.3, 3, 10)).get(name, (0, 0.5, 2, 10))
        return [min(value * f, 1.0) if name == "epsilon" else value * f for f in factors]
    n = scale_of(name, value, epsilon)
    return [0.0, -value] + [value + n * d for d in (-3, -1, -0.3, 0.3, 1, 3)]


def test_initial_unknowns_declare_exactly_the_knowns_they_change_with(loaded, structure):
    declared = structure["InitialUnknowns"]
    unknowns = list(declared)
    reals = real_unknowns(structure, "InitialUnknowns")

    counters = [u for u in unknowns if u in NOT_REAL and u not in ("mode", "contact")]    # Integers

    def read(inst):
        contact, mode = inst.mode()
        counts = inst.rod.fmu.getInteger([inst.vr[n] for n in counters])
        return dict(zip(reals, inst.values(reals)), mode=mode, contact=contact, **dict(zip(counters, counts)))

    changes = {(u, k): False for u in unknowns for k in INIT_KNOWNS}
    # Smooth dependence: a nonzero central difference in some mode.
    for name, (start, _) in SMOOTH.items():
        inst = Instance(loaded, start, initialization=True)
        knowns = [k for k in INIT_KNOWNS if not (name == "stick" and k == "v")]
        _, FD, _ = jacobians(inst, reals, knowns)
        inst.free()
        for i, u in enumerate(reals):
            for j, k in enumerate(knowns):
                changes[u, k] |= bool(FD[i, j] != 0)
    # Any dependence, through the mode decision too: large perturbations, also near the surfaces.
    for start in [s for s, _ in SMOOTH.values()] + list(NEAR_SURFACES.values()):
        inst = Instance(loaded, start, initialization=True)
        base, eps = read(inst), inst.known("epsilon")
        for k in INIT_KNOWNS:
            k0 = inst.known(k)
            for value in probe_values(k, k0, eps):
                inst.set_known(k, value)
                now = read(inst)
                for u in unknowns:
                    changes[u, k] |= bool(now[u] != base[u])
            inst.set_known(k, k0)
            assert read(inst) == base
        inst.free()
    wrong = [f"{u} on {k}: declared {k in declared[u]}, changes {changes[u, k]}"
             for u in unknowns for k in INIT_KNOWNS if (k in declared[u]) != changes[u, k]]
    assert not wrong, "; ".join(wrong)


# --------------------------------------------------------------- what is refused
@pytest.mark.parametrize("unknown, known, initialization", [
    ("mode", "y", False), ("contact", "y", False), ("der(v)", "mode", False), ("der(v)", "contact", False),
    ("mode", "alpha", True), ("contact", "y", True), ("F_N", "contact", True),
    ("der(v)", "alpha", False),            # parameters are knowns in Initialization Mode only
    ("der(v)", "der(w)", False),           # a derivative is no known
])
def test_directional_derivative_of_or_by_a_non_known_is_an_error(loaded, unknown, known, initialization):
    # FMI 2.0 defines directional derivatives of Real unknowns by Real knowns (§2.1.9, §2.2.8).
    inst = Instance(loaded, SMOOTH["slip forward"][0], initialization)
    with pytest.raises(FMICallException) as err:
        inst.directional([unknown], [known], [1.0])
    assert err.value.status == FMI2_ERROR
    status, category, message = inst.rod.messages[-1]
    assert category == "logStatusError" and message.startswith("fmi2GetDirectionalDerivative: ")
    inst.free()


@pytest.mark.parametrize("unknown, known", [("der(v)", 999), (999, "y"), ("F_N", 10**6)])
def test_a_value_reference_the_model_does_not_have_is_an_error_naming_it(loaded, unknown, known):
    # Never another variable's derivative: an unknown value reference is refused, by number.
    inst = Instance(loaded, SMOOTH["slip forward"][0], False)
    vr = [inst.vr.get(unknown, unknown), inst.vr.get(known, known)]
    with pytest.raises(FMICallException) as err:
        inst.rod.fmu.getDirectionalDerivative([vr[0]], [vr[1]], [1.0])
    assert err.value.status == FMI2_ERROR
    status, category, message = inst.rod.messages[-1]
    bad = vr[0] if unknown not in inst.vr else vr[1]
    assert category == "logStatusError" and f"value reference {bad} is not" in message
    inst.free()
