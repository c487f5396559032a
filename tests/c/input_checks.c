/* SPDX-License-Identifier: BSD-2-Clause */
/* The inputs of modelDescription.xml (causality = "input"): that an FMU state
 * carries them (get, set, serialize, deserialize), that a Co-Simulation step
 * after an input jump restarts from the new input, and, for a model with a
 * force and torque on a rigid body (F_x, F_y, tau on a centre of mass vx_cm,
 * vy_cm turning at phi), that a jump acts from the communication point on by
 * Newton's laws. Where an input may be set and what a NaN does are checked
 * with every variable (conformance_table.c, fmi_driver.c). A model without
 * inputs has nothing to check here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "driver.h"

static const FmiApi *const f = &api;

/* The inputs (ScalarVariable indices); their number. */
static int input_indices(int out[MAX_VARS])
{
    int n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < MAX_VARS; ++k)
        if (md_var(k)->causality == MD_INPUT && md_var(k)->type == MD_REAL) out[n++] = k;
    return n;
}

/* Variable `name`'s index, 0 if the model has none. */
static int index_of(const char *name)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (strcmp(md_var(k)->name, name) == 0) return k;
    return 0;
}

/* Input k (of n) moved away from its start by `step` times a few of its own units. */
static double moved(int index, int k, double step)
{
    return md_var(index)->start + step * (1 + 0.5 * k);
}

static fmi2Status set_inputs(Inst *in, const int *inputs, int n, double step)
{
    fmi2Status st = fmi2OK;
    for (int k = 0; k < n && st == fmi2OK; ++k) {
        const fmi2ValueReference vr = md_var(inputs[k])->vr;
        const double value = moved(inputs[k], k, step);
        st = f->SetReal(in->c, &vr, 1, &value);
    }
    return st;
}

/* Every Real variable's value (value references in order of the XML). */
static int read_reals(Inst *in, double v[MAX_VARS])
{
    fmi2ValueReference vr[MAX_VARS];
    int n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < MAX_VARS; ++k)
        if (md_var(k)->type == MD_REAL) vr[n++] = md_var(k)->vr;
    CHECK(f->GetReal(in->c, vr, (size_t)n, v) == fmi2OK, "fmi2GetReal of every Real in %s: %s", STATE_NAME[in->state],
          harness.last_message);
    return n;
}

/* The first Real that differs (its name), NULL if none does. */
static const char *first_difference(const double *a, const double *b, int n)
{
    int r = 0;
    for (int k = 1; k <= MD_N_VARIABLES; ++k) {
        if (md_var(k)->type != MD_REAL) continue;
        if (r < n && memcmp(&a[r], &b[r], sizeof a[r]) != 0) return md_var(k)->name;
        ++r;
    }
    return NULL;
}

/* In `state`: inputs set to a, the FMU state taken and serialized, inputs set
 * to b; fmi2SetFMUstate of the state, then of its deserialized copy, each
 * gives back every Real as it was with a (the inputs and what they drive). */
static void check_state_carries_inputs(State state, const int *inputs, int n)
{
    Inst in;
    if (!inst_reach(&in, state, false)) return;
    char what[160];
    snprintf(what, sizeof what, "the FMU state of %s with inputs moved", STATE_NAME[state]);
    double with_a[MAX_VARS], again[MAX_VARS];
    fmi2FMUstate s = NULL, t = NULL;
    fmi2Byte *bytes = NULL;
    size_t size = 0;
    if (!CHECK(set_inputs(&in, inputs, n, 1e-3) == fmi2OK, "%s: setting the inputs: %s", what, harness.last_message))
        goto done;
    const int nr = read_reals(&in, with_a);
    if (!CHECK(f->GetFMUstate(in.c, &s) == fmi2OK && f->SerializedFMUstateSize(in.c, s, &size) == fmi2OK,
               "%s: fmi2GetFMUstate: %s", what, harness.last_message))
        goto done;
    bytes = malloc(size ? size : 1);
    if (!CHECK(bytes && f->SerializeFMUstate(in.c, s, bytes, size) == fmi2OK, "%s: fmi2SerializeFMUstate: %s", what,
               harness.last_message))
        goto done;
    CHECK(set_inputs(&in, inputs, n, -2e-3) == fmi2OK, "%s: setting the inputs again: %s", what, harness.last_message);
    read_reals(&in, again);
    CHECK(first_difference(with_a, again, nr) != NULL, "%s: moving the inputs changed no Real", what);

    CHECK(f->SetFMUstate(in.c, s) == fmi2OK, "%s: fmi2SetFMUstate: %s", what, harness.last_message);
    read_reals(&in, again);
    const char *differs = first_difference(with_a, again, nr);
    CHECK(!differs, "%s: after fmi2SetFMUstate %s differs from when the state was taken", what, differs);

    CHECK(set_inputs(&in, inputs, n, -2e-3) == fmi2OK, "%s: setting the inputs again: %s", what, harness.last_message);
    CHECK(f->DeSerializeFMUstate(in.c, bytes, size, &t) == fmi2OK && f->SetFMUstate(in.c, t) == fmi2OK,
          "%s: a deserialized state refused: %s", what, harness.last_message);
    read_reals(&in, again);
    differs = first_difference(with_a, again, nr);
    CHECK(!differs, "%s: after deserializing %s differs from when the state was taken", what, differs);
    inst_works(&in, what);
done:
    if (t) f->FreeFMUstate(in.c, &t);
    if (s) f->FreeFMUstate(in.c, &s);
    free(bytes);
    inst_free(&in);
}

/* Inputs set before initialization (FMI 2.0 leaves them out of condition 1;
 * fmpy sets them there, and the FMUs accept them: conformance_table.c) act as
 * if set in Initialization Mode: after fmi2ExitInitializationMode every Real
 * is the same either way, the inputs the values given. */
static void check_inputs_set_before_initialization(const int *inputs, int n)
{
    Inst early, late;
    if (!inst_reach(&early, ME_INSTANTIATED, false)) return;
    fmi2Status st = set_inputs(&early, inputs, n, 1e-3);
    if (st == fmi2OK) st = f->SetupExperiment(early.c, fmi2False, 0, 0, fmi2False, 0);
    if (st == fmi2OK) st = f->EnterInitializationMode(early.c);
    if (st == fmi2OK) st = f->ExitInitializationMode(early.c);
    CHECK(st == fmi2OK, "inputs set before initialization: %s (%s)", status_name(st), harness.last_message);
    double reals_early[MAX_VARS], reals_late[MAX_VARS];
    const int nr = read_reals(&early, reals_early);
    f->FreeInstance(early.c);
    if (!inst_reach(&late, ME_INIT, false)) return;
    st = set_inputs(&late, inputs, n, 1e-3);
    if (st == fmi2OK) st = f->ExitInitializationMode(late.c);
    CHECK(st == fmi2OK, "inputs set in Initialization Mode: %s (%s)", status_name(st), harness.last_message);
    late.state = ME_EVENT;
    read_reals(&late, reals_late);
    const char *differs = first_difference(reals_early, reals_late, nr);
    CHECK(!differs, "inputs set before initialization: %s differs from the run that set them while initializing",
          differs);
    for (int k = 0; k < n; ++k) {
        double value = NAN;
        const fmi2ValueReference vr = md_var(inputs[k])->vr;
        CHECK(f->GetReal(late.c, &vr, 1, &value) == fmi2OK && value == moved(inputs[k], k, 1e-3),
              "input %s reads %g, set to %g", md_var(inputs[k])->name, value, moved(inputs[k], k, 1e-3));
    }
    inst_free(&late);
}

/* A communication step after input k jumped equals, bit for bit, the same
 * step from the same FMU state set afresh (fmi2SetFMUstate: a new integration
 * from the communication point) with the same jump: the jump restarts the
 * integration at the point, it does not carry the solver's history across it. */
static void check_step_after_jump(const int *inputs, int k)
{
    Inst a, b;
    if (!inst_reach(&a, CS_STEP_COMPLETE, false)) return;
    if (!inst_reach(&b, CS_STEP_COMPLETE, false)) {
        inst_free(&a);
        return;
    }
    const char *name = md_var(inputs[k])->name;
    fmi2FMUstate s = NULL;
    CHECK(f->GetFMUstate(b.c, &s) == fmi2OK && f->SetFMUstate(b.c, s) == fmi2OK, "fmi2Get/SetFMUstate: %s",
          harness.last_message);
    if (s) f->FreeFMUstate(b.c, &s);
    const fmi2ValueReference vr = md_var(inputs[k])->vr;
    const double value = moved(inputs[k], k, 1e-2);
    const double h = 0.01;
    double after_a[MAX_VARS], after_b[MAX_VARS];
    fmi2Status st = f->SetReal(a.c, &vr, 1, &value);
    if (st == fmi2OK) st = f->DoStep(a.c, a.t, h, fmi2True);
    CHECK(st == fmi2OK, "a step after %s jumped to %g: %s (%s)", name, value, status_name(st), harness.last_message);
    st = f->SetReal(b.c, &vr, 1, &value);
    if (st == fmi2OK) st = f->DoStep(b.c, b.t, h, fmi2True);
    CHECK(st == fmi2OK, "a step after fmi2SetFMUstate and %s = %g: %s (%s)", name, value, status_name(st),
          harness.last_message);
    const int nr = read_reals(&a, after_a);
    read_reals(&b, after_b);
    const char *differs = first_difference(after_a, after_b, nr);
    CHECK(!differs, "a step after %s jumped differs in %s from the step restarted from the FMU state", name, differs);
    a.t += h;
    f->FreeInstance(b.c); /* first: inst_free checks that nothing is left */
    inst_works(&a, "a step after an input jump");
    inst_free(&a);
}

/* Free flight (the contact end 1 m above the floor): the centre of mass and
 * the rotation obey Newton's laws alone, m dV/dt = (F_x, F_y - m g) and
 * J dphi/dt = tau, so a jump of the loads at a communication point changes
 * the velocities over the next step h by exactly those accelerations times h
 * (to the integrator's tolerance): not earlier, later or in part. */
static void check_loads_jump_by_newtons_laws(void)
{
    const int fx = index_of("F_x"), fy = index_of("F_y"), tau = index_of("tau"), vx = index_of("vx_cm"),
              vy = index_of("vy_cm"), phi = index_of("phi"), y = index_of("y"), m = index_of("m"), J = index_of("J"),
              g = index_of("g");
    if (!(fx && fy && tau && vx && vy && phi && y && m && J && g)) return;
    Inst in;
    if (!inst_reach(&in, CS_INSTANTIATED, false)) return;
    const fmi2ValueReference vr_y = md_var(y)->vr, loads[3] = { md_var(fx)->vr, md_var(fy)->vr, md_var(tau)->vr },
                             watch[3] = { md_var(vx)->vr, md_var(vy)->vr, md_var(phi)->vr };
    const double high = 1.0, load[3] = { 3.0, 5.0, 0.7 }, h = 0.01;
    double before[3], after[3];
    fmi2Status st = f->SetReal(in.c, &vr_y, 1, &high);
    if (st == fmi2OK) st = f->SetupExperiment(in.c, fmi2False, 0, 0, fmi2False, 0);
    if (st == fmi2OK) st = f->EnterInitializationMode(in.c);
    if (st == fmi2OK) st = f->ExitInitializationMode(in.c);
    if (st == fmi2OK) st = f->DoStep(in.c, 0, h, fmi2True);
    if (st == fmi2OK) st = f->GetReal(in.c, watch, 3, before);
    if (st == fmi2OK) st = f->SetReal(in.c, loads, 3, load);
    if (st == fmi2OK) st = f->DoStep(in.c, h, h, fmi2True);
    if (st == fmi2OK) st = f->GetReal(in.c, watch, 3, after);
    if (CHECK(st == fmi2OK, "free flight with a jump of the loads: %s (%s)", status_name(st), harness.last_message)) {
        const double mass = md_var(m)->start, inertia = md_var(J)->start, gravity = md_var(g)->start;
        const double expected[3] = { load[0] / mass * h, (load[1] / mass - gravity) * h, load[2] / inertia * h };
        for (int k = 0; k < 3; ++k)
            CHECK(fabs(after[k] - before[k] - expected[k]) <= 1e-5 * (1 + fabs(before[k])),
                  "free flight: %s changed by %.10g over the step after the loads jumped, Newton's laws say %.10g",
                  md_var(k == 0 ? vx : k == 1 ? vy : phi)->name, after[k] - before[k], expected[k]);
        printf("inputs: free flight after a jump of F_x, F_y, tau follows Newton's laws\n");
    }
    inst_free(&in);
}

void test_inputs(void)
{
    int inputs[MAX_VARS];
    const int n = input_indices(inputs);
    static const State STATES[] = { ME_INIT, ME_EVENT, ME_CONTINUOUS, CS_INIT, CS_STEP_COMPLETE };
    for (size_t s = 0; n > 0 && s < sizeof STATES / sizeof STATES[0]; ++s)
        check_state_carries_inputs(STATES[s], inputs, n);
    for (int k = 0; k < n; ++k) check_step_after_jump(inputs, k);
    if (n > 0) check_inputs_set_before_initialization(inputs, n);
    check_loads_jump_by_newtons_laws();
    printf("inputs: %d checked\n", n);
}
