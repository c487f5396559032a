/* SPDX-License-Identifier: BSD-2-Clause */
/* The calls that read or set variables, variable by variable from
 * modelDescription.xml, in every state of both state machines against the
 * numbered conditions of the tables of FMI 2.0.4 §3.2.3 and §4.2.4 (a part of
 * the conformance table, conformance_table.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conformance.h"

static const FmiApi *const f = &api;

static bool instantiated(State s) { return s == ME_INSTANTIATED || s == CS_INSTANTIATED; }

/* fmi2GetXXX of variable `index` in state s: not in Instantiated; in
 * InitializationMode "2": outputs and <InitialUnknowns>; elsewhere "x" or "7". */
static bool get_allowed(State s, int index)
{
    (void)index;
    /* In Initialization Mode condition 2 asks for outputs and InitialUnknowns only;
     * the FMUs also answer the parameters and states an importer has just set
     * (tools read them back), which the standard does not forbid an FMU to do. */
    return !instantiated(s);
}

/* fmi2SetXXX of variable `index` in state s, by the numbered conditions. */
static bool set_allowed(State s, int index)
{
    const MdVariable *v = md_var(index);
    const bool not_constant = v->variability != MD_CONSTANT;
    const bool input = v->causality == MD_INPUT;
    const bool tunable_parameter = v->causality == MD_PARAMETER && v->variability == MD_TUNABLE;
    switch (s) {
    case ME_INSTANTIATED: case CS_INSTANTIATED: /* 1, and a deliberate leniency for inputs */
        /* Condition 1 leaves inputs out (they have no initial; FMI 2.0.1 made it
         * explicit, fmi-standard #440), but fmpy sets them there (its
         * settable_in_instantiated, for start_values), as fmusim did
         * (Reference-FMUs #511), and FMI 3.0 allows it: the FMUs accept an input
         * before initialization and use it (input_checks.c). */
        return (not_constant && (v->initial == MD_INITIAL_EXACT || v->initial == MD_INITIAL_APPROX)) || input;
    case ME_INIT: case CS_INIT: /* 3 */
        return (not_constant && v->initial == MD_INITIAL_EXACT) || input;
    case ME_EVENT: case ME_EVENT_AGAIN: case CS_STEP_COMPLETE: /* 4, 6 */
        return input || tunable_parameter;
    case ME_CONTINUOUS: /* 5: fmi2SetReal only */
        return v->type == MD_REAL && ((input && v->variability == MD_CONTINUOUS) || v->state);
    default: return false; /* Terminated, Error */
    }
}

/* Reads variable `index` as its type; the value as a double. */
static fmi2Status get_var(Inst *in, int index, double *value)
{
    const MdVariable *v = md_var(index);
    const fmi2ValueReference vr = v->vr;
    fmi2Status st;
    *value = NAN;
    switch (v->type) {
    case MD_REAL: st = f->GetReal(in->c, &vr, 1, value); break;
    case MD_BOOLEAN: {
        fmi2Boolean b = 7;
        st = f->GetBoolean(in->c, &vr, 1, &b);
        if (st == fmi2OK) CHECK(b == fmi2True || b == fmi2False, "%s = %d", v->name, b);
        *value = b;
        break;
    }
    case MD_STRING: {
        fmi2String str = NULL;
        st = f->GetString(in->c, &vr, 1, &str);
        if (st == fmi2OK) CHECK(str != NULL, "%s is NULL", v->name);
        *value = 0;
        break;
    }
    default: {
        fmi2Integer i = 0;
        st = f->GetInteger(in->c, &vr, 1, &i);
        *value = i;
    }
    }
    if (st == fmi2OK) CHECK(isfinite(*value), "%s = %g", v->name, *value);
    return st;
}

static fmi2Status set_var(Inst *in, int index, double value)
{
    const MdVariable *v = md_var(index);
    const fmi2ValueReference vr = v->vr;
    switch (v->type) {
    case MD_REAL: return f->SetReal(in->c, &vr, 1, &value);
    case MD_BOOLEAN: {
        const fmi2Boolean b = value != 0;
        return f->SetBoolean(in->c, &vr, 1, &b);
    }
    case MD_STRING: {
        const fmi2String str = "";
        return f->SetString(in->c, &vr, 1, &str);
    }
    default: {
        const fmi2Integer i = (fmi2Integer)value;
        return f->SetInteger(in->c, &vr, 1, &i);
    }
    }
}

static const char *const GETTER[] = { "fmi2GetReal", "fmi2GetInteger", "fmi2GetBoolean", "fmi2GetString",
                                      "fmi2GetInteger" };
static const char *const SETTER[] = { "fmi2SetReal", "fmi2SetInteger", "fmi2SetBoolean", "fmi2SetString",
                                      "fmi2SetInteger" };

void test_conformance_variables(void)
{
    for (int s = 0; s < N_STATES; ++s) {
        for (int index = 1; index <= MD_N_VARIABLES; ++index) {
            const MdVariable *v = md_var(index);
            char what[200];
            Inst in;
            double value;

            if (inst_reach(&in, (State)s, true)) {
                snprintf(what, sizeof what, "%s(%s) in %s", GETTER[v->type], v->name, STATE_NAME[s]);
                const long errors_before = harness.error_messages, messages_before = harness.messages;
                const fmi2Status st = get_var(&in, index, &value);
                check_call(&in, GETTER[v->type], what, st, get_allowed((State)s, index), fmi2OK, SAME,
                           errors_before, messages_before);
                inst_free(&in);
            }

            if (inst_reach(&in, (State)s, true)) {
                /* A legal value: the one it has, where it can be read, else its start value. */
                const bool readable = get_allowed((State)s, index);
                if (!(readable && get_var(&in, index, &value) == fmi2OK)) value = v->has_start ? v->start : 0;
                snprintf(what, sizeof what, "%s(%s = %g) in %s", SETTER[v->type], v->name, value, STATE_NAME[s]);
                const long errors_before = harness.error_messages, messages_before = harness.messages;
                const fmi2Status st = set_var(&in, index, value);
                double again;
                if (st == fmi2OK && readable && v->type != MD_STRING)
                    CHECK(get_var(&in, index, &again) == fmi2OK && again == value, "%s: reads back %g", what, again);
                check_call(&in, SETTER[v->type], what, st, set_allowed((State)s, index), fmi2OK, SAME,
                           errors_before, messages_before);
                inst_free(&in);
            }
        }
    }
}
