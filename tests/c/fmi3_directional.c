/* SPDX-License-Identifier: BSD-2-Clause */
/* fmi3GetDirectionalDerivative and fmi3GetAdjointDerivative for every
 * (unknown, known) pair that FMI 3.0 defines in each state, from the
 * <ModelStructure> of the FMI 3.0 modelDescription.xml (§2.2.11 "Getting
 * Partial Derivatives"; the pairs are FMI 2.0's, model_structure.h):
 *   - Initialization Mode: the Float64 <InitialUnknown>s by the knowns with
 *     initial = "exact" (parameters, initial states);
 *   - Event and Continuous-Time Mode, Step Mode: Float64 <Output>s and
 *     <ContinuousStateDerivative>s by the inputs and continuous-time states;
 *   - "EventIndicators must not be included among v_unknown".
 * Each such call must succeed; where `dependencies` leaves the known out the
 * partial is 0 exactly; the directional derivative equals central differences
 * of fmi3GetFloat64 where the knowns can be set (Initialization Mode:
 * fmi3SetFloat64; Continuous-Time Mode: fmi3SetContinuousStates, inputs by
 * fmi3SetFloat64); the start point is the model's profile's; the adjoint
 * of a pair equals its directional derivative, and with many unknowns and
 * knowns the two give J v and v^T J. Any other pair is an fmi3Error with a
 * message, from either function. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "driver3.h"

static const Fmi3Api *const f = &api3;

/* A point inside one mode of the model, away from its switching surfaces, so
 * that central differences stay in it (the profile's; inputs among it are set
 * before initialization too, which FMI 3.0 allows). */
static const struct {
    fmi3ValueReference vr;
    double value;
} START[] = PROFILE_DD_START;

static bool reach(Inst3 *in, State3 state)
{
    if (!inst3_reach(in, state3_is_cs(state) ? C3_INSTANTIATED : M3_INSTANTIATED, false)) return false;
    fmi3Status st = fmi3OK;
    for (size_t k = 0; k < sizeof START / sizeof START[0] && st == fmi3OK; ++k)
        st = f->SetFloat64(in->c, &START[k].vr, 1, &START[k].value, 1);
    if (st == fmi3OK) st = f->EnterInitializationMode(in->c, fmi3False, 0, 0, fmi3False, 0);
    if (state != M3_INIT && state != C3_INIT && st == fmi3OK) st = f->ExitInitializationMode(in->c);
    bool changed;
    if (state == M3_CONTINUOUS && st == fmi3OK) st = harness3_update_discrete_states(f, in->c, &changed);
    if (state == M3_CONTINUOUS && st == fmi3OK) st = f->EnterContinuousTimeMode(in->c);
    in->t = 0;
    if (state == C3_STEP && st == fmi3OK) st = harness3_do_step(f, in->c, &in->t, 1e-6, NULL);
    in->state = state;
    if (!CHECK(st == fmi3OK, "reaching %s from the derivatives' start: %s (%s)", STATE3_NAME[state],
               status3_name(st), harness.last_message)) {
        inst3_free(in);
        return false;
    }
    return true;
}

static MdMode mode_of(State3 s)
{
    switch (s) {
    case M3_INIT: case C3_INIT: return MD_MODE_INIT;
    case M3_EVENT: return MD_MODE_EVENT;
    case M3_CONTINUOUS: return MD_MODE_CONTINUOUS;
    default: return MD_MODE_STEP;
    }
}

static fmi3Status partial(Inst3 *in, int unknown, int known, bool adjoint, double *d)
{
    const fmi3ValueReference u = md_var(unknown)->vr, k = md_var(known)->vr;
    const double seed = 1;
    *d = NAN;
    return adjoint ? f->GetAdjointDerivative(in->c, &u, 1, &k, 1, &seed, 1, d, 1)
                   : f->GetDirectionalDerivative(in->c, &u, 1, &k, 1, &seed, 1, d, 1);
}

static double read_float(Inst3 *in, int index)
{
    const fmi3ValueReference vr = md_var(index)->vr;
    double v = NAN;
    CHECK(f->GetFloat64(in->c, &vr, 1, &v, 1) == fmi3OK, "fmi3GetFloat64(%s): %s", md_var(index)->name,
          harness.last_message);
    return v;
}

/* Known `index` set the way the mode allows: in Initialization Mode and for
 * inputs fmi3SetFloat64, states in Continuous-Time Mode fmi3SetContinuousStates. */
static void set_known(Inst3 *in, int index, double value)
{
    const int position = md_state_position(index);
    if (mode_of(in->state) == MD_MODE_INIT || position < 0) {
        const fmi3ValueReference vr = md_var(index)->vr;
        CHECK(f->SetFloat64(in->c, &vr, 1, &value, 1) == fmi3OK, "fmi3SetFloat64(%s = %g): %s", md_var(index)->name,
              value, harness.last_message);
        return;
    }
    double x[MODEL_NX];
    CHECK(f->GetContinuousStates(in->c, x, MODEL_NX) == fmi3OK, "fmi3GetContinuousStates");
    x[position] = value;
    CHECK(f->SetContinuousStates(in->c, x, MODEL_NX) == fmi3OK, "fmi3SetContinuousStates: %s", harness.last_message);
}

/* d unknown / d known by central differences of fmi3GetFloat64 (FMI 3.0
 * lets every variable be read in Initialization Mode, the knowns too). */
static double central_difference(Inst3 *in, int unknown, int known, double nominal)
{
    const double x0 = read_float(in, known);
    const double h = 1e-4 * fmax(fabs(x0), nominal);
    set_known(in, known, x0 + h);
    const double plus = read_float(in, unknown);
    set_known(in, known, x0 - h);
    const double minus = read_float(in, unknown);
    set_known(in, known, x0);
    return (plus - minus) / (2 * h);
}

static void check_defined_pairs(State3 state)
{
    Inst3 in;
    if (!reach(&in, state)) return;
    const MdMode mode = mode_of(state);
    int unknowns[MAX_VARS], knowns[MAX_VARS], nu, nk;
    md_mode_sets(mode, MAX_VARS, unknowns, &nu, knowns, &nk);
    CHECK(nu > 0 && nk > 0, "%s: modelDescription.xml defines %d unknowns and %d knowns", STATE3_NAME[state], nu, nk);
    static double J[MAX_VARS][MAX_VARS];
    double nominal[MODEL_NX];
    for (int i = 0; i < MODEL_NX; ++i) nominal[i] = 1;
    if (!state3_is_cs(state))
        CHECK(f->GetNominalsOfContinuousStates(in.c, nominal, MODEL_NX) == fmi3OK, "nominals: %s", harness.last_error);
    const bool differences = state == M3_INIT || state == M3_CONTINUOUS;
    for (int i = 0; i < nu; ++i) {
        const MdUnknown *u = md_unknown_of_mode(mode, unknowns[i]);
        const char *uname = md_var(unknowns[i])->name;
        double fd[MAX_VARS], scale = 1e-300;
        for (int j = 0; j < nk; ++j) {
            const char *kname = md_var(knowns[j])->name;
            double adj = NAN;
            const fmi3Status st = partial(&in, unknowns[i], knowns[j], false, &J[i][j]);
            const fmi3Status sa = st == fmi3OK ? partial(&in, unknowns[i], knowns[j], true, &adj) : st;
            if (!CHECK(st == fmi3OK && sa == fmi3OK, "d %s / d %s in %s: directional %s, adjoint %s (%s)", uname,
                       kname, STATE3_NAME[state], status3_name(st), status3_name(sa), harness.last_error)) {
                inst3_free(&in);
                if (!reach(&in, state)) return;
                J[i][j] = fd[j] = 0;
                continue;
            }
            CHECK(isfinite(J[i][j]), "d %s / d %s = %g in %s", uname, kname, J[i][j], STATE3_NAME[state]);
            CHECK(adj == J[i][j], "d %s / d %s in %s: adjoint %.17g, directional %.17g", uname, kname,
                  STATE3_NAME[state], adj, J[i][j]);
            if (!md_depends(u, knowns[j]))
                CHECK(J[i][j] == 0, "d %s / d %s = %g in %s, but modelDescription.xml declares no dependency", uname,
                      kname, J[i][j], STATE3_NAME[state]);
            const int position = md_state_position(knowns[j]);
            const double nom = position >= 0 ? nominal[position] : 1e-6;
            fd[j] = differences ? central_difference(&in, unknowns[i], knowns[j], nom) : 0;
            scale = fmax(scale, fmax(fabs(fd[j]), fabs(J[i][j])));
        }
        for (int j = 0; differences && j < nk; ++j)
            CHECK(fabs(J[i][j] - fd[j]) <= 1e-5 * scale, "d %s / d %s = %.10g in %s, central differences %.10g",
                  uname, md_var(knowns[j])->name, J[i][j], STATE3_NAME[state], fd[j]);
    }
    /* All unknowns by all knowns at once: J v and w^T J. */
    fmi3ValueReference uvr[MAX_VARS], kvr[MAX_VARS];
    double seed_k[MAX_VARS], seed_u[MAX_VARS], out_u[MAX_VARS], out_k[MAX_VARS];
    for (int i = 0; i < nu; ++i) {
        uvr[i] = md_var(unknowns[i])->vr;
        seed_u[i] = 0.25 * (i % 4) - 0.3;
    }
    for (int j = 0; j < nk; ++j) {
        kvr[j] = md_var(knowns[j])->vr;
        seed_k[j] = (j % 3 - 1) * 0.5 + 0.125 * j;
    }
    fmi3Status st = f->GetDirectionalDerivative(in.c, uvr, (size_t)nu, kvr, (size_t)nk, seed_k, (size_t)nk, out_u,
                                                (size_t)nu);
    if (st == fmi3OK)
        st = f->GetAdjointDerivative(in.c, uvr, (size_t)nu, kvr, (size_t)nk, seed_u, (size_t)nu, out_k, (size_t)nk);
    CHECK(st == fmi3OK, "directional and adjoint derivatives of all %d unknowns by all %d knowns in %s: %s (%s)", nu,
          nk, STATE3_NAME[state], status3_name(st), harness.last_error);
    if (st >= fmi3Error) in.state = state3_is_cs(state) ? C3_ERROR : M3_ERROR;
    for (int i = 0; st == fmi3OK && i < nu; ++i) {
        double sum = 0, size = 0;
        for (int j = 0; j < nk; ++j) {
            sum += J[i][j] * seed_k[j];
            size += fabs(J[i][j] * seed_k[j]);
        }
        CHECK(fabs(out_u[i] - sum) <= 1e-12 * size, "%s: J v gives %.17g for %s, the columns %.17g",
              STATE3_NAME[state], out_u[i], md_var(unknowns[i])->name, sum);
    }
    for (int j = 0; st == fmi3OK && j < nk; ++j) {
        double sum = 0, size = 0;
        for (int i = 0; i < nu; ++i) {
            sum += seed_u[i] * J[i][j];
            size += fabs(seed_u[i] * J[i][j]);
        }
        CHECK(fabs(out_k[j] - sum) <= 1e-12 * size, "%s: w^T J gives %.17g for %s, the rows %.17g",
              STATE3_NAME[state], out_k[j], md_var(knowns[j])->name, sum);
    }
    inst3_works(&in, "directional and adjoint derivatives");
    inst3_free(&in);
}

static void check_undefined_pair(State3 state, int unknown, int known, bool adjoint)
{
    Inst3 in;
    if (!reach(&in, state)) return;
    const char *call = adjoint ? "fmi3GetAdjointDerivative" : "fmi3GetDirectionalDerivative";
    char what[200];
    snprintf(what, sizeof what, "%s(%s by %s) in %s", call, md_var(unknown)->name, md_var(known)->name,
             STATE3_NAME[state]);
    const long errors_before = harness.error_messages;
    double d;
    const fmi3Status st = partial(&in, unknown, known, adjoint, &d);
    CHECK(st == fmi3Error, "%s: %s, expected fmi3Error: the pair is not defined there", what, status3_name(st));
    if (st == fmi3Error) {
        check3_error_reported(what, call, errors_before);
        in.state = state3_is_cs(state) ? C3_ERROR : M3_ERROR;
    }
    inst3_works(&in, what);
    inst3_free(&in);
}

void test3_derivatives(void)
{
    static const State3 STATES[] = { M3_INIT, M3_EVENT, M3_CONTINUOUS, C3_INIT, C3_STEP };
    for (size_t s = 0; s < sizeof STATES / sizeof STATES[0]; ++s) {
        const State3 state = STATES[s];
        const MdMode mode = mode_of(state);
        int unknowns[MAX_VARS], knowns[MAX_VARS], nu, nk;
        md_mode_sets(mode, MAX_VARS, unknowns, &nu, knowns, &nk);
        /* A model that provides none (providesDirectionalDerivatives="false"): even a defined pair is an
         * error, directional and adjoint. */
        if (!MD_PROVIDES_DIRECTIONAL_DERIVATIVE) {
            for (int adjoint = 0; adjoint <= 1 && nu > 0 && nk > 0; ++adjoint)
                check_undefined_pair(state, unknowns[0], knowns[0], adjoint);
            continue;
        }
        check_defined_pairs(state);
        if (nu == 0 || nk == 0) continue;
        /* Each variable (event indicators and time included) as the unknown by a
         * known of the mode, and as the known for an unknown of it. */
        for (int k = 1; k <= MD_N_VARIABLES; ++k) {
            for (int adjoint = 0; adjoint < 2; ++adjoint) {
                if (!md_unknown_of_mode(mode, k)) check_undefined_pair(state, k, knowns[0], adjoint);
                if (!md_known_of_mode(mode, k)) check_undefined_pair(state, unknowns[0], k, adjoint);
            }
        }
    }
}
