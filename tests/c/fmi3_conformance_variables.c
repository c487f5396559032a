/* SPDX-License-Identifier: BSD-2-Clause */
/* The FMI 3.0 getters and setters, variable by variable from the FMI 3.0
 * modelDescription.xml, in every state of both state machines against the
 * "Allowed Function Calls" of FMI 3.0 (a part of the conformance table,
 * fmi3_conformance.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conformance3.h"

static const Fmi3Api *const f = &api3;

static bool instantiated(State3 s) { return s == M3_INSTANTIATED || s == C3_INSTANTIATED; }

/* fmi3Get{VariableType} of any variable, wherever the getters are allowed:
 * in Initialization Mode too, "For variables not computed by f_init their
 * start values will be returned" (§2.3.3). */
static bool get_allowed(State3 s) { return !instantiated(s); }

/* fmi3Set{VariableType} of variable `index` in state s. */
static bool set_allowed(State3 s, int index)
{
    const MdVariable *v = md_var(index);
    const bool not_constant = v->variability != MD_CONSTANT, input = v->causality == MD_INPUT;
    const bool tunable_parameter = v->causality == MD_PARAMETER && v->variability == MD_TUNABLE;
    switch (s) {
    case M3_INSTANTIATED: case C3_INSTANTIATED: /* §2.3.2: inputs too, unlike FMI 2.0.4 */
        return (not_constant && (v->initial == MD_INITIAL_EXACT || v->initial == MD_INITIAL_APPROX)) || input;
    case M3_INIT: case C3_INIT: /* §2.3.3 */
        return (not_constant && v->initial == MD_INITIAL_EXACT) || input;
    case M3_EVENT: case M3_EVENT_AGAIN: case C3_EVENT: case C3_EVENT_AGAIN: case C3_STEP: case C3_STEP_EM:
        return input || tunable_parameter; /* §2.3.5 (FMI 3.0; 3.0.2 adds states with reinit = false), §4.2.1 */
    case M3_CONTINUOUS: /* §3.2.1 */
        return (input && v->variability == MD_CONTINUOUS) || v->state;
    default: return false; /* Terminated */
    }
}

static fmi3Status get_var(Inst3 *in, int index, double *value)
{
    const MdVariable *v = md_var(index);
    const fmi3ValueReference vr = v->vr;
    fmi3Status st;
    *value = NAN;
    switch (v->type) {
    case MD_REAL: st = f->GetFloat64(in->c, &vr, 1, value, 1); break;
    case MD_BOOLEAN: {
        fmi3Boolean b = 7;
        st = f->GetBoolean(in->c, &vr, 1, &b, 1);
        if (st == fmi3OK) CHECK(b == fmi3True || b == fmi3False, "%s = %d", v->name, b);
        *value = b;
        break;
    }
    default: {
        fmi3Int32 i = 0;
        st = f->GetInt32(in->c, &vr, 1, &i, 1);
        *value = i;
    }
    }
    if (st == fmi3OK) CHECK(isfinite(*value), "%s = %g", v->name, *value);
    return st;
}

static fmi3Status set_var(Inst3 *in, int index, double value)
{
    const MdVariable *v = md_var(index);
    const fmi3ValueReference vr = v->vr;
    switch (v->type) {
    case MD_REAL: return f->SetFloat64(in->c, &vr, 1, &value, 1);
    case MD_BOOLEAN: {
        const fmi3Boolean b = value != 0;
        return f->SetBoolean(in->c, &vr, 1, &b, 1);
    }
    default: {
        const fmi3Int32 i = (fmi3Int32)value;
        return f->SetInt32(in->c, &vr, 1, &i, 1);
    }
    }
}

static const char *const GETTER[] = { "fmi3GetFloat64", "fmi3GetInt32", "fmi3GetBoolean" };
static const char *const SETTER[] = { "fmi3SetFloat64", "fmi3SetInt32", "fmi3SetBoolean" };

void test3_conformance_variables(void)
{
    for (int s = 0; s < N3_STATES; ++s) {
        for (int index = 1; index <= MD_N_VARIABLES; ++index) {
            const MdVariable *v = md_var(index);
            if (!CHECK(v->type <= MD_BOOLEAN, "%s: a type the driver does not handle", v->name)) continue;
            char what[200];
            Inst3 in;
            double value;
            if (inst3_reach(&in, (State3)s, true)) {
                snprintf(what, sizeof what, "%s(%s) in %s", GETTER[v->type], v->name, STATE3_NAME[s]);
                const long errors_before = harness.error_messages;
                const fmi3Status st = get_var(&in, index, &value);
                check_call(&in, GETTER[v->type], what, st, get_allowed((State3)s), fmi3OK, SAME, errors_before);
                inst3_free(&in);
            }
            if (inst3_reach(&in, (State3)s, true)) {
                /* A legal value: the one it has, where it can be read, else its start value. */
                const bool readable = get_allowed((State3)s);
                if (!(readable && get_var(&in, index, &value) == fmi3OK)) value = v->has_start ? v->start : 0;
                snprintf(what, sizeof what, "%s(%s = %g) in %s", SETTER[v->type], v->name, value, STATE3_NAME[s]);
                const long errors_before = harness.error_messages;
                const fmi3Status st = set_var(&in, index, value);
                double again;
                if (st == fmi3OK && readable)
                    CHECK(get_var(&in, index, &again) == fmi3OK && again == value, "%s: reads back %g", what, again);
                check_call(&in, SETTER[v->type], what, st, set_allowed((State3)s, index), fmi3OK, SAME,
                           errors_before);
                inst3_free(&in);
            }
        }
    }
}
