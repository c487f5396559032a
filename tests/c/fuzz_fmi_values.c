/* SPDX-License-Identifier: BSD-2-Clause */
/* fuzz_fmi's calls on values: fmi2Get and fmi2Set of every type, the arrays of
 * Model Exchange (states, derivatives, event indicators, nominals), directional derivatives. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_fmi.h"

static const FmiApi *const f = &api;

/* The arguments of a fmi2Get/fmi2Set call, read from the input: a count (or NULL arrays),
 * CAP value references and, for a Set, CAP values of each type. */
typedef struct {
    fmi2ValueReference vr[CAP];
    double r[CAP];
    fmi2Integer iv[CAP];
    fmi2Boolean bv[CAP];
    fmi2String sv[CAP];
    bool null_arrays;
    size_t n;
} ValueArgs;

static void take_value_args(ValueArgs *a, bool values)
{
    memset(a, 0, sizeof *a);
    a->n = take_count(&fuzz_input, &a->null_arrays);
    for (size_t k = 0; k < CAP; ++k) {
        a->vr[k] = take_vr(&fuzz_input);
        if (!values) continue;
        a->r[k] = take_double(&fuzz_input);
        a->iv[k] = (int8_t)take(&fuzz_input);
        a->bv[k] = a->iv[k] & 1;
        a->sv[k] = a->iv[k] & 2 ? "%s" : NULL;
    }
}

/* Whether an Integer value lies within its variable's min and max (modelDescription.xml). */
static bool within_bounds(fmi2ValueReference vr, fmi2Integer value)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k) {
        const MdVariable *v = md_var(k);
        if (v->vr != vr || v->type != MD_INTEGER) continue;
        return (!v->has_min || value >= v->min) && (!v->has_max || value <= v->max);
    }
    return false;
}

void op_get(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    ValueArgs a;
    take_value_args(&a, false);
    const bool null_arrays = a.null_arrays;
    const size_t n = a.n;
    const fmi2ValueReference *v = null_arrays ? NULL : a.vr;
    fmi2Component c = s->sim.c;
    switch (which % 4) {
    case 0:
        if (CALL(s, true, f->GetReal(c, v, n, null_arrays ? NULL : a.r)) == fmi2OK && !null_arrays)
            require_finite("fmi2GetReal", a.r, n);
        break;
    case 1:
        if (CALL(s, true, f->GetInteger(c, v, n, null_arrays ? NULL : a.iv)) == fmi2OK && !null_arrays)
            for (size_t k = 0; k < n; ++k)   /* within the min and max of modelDescription.xml */
                INVARIANT(within_bounds(a.vr[k], a.iv[k]), "Integer %u = %d", a.vr[k], a.iv[k]);
        break;
    case 2:
        if (CALL(s, true, f->GetBoolean(c, v, n, null_arrays ? NULL : a.bv)) == fmi2OK && !null_arrays)
            for (size_t k = 0; k < n; ++k) INVARIANT(a.bv[k] == 0 || a.bv[k] == 1, "contact = %d", a.bv[k]);
        break;
    default:
        CALL(s, true, f->GetString(c, v, n, null_arrays ? NULL : a.sv));
    }
}

void op_set(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    ValueArgs a;
    take_value_args(&a, true);
    const bool null_arrays = a.null_arrays;
    const size_t n = a.n;
    const fmi2ValueReference *v = null_arrays ? NULL : a.vr;
    fmi2Component c = s->sim.c;
    switch (which % 4) {
    case 0: CALL(s, false, f->SetReal(c, v, n, null_arrays ? NULL : a.r)); break;
    case 1: CALL(s, false, f->SetInteger(c, v, n, null_arrays ? NULL : a.iv)); break;
    case 2: CALL(s, false, f->SetBoolean(c, v, n, null_arrays ? NULL : a.bv)); break;
    default: CALL(s, false, f->SetString(c, v, n, null_arrays ? NULL : a.sv));
    }
}

/* fmi2GetDerivatives, GetEventIndicators, GetContinuousStates, GetNominals,
 * SetContinuousStates, with right, wrong and huge sizes. */
void op_arrays(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    double v[CAP];
    bool null_arrays;
    const uint8_t size_sel = take(&fuzz_input);
    size_t n = size_sel < 200 ? (which % 5 == 1 ? MODEL_NZ : MODEL_NX) : take_count(&fuzz_input, &null_arrays);
    null_arrays = n > CAP || size_sel == 255;
    for (size_t k = 0; k < CAP; ++k) v[k] = take_double(&fuzz_input);
    double *a = null_arrays ? NULL : v;
    fmi2Component c = s->sim.c;
    fmi2Status st;
    switch (which % 5) {
    case 0: st = CALL(s, true, f->GetDerivatives(c, a, n)); break;
    case 1: st = CALL(s, true, f->GetEventIndicators(c, a, n)); break;
    case 2: st = CALL(s, true, f->GetContinuousStates(c, a, n)); break;
    case 3: st = CALL(s, true, f->GetNominalsOfContinuousStates(c, a, n)); break;
    default: CALL(s, false, f->SetContinuousStates(c, a, n)); return;
    }
    if (st == fmi2OK && a) require_finite("array getter", a, n);
}

/* A value reference for a directional derivative, from modelDescription.xml:
 * mostly an unknown (an output, a derivative, an initial unknown) or a known
 * (a state, a variable with initial = "exact") that some mode defines, often
 * a pair that the current mode does not, sometimes an Integer or Boolean
 * variable, sometimes far out. */
static fmi2ValueReference take_dd_vr(Bytes *b, bool unknown)
{
    const uint8_t sel = take(b);
    if (sel >= 224) return take_vr(b);
    int candidates[64], n = 0;
    for (int index = 1; index <= MD_N_VARIABLES && n < 64; ++index) {
        bool defined = false;
        for (int mode = MD_MODE_INIT; mode <= MD_MODE_STEP; ++mode)
            defined |= unknown ? md_unknown_of_mode((MdMode)mode, index) != NULL : md_known_of_mode((MdMode)mode, index);
        if (defined || sel >= 160) candidates[n++] = index;
    }
    return n ? md_var(candidates[sel % n])->vr : take_vr(b);
}

void op_directional_derivative(Slot *s)
{
    const long errors_before = harness.error_messages;
    fmi2ValueReference unknown[CAP], known[CAP];
    double dv_known[CAP], dv_unknown[CAP];
    bool null_u, null_k;
    const size_t nu = take_count(&fuzz_input, &null_u), nk = take_count(&fuzz_input, &null_k);
    for (size_t k = 0; k < CAP; ++k) {
        unknown[k] = take_dd_vr(&fuzz_input, true);
        known[k] = take_dd_vr(&fuzz_input, false);
        dv_known[k] = take_double(&fuzz_input);
    }
    /* Allowed in the Error state ("7" in both tables). */
    const fmi2Status st = CALL(s, true,
                               f->GetDirectionalDerivative(s->sim.c, null_u ? NULL : unknown, nu, null_k ? NULL : known,
                                                           nk, null_k ? NULL : dv_known, null_u ? NULL : dv_unknown));
    (void)st; /* the product of finite Jacobian entries and any seed may be anything */
}
