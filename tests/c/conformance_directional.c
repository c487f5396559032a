/* SPDX-License-Identifier: BSD-2-Clause */
/* fmi2GetDirectionalDerivative for every (unknown, known) pair that FMI
 * 2.0.4 defines in each mode, from the <ModelStructure> of
 * modelDescription.xml (§2.1.9, §2.2.8):
 *   - InitializationMode: the Real <InitialUnknowns> by the inputs and the
 *     knowns with initial = "exact" (parameters, initial states);
 *   - Event and Continuous-Time Mode, Co-Simulation's communication points:
 *     Real <Outputs> and <Derivatives> by the inputs and continuous-time states.
 * Each such call must succeed, and where `dependencies` leaves the known out
 * the partial derivative is 0 exactly ("the Unknown depends on the Knowns
 * defined by the given indices"). The values are compared with central
 * differences of fmi2GetReal where the knowns can be set (InitializationMode:
 * fmi2SetReal; Continuous-Time Mode: fmi2SetContinuousStates for states,
 * fmi2SetReal for inputs): declared pairs must agree, undeclared ones must be
 * 0 by differences too (a dependency the XML misses). A call with several
 * unknowns and knowns must give J times the seed. Any other unknown (a state
 * in Continuous-Time Mode, an Integer or Boolean, a parameter) or known (a
 * parameter after initialization, a derivative) is an fmi2Error with a
 * message. The start point is the model's profile's (PROFILE_DD_START). A model whose description
 * says providesDirectionalDerivative="false" must answer every such call with fmi2Error. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "driver.h"

static const FmiApi *const f = &api;

/* Central differences (steps of 1e-4 of the known's size) and the analytic
 * partials agree to this: the change each makes in the unknown for a change
 * of its known by the known's size, relative to the largest such change of
 * the unknown's row (knowns of different units compare by what they do). */
#define DIFFERENCE_TOLERANCE 1e-6

/* A state inside one mode of the model, away from its switching surfaces
 * (the profile's). */
static const struct {
    fmi2ValueReference vr;
    double value;
} START[] = PROFILE_DD_START;
#define N_START (sizeof START / sizeof START[0])

static bool is_input(fmi2ValueReference vr)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (md_var(k)->vr == vr) return md_var(k)->causality == MD_INPUT;
    return false;
}

/* START's values of one kind: inputs (settable from Initialization Mode on,
 * FMI 2.0.4 §3.2.3 condition 3) or the others (before it: condition 1). */
static fmi2Status set_start(Inst *in, bool inputs)
{
    fmi2Status st = fmi2OK;
    for (size_t k = 0; k < N_START && st == fmi2OK; ++k)
        if (is_input(START[k].vr) == inputs) st = f->SetReal(in->c, &START[k].vr, 1, &START[k].value);
    return st;
}

/* A new instance in `state`, started from START. */
static bool reach(Inst *in, State state)
{
    const bool cs = state_is_cs(state);
    if (!inst_reach(in, cs ? CS_INSTANTIATED : ME_INSTANTIATED, false)) return false;
    fmi2Status st = set_start(in, false);
    if (st == fmi2OK) st = f->SetupExperiment(in->c, fmi2False, 0, 0, fmi2False, 0);
    if (st == fmi2OK) st = f->EnterInitializationMode(in->c);
    if (st == fmi2OK) st = set_start(in, true);
    if (state != ME_INIT && state != CS_INIT && st == fmi2OK) st = f->ExitInitializationMode(in->c);
    bool changed;
    if (state == ME_CONTINUOUS && st == fmi2OK) st = harness_event_iteration(f, in->c, &changed);
    if (state == CS_STEP_COMPLETE && st == fmi2OK) st = f->DoStep(in->c, 0, 1e-6, fmi2True);
    in->state = state;
    in->t = state == CS_STEP_COMPLETE ? 1e-6 : 0;
    if (!CHECK(st == fmi2OK, "reaching %s from the directional-derivative start: %s (%s)", STATE_NAME[state],
               status_name(st), harness.last_message)) {
        inst_free(in);
        return false;
    }
    return true;
}

static MdMode mode_of(State s)
{
    switch (s) {
    case ME_INIT: case CS_INIT: return MD_MODE_INIT;
    case ME_EVENT: case ME_EVENT_AGAIN: return MD_MODE_EVENT;
    case ME_CONTINUOUS: return MD_MODE_CONTINUOUS;
    default: return MD_MODE_STEP;
    }
}

static fmi2Status partial(Inst *in, int unknown, int known, double *d)
{
    const fmi2ValueReference u = md_var(unknown)->vr, k = md_var(known)->vr;
    const double seed = 1;
    *d = NAN;
    return f->GetDirectionalDerivative(in->c, &u, 1, &k, 1, &seed, d);
}

static double read_real(Inst *in, int index)
{
    const fmi2ValueReference vr = md_var(index)->vr;
    double v = NAN;
    CHECK(f->GetReal(in->c, &vr, 1, &v) == fmi2OK, "fmi2GetReal(%s): %s", md_var(index)->name, harness.last_message);
    return v;
}

/* Sets known `index` to `value` the way the mode allows: in Initialization
 * Mode and for inputs fmi2SetReal, states in Continuous-Time Mode
 * fmi2SetContinuousStates. */
static void set_known(Inst *in, int index, double value)
{
    const int position = md_state_position(index);
    if (mode_of(in->state) == MD_MODE_INIT || position < 0) {
        const fmi2ValueReference vr = md_var(index)->vr;
        CHECK(f->SetReal(in->c, &vr, 1, &value) == fmi2OK, "fmi2SetReal(%s = %g) in %s: %s", md_var(index)->name,
              value, STATE_NAME[in->state], harness.last_message);
        return;
    }
    double x[MODEL_NX];
    CHECK(f->GetContinuousStates(in->c, x, MODEL_NX) == fmi2OK, "fmi2GetContinuousStates");
    x[position] = value;
    CHECK(f->SetContinuousStates(in->c, x, MODEL_NX) == fmi2OK, "fmi2SetContinuousStates: %s", harness.last_message);
}

/* The value of known `index`: read where the mode allows (Continuous-Time
 * Mode), else (InitializationMode, where parameters cannot be read) the
 * value it was given: START's or modelDescription.xml's start. */
static double known_value(Inst *in, int index)
{
    if (mode_of(in->state) != MD_MODE_INIT) return read_real(in, index);
    for (size_t k = 0; k < N_START; ++k)
        if (START[k].vr == md_var(index)->vr) return START[k].value;
    return md_var(index)->start;
}

/* The size of known `index` at the instance's point: its value, or its
 * nominal where that is larger (a state at 0). */
static double known_size(Inst *in, int index, double nominal)
{
    return fmax(fabs(known_value(in, index)), nominal);
}

/* d unknown / d known by central differences of fmi2GetReal. */
static double central_difference(Inst *in, int unknown, int known, double nominal)
{
    const double x0 = known_value(in, known);
    /* Small against the distance to the mode's surfaces, large against rounding. */
    const double h = 1e-4 * known_size(in, known, nominal);
    set_known(in, known, x0 + h);
    const double plus = read_real(in, unknown);
    set_known(in, known, x0 - h);
    const double minus = read_real(in, unknown);
    set_known(in, known, x0);
    return (plus - minus) / (2 * h);
}

/* Every defined pair in `state`: status, structural zeros, differences, linearity. */
static void check_defined_pairs(State state)
{
    Inst in;
    if (!reach(&in, state)) return;
    const MdMode mode = mode_of(state);
    int unknowns[MAX_VARS], knowns[MAX_VARS], nu, nk;
    md_mode_sets(mode, MAX_VARS, unknowns, &nu, knowns, &nk);
    CHECK(nu > 0 && nk > 0, "%s: modelDescription.xml defines %d unknowns and %d knowns", STATE_NAME[state], nu, nk);
    static double J[MAX_VARS][MAX_VARS];
    double nominal[MODEL_NX];
    for (int i = 0; i < MODEL_NX; ++i) nominal[i] = 1;
    if (!state_is_cs(state)) CHECK(f->GetNominalsOfContinuousStates(in.c, nominal, MODEL_NX) == fmi2OK, "nominals");
    const bool differences = state == ME_INIT || state == ME_CONTINUOUS;
    for (int i = 0; i < nu; ++i) {
        const MdUnknown *u = md_unknown_of_mode(mode, unknowns[i]);
        const char *uname = md_var(unknowns[i])->name;
        /* The knowns have units of their own: each partial is weighed by its
         * known's size, the change it makes in the unknown. */
        double fd[MAX_VARS], size[MAX_VARS], scale = 1e-300;
        for (int j = 0; j < nk; ++j) {
            const char *kname = md_var(knowns[j])->name;
            const fmi2Status st = partial(&in, unknowns[i], knowns[j], &J[i][j]);
            if (!CHECK(st == fmi2OK, "fmi2GetDirectionalDerivative(%s by %s) in %s: %s, expected fmi2OK (%s)", uname,
                       kname, STATE_NAME[state], status_name(st), harness.last_error)) {
                inst_free(&in);
                if (!reach(&in, state)) return;
                J[i][j] = 0;
                fd[j] = 0;
                size[j] = 0;
                continue;
            }
            CHECK(isfinite(J[i][j]), "d %s / d %s = %g in %s", uname, kname, J[i][j], STATE_NAME[state]);
            if (!md_depends(u, knowns[j]))
                CHECK(J[i][j] == 0, "d %s / d %s = %g in %s, but modelDescription.xml declares no dependency", uname,
                      kname, J[i][j], STATE_NAME[state]);
            const int position = md_state_position(knowns[j]);
            const double nom = position >= 0 ? nominal[position] : 1e-6;
            fd[j] = differences ? central_difference(&in, unknowns[i], knowns[j], nom) : 0;
            size[j] = differences ? known_size(&in, knowns[j], nom) : 1;
            scale = fmax(scale, fmax(fabs(fd[j]), fabs(J[i][j])) * size[j]);
        }
        /* Declared pairs against the differences; undeclared ones, exactly 0 from
         * the FMU, must be 0 by differences too: else the XML misses a dependency. */
        for (int j = 0; differences && j < nk; ++j) {
            if (md_depends(u, knowns[j]))
                CHECK(fabs(J[i][j] - fd[j]) * size[j] <= DIFFERENCE_TOLERANCE * scale,
                      "d %s / d %s = %.10g in %s, central differences %.10g", uname, md_var(knowns[j])->name, J[i][j],
                      STATE_NAME[state], fd[j]);
            else
                CHECK(fabs(fd[j]) * size[j] <= DIFFERENCE_TOLERANCE * scale,
                      "d %s / d %s: modelDescription.xml declares no dependency, but central differences give %.10g "
                      "in %s (%s's size %.3g, the row's largest change %.3g)", uname, md_var(knowns[j])->name, fd[j],
                      STATE_NAME[state], md_var(knowns[j])->name, size[j], scale);
        }
    }
    /* All unknowns by all knowns at once: J times the seed (§2.1.9). */
    fmi2ValueReference uvr[MAX_VARS], kvr[MAX_VARS];
    double seed[MAX_VARS], out[MAX_VARS];
    for (int i = 0; i < nu; ++i) uvr[i] = md_var(unknowns[i])->vr;
    for (int j = 0; j < nk; ++j) {
        kvr[j] = md_var(knowns[j])->vr;
        seed[j] = (j % 3 - 1) * 0.5 + 0.125 * j;
    }
    const fmi2Status st = f->GetDirectionalDerivative(in.c, uvr, (size_t)nu, kvr, (size_t)nk, seed, out);
    CHECK(st == fmi2OK, "fmi2GetDirectionalDerivative(all %d unknowns by all %d knowns) in %s: %s (%s)", nu, nk,
          STATE_NAME[state], status_name(st), harness.last_error);
    if (st >= fmi2Error) in.state = state_is_cs(state) ? CS_ERROR : ME_ERROR;
    for (int i = 0; st == fmi2OK && i < nu; ++i) {
        double sum = 0, size = 0;
        for (int j = 0; j < nk; ++j) {
            sum += J[i][j] * seed[j];
            size += fabs(J[i][j] * seed[j]);
        }
        CHECK(fabs(out[i] - sum) <= 1e-12 * size, "%s: J times the seed gives %.17g for %s, the columns %.17g",
              STATE_NAME[state], out[i], md_var(unknowns[i])->name, sum);
    }
    inst_works(&in, "directional derivatives");
    inst_free(&in);
}

/* A pair outside the mode's sets: fmi2Error with a message, and the Error state. */
static void check_undefined_pair(State state, int unknown, int known)
{
    Inst in;
    if (!reach(&in, state)) return;
    char what[200];
    snprintf(what, sizeof what, "fmi2GetDirectionalDerivative(%s by %s) in %s", md_var(unknown)->name,
             md_var(known)->name, STATE_NAME[state]);
    const long errors_before = harness.error_messages;
    double d;
    const fmi2Status st = partial(&in, unknown, known, &d);
    CHECK(st == fmi2Error, "%s: %s, expected fmi2Error: the pair is not defined there", what, status_name(st));
    if (st == fmi2Error) {
        check_error_reported(what, "fmi2GetDirectionalDerivative", errors_before);
        in.state = state_is_cs(state) ? CS_ERROR : ME_ERROR;
    }
    inst_works(&in, what);
    inst_free(&in);
}

void test_directional_derivatives(void)
{
    static const State STATES[] = { ME_INIT, ME_EVENT, ME_CONTINUOUS, CS_INIT, CS_STEP_COMPLETE };
    for (size_t s = 0; s < sizeof STATES / sizeof STATES[0]; ++s) {
        const State state = STATES[s];
        const MdMode mode = mode_of(state);
        int unknowns[MAX_VARS], knowns[MAX_VARS], nu, nk;
        md_mode_sets(mode, MAX_VARS, unknowns, &nu, knowns, &nk);
        /* A model that provides none (its capability flag false): even a defined pair is an error. */
        if (!MD_PROVIDES_DIRECTIONAL_DERIVATIVE) {
            if (nu > 0 && nk > 0) check_undefined_pair(state, unknowns[0], knowns[0]);
            continue;
        }
        check_defined_pairs(state);
        if (nu == 0 || nk == 0) continue;
        /* Each variable as the unknown by a known of the mode, and as the known for an unknown of it. */
        for (int k = 1; k <= MD_N_VARIABLES; ++k) {
            if (!md_unknown_of_mode(mode, k)) check_undefined_pair(state, k, knowns[0]);
            if (!md_known_of_mode(mode, k)) check_undefined_pair(state, unknowns[0], k);
        }
    }
}
