/* SPDX-License-Identifier: BSD-2-Clause */
/* The native driver's runs (driver.h): the FMU's set-up, CVODE's view of it,
 * and one case from fmi2Reset to fmi2Terminate. */
#include "driver.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "native_fail.h"

#define MAX_EVENT_ITERATIONS 1000 /* fmi2NewDiscreteStates calls at one event */

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...)
{
    (void)instance, (void)category;
    Driver *d = env;
    if (status < fmi2Error || !message) return;
    va_list ap;
    va_start(ap, message);
    vsnprintf(d->fmu_message, sizeof d->fmu_message, message, ap);
    va_end(ap);
}

#define OK(status) ((status) <= fmi2Warning)

/* ------------------------------------------------ CVODE's view of the FMU */

static int set_time_and_states(Driver *d, sunrealtype t, N_Vector y)
{
    if (!OK(d->fmu.fmi.SetTime(d->c, t))) {
        d->failed_call = "fmi2SetTime";
        return -1;
    }
    if (!OK(d->fmu.fmi.SetContinuousStates(d->c, N_VGetArrayPointer(y), d->fmu.nx))) {
        d->failed_call = "fmi2SetContinuousStates";
        return -1;
    }
    return 0;
}

static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    Driver *d = data;
    if (set_time_and_states(d, t, y)) return -1;
    if (!OK(d->fmu.fmi.GetDerivatives(d->c, N_VGetArrayPointer(ydot), d->fmu.nx))) {
        d->failed_call = "fmi2GetDerivatives";
        return -1;
    }
    return 0;
}

static int roots(sunrealtype t, N_Vector y, sunrealtype *z, void *data)
{
    Driver *d = data;
    if (set_time_and_states(d, t, y)) return -1;
    if (!OK(d->fmu.fmi.GetEventIndicators(d->c, z, d->fmu.nz))) {
        d->failed_call = "fmi2GetEventIndicators";
        return -1;
    }
    return 0;
}

/* J column by column: the derivatives' directional derivative along each state. */
static int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *data, N_Vector t1, N_Vector t2,
                    N_Vector t3)
{
    (void)fy, (void)t1, (void)t2, (void)t3;
    Driver *d = data;
    if (set_time_and_states(d, t, y)) return -1;
    const size_t nx = d->fmu.nx;
    const double one = 1.0;
    for (size_t j = 0; j < nx; ++j) {
        sunrealtype *column = SM_COLUMN_D(J, (sunindextype)j);
        if (!OK(d->fmu.fmi.GetDirectionalDerivative(d->c, d->fmu.derivative_vr, nx, &d->fmu.state_vr[j], 1, &one,
                                                column))) {
            d->failed_call = "fmi2GetDirectionalDerivative";
            return -1;
        }
    }
    return 0;
}

static int state_index(const Driver *d, unsigned int vr, size_t *index)
{
    for (size_t i = 0; i < d->fmu.nx; ++i)
        if (d->fmu.state_vr[i] == vr) {
            *index = i;
            return 1;
        }
    return 0;
}

/* Value references by name, from modelDescription.xml. */
static int find_variables(Driver *d, char *err, size_t n)
{
    const FmuImport *f = &d->fmu;
    for (int k = 0; k < N_SET; ++k) {
        const FmuVariable *v = fmu_import_variable(f, SET_NAME[k], 'R');
        if (!v) FAIL("%s/modelDescription.xml has no Real variable '%s': not the PainleveRod FMU", f->fmu_dir, SET_NAME[k]);
        d->vr_set[k] = v->vr;
    }
    const FmuVariable *contact = fmu_import_variable(f, "contact", 'B');
    const FmuVariable *mode = fmu_import_variable(f, "mode", 'I');
    if (!contact || !mode)
        FAIL("%s/modelDescription.xml lacks the Boolean 'contact' or the Integer 'mode': not the PainleveRod FMU",
             f->fmu_dir);
    d->vr_contact = contact->vr;
    d->vr_mode = mode->vr;
    if (!state_index(d, d->vr_set[P_Y], &d->ix_y) || !state_index(d, d->vr_set[P_W], &d->ix_w) ||
        !state_index(d, d->vr_set[P_V], &d->ix_v) || !state_index(d, d->vr_set[P_THETA], &d->ix_theta) ||
        !state_index(d, d->vr_set[P_PHI], &d->ix_phi))
        FAIL("%s/modelDescription.xml: v, y, w, theta and phi must be continuous states", f->fmu_dir);
    return 1;
}

static int create_cvode(Driver *d, char *err, size_t n)
{
    const sunindextype nx = (sunindextype)d->fmu.nx;
    if (SUNContext_Create(SUN_COMM_NULL, &d->ctx)) FAIL("SUNContext_Create failed");
    d->y = N_VNew_Serial(nx, d->ctx);
    d->abstol = N_VNew_Serial(nx, d->ctx);
    d->A = SUNDenseMatrix(nx, nx, d->ctx);
    d->cvode = CVodeCreate(CV_BDF, d->ctx);
    if (!d->y || !d->abstol || !d->A || !d->cvode) FAIL("out of memory setting up CVODE");
    d->solver = SUNLinSol_Dense(d->y, d->A, d->ctx);
    if (!d->solver) FAIL("out of memory setting up CVODE's dense linear solver");
    N_VConst(0.0, d->y);
    N_VConst(1.0, d->abstol);
    if (CVodeInit(d->cvode, rhs, 0.0, d->y) != CV_SUCCESS || sundials_catch_errors(d->ctx, d->cvode, &d->cvode_error) ||
        CVodeSetUserData(d->cvode, d) != CV_SUCCESS ||
        (d->fmu.nz > 0 && CVodeRootInit(d->cvode, (int)d->fmu.nz, roots) != CV_SUCCESS) ||
        CVodeSetLinearSolver(d->cvode, d->solver, d->A) != CV_SUCCESS ||
        (d->analytic && CVodeSetJacFn(d->cvode, jacobian) != CV_SUCCESS) ||
        CVodeSetNoInactiveRootWarn(d->cvode) != CV_SUCCESS)
        FAIL("CVODE set-up failed: %s", d->cvode_error.text);
    return 1;
}

int driver_open(Driver *d, const char *path, int analytic, char *err, size_t n)
{
    memset(d, 0, sizeof *d);
    d->analytic = analytic;
    if (!fmu_import_open(&d->fmu, path, err, n)) return 0;
    if (!find_variables(d, err, n)) return 0;
    const size_t nx = d->fmu.nx;
    d->nominal = calloc(nx, sizeof *d->nominal);
    if (!d->nominal) FAIL("out of memory");
    if (!create_cvode(d, err, n)) return 0;
    d->callbacks = (fmi2CallbackFunctions){ .logger = logger, .allocateMemory = calloc, .freeMemory = free,
                                            .stepFinished = NULL, .componentEnvironment = d };
    d->c = d->fmu.fmi.Instantiate("native_me", fmi2ModelExchange, d->fmu.guid, d->fmu.resource_uri, &d->callbacks,
                              fmi2False, fmi2False);
    if (!d->c)
        FAIL("fmi2Instantiate failed%s%s", d->fmu_message[0] ? ": " : " (no message)", d->fmu_message);
    return 1;
}

void driver_close(Driver *d)
{
    if (d->c) d->fmu.fmi.FreeInstance(d->c);
    if (d->cvode) CVodeFree(&d->cvode);
    if (d->solver) SUNLinSolFree(d->solver);
    if (d->A) SUNMatDestroy(d->A);
    if (d->y) N_VDestroy(d->y);
    if (d->abstol) N_VDestroy(d->abstol);
    if (d->ctx) SUNContext_Free(&d->ctx);
    free(d->nominal);
    fmu_import_close(&d->fmu);
    memset(d, 0, sizeof *d);
}

/* ------------------------------------------------------------- one run */

/* "fmi2X failed: <the FMU's message>" */
static int fmu_failed(Driver *d, const char *call, char *err, size_t n)
{
    const char *said = d->fmu_message;
    const size_t len = strlen(call);
    if (strncmp(said, call, len) == 0 && strncmp(said + len, ": ", 2) == 0) said += len + 2; /* "call: reason" */
    FAIL("%s failed: %s", call, *said ? said : "(the FMU logged no message)");
}

#define CALL(name, ...) \
    if (!OK(d->fmu.fmi.name(__VA_ARGS__))) return fmu_failed(d, "fmi2" #name, err, n)

typedef struct {
    long nst, nfe, nfeLS, nje, nge;
} Counts;

static void add_counts(Driver *d, Counts *total)
{
    long nst = 0, nfe = 0, nfeLS = 0, nje = 0, nge = 0;
    CVodeGetNumSteps(d->cvode, &nst);
    CVodeGetNumRhsEvals(d->cvode, &nfe);
    CVodeGetNumLinRhsEvals(d->cvode, &nfeLS);
    CVodeGetNumJacEvals(d->cvode, &nje);
    CVodeGetNumGEvals(d->cvode, &nge);
    total->nst += nst, total->nfe += nfe, total->nfeLS += nfeLS, total->nje += nje, total->nge += nge;
}

/* fmi2NewDiscreteStates until no more are needed, then continuous-time mode. */
static int event_iteration(Driver *d, fmi2EventInfo *info, double t, char *err, size_t n)
{
    fmi2Boolean values_changed = fmi2False, nominals_changed = fmi2False;
    info->newDiscreteStatesNeeded = fmi2True;
    info->terminateSimulation = fmi2False;
    for (int k = 0; info->newDiscreteStatesNeeded && !info->terminateSimulation; ++k) {
        if (k == MAX_EVENT_ITERATIONS)
            FAIL("the event iteration at t = %.17g did not converge in %d fmi2NewDiscreteStates calls", t,
                 MAX_EVENT_ITERATIONS);
        CALL(NewDiscreteStates, d->c, info);
        values_changed |= info->valuesOfContinuousStatesChanged;
        nominals_changed |= info->nominalsOfContinuousStatesChanged;
    }
    if (info->terminateSimulation) FAIL("the FMU asked to terminate at t = %.17g, before the rod came back to y = 0", t);
    info->valuesOfContinuousStatesChanged = values_changed;
    info->nominalsOfContinuousStatesChanged = nominals_changed;
    CALL(EnterContinuousTimeMode, d->c);
    return 1;
}

static int set_tolerances(Driver *d, double rtol, char *err, size_t n)
{
    CALL(GetNominalsOfContinuousStates, d->c, d->nominal, d->fmu.nx);
    double *abstol = N_VGetArrayPointer(d->abstol);
    for (size_t i = 0; i < d->fmu.nx; ++i) abstol[i] = rtol * d->nominal[i];
    if (CVodeSVtolerances(d->cvode, rtol, d->abstol) != CV_SUCCESS) FAIL("CVodeSVtolerances: %s", d->cvode_error.text);
    return 1;
}

/* touched/stuck/back from the FMU's discrete states, after an event iteration. */
static int observe(Driver *d, int *touched, int *stuck, int *back, char *err, size_t n)
{
    fmi2Boolean contact;
    fmi2Integer mode;
    CALL(GetBoolean, d->c, &d->vr_contact, 1, &contact);
    CALL(GetInteger, d->c, &d->vr_mode, 1, &mode);
    *touched |= contact != fmi2False;
    *stuck |= contact && mode == 0;
    *back = *touched && !contact && NV_Ith_S(d->y, (sunindextype)d->ix_y) >= 0;
    return 1;
}

int run_case(Driver *d, const Case *k, double rtol, Result *r, char *err, size_t n)
{
    const double *x = k->value, eps = x[EPSILON];
    const double horizon = horizon_of(k);
    const int have_horizon = isfinite(horizon) && horizon > 0;
    d->fmu_message[0] = d->cvode_error.text[0] = '\0';
    d->failed_call = NULL;
    memset(r, 0, sizeof *r);

    if (d->used) CALL(Reset, d->c);
    d->used = 1;
    CALL(SetupExperiment, d->c, fmi2False, 0.0, 0.0, have_horizon ? fmi2True : fmi2False, have_horizon ? horizon : 0.0);
    const double start[N_SET] = { x[ALPHA], x[MU], x[DELTA], eps, 0.0, x[V0], 0.0, eps * x[W10], x[THETA0], x[PHI0] };
    CALL(SetReal, d->c, d->vr_set, N_SET, start);
    if (!have_horizon)
        FAIL("p_+(theta0) >= 0 for theta0 = %g, alpha = %g, mu = %g: outside the Painleve wedge there is no IWC "
             "(the run's horizon needs lambda_+ > 0; pick theta0 in (theta_1, theta_2))", x[THETA0], x[ALPHA], x[MU]);
    CALL(EnterInitializationMode, d->c);
    CALL(ExitInitializationMode, d->c);
    fmi2EventInfo info;
    if (!event_iteration(d, &info, 0.0, err, n)) return 0;

    /* fmpy's CVodeSolver: states and nominals from the FMU, abstol = rtol * nominal. */
    CALL(GetContinuousStates, d->c, N_VGetArrayPointer(d->y), d->fmu.nx);
    if (CVodeReInit(d->cvode, 0.0, d->y) != CV_SUCCESS) FAIL("CVodeReInit: %s", d->cvode_error.text);
    if (!set_tolerances(d, rtol, err, n)) return 0;
    /* fmpy: maxStep = (stop - start) / 50; at most 500 steps per output interval eps/2. */
    const double intervals = ceil(horizon / (eps / 2));
    const long max_steps = intervals < 1e9 / 500 ? 500L * (long)intervals : 1000000000L;
    if (CVodeSetMaxStep(d->cvode, horizon / 50) != CV_SUCCESS ||
        CVodeSetMaxNumSteps(d->cvode, max_steps) != CV_SUCCESS)
        FAIL("CVODE options: %s", d->cvode_error.text);

    int touched = 0, stuck = 0, back = 0;
    if (!observe(d, &touched, &stuck, &back, err, n)) return 0;
    Counts counts = { 0, 0, 0, 0, 0 };
    sunrealtype t = 0.0;
    while (!back) {
        const int time_event = info.nextEventTimeDefined && info.nextEventTime < horizon;
        const double tout = time_event ? info.nextEventTime : horizon;
        if (CVodeSetStopTime(d->cvode, tout) != CV_SUCCESS) FAIL("CVodeSetStopTime(%.17g): %s", tout, d->cvode_error.text);
        const int flag = CVode(d->cvode, tout, d->y, &t, CV_NORMAL);
        if (flag < 0) {
            if (d->failed_call) return fmu_failed(d, d->failed_call, err, n);
            FAIL("CVODE failed at t = %.17g: %s", t, d->cvode_error.text);
        }
        CALL(SetTime, d->c, t);
        CALL(SetContinuousStates, d->c, N_VGetArrayPointer(d->y), d->fmu.nx);
        fmi2Boolean enter_event_mode = fmi2False, terminate = fmi2False;
        CALL(CompletedIntegratorStep, d->c, fmi2True, &enter_event_mode, &terminate);
        if (terminate) FAIL("the FMU asked to terminate at t = %.17g, before the rod came back to y = 0", t);
        const int reached_time_event = time_event && t >= info.nextEventTime;
        if (flag == CV_ROOT_RETURN || reached_time_event || enter_event_mode) {
            CALL(EnterEventMode, d->c);
            if (!event_iteration(d, &info, t, err, n)) return 0;
            ++r->nevents;
            if (info.valuesOfContinuousStatesChanged)
                CALL(GetContinuousStates, d->c, N_VGetArrayPointer(d->y), d->fmu.nx);
            if (info.nominalsOfContinuousStatesChanged && !set_tolerances(d, rtol, err, n)) return 0;
            add_counts(d, &counts); /* CVodeReInit zeroes CVODE's counters */
            if (CVodeReInit(d->cvode, t, d->y) != CV_SUCCESS) FAIL("CVodeReInit: %s", d->cvode_error.text);
            if (!observe(d, &touched, &stuck, &back, err, n)) return 0;
        } else if (t >= horizon) {
            FAIL("the rod did not come back to y = 0 by t = %.6g, the horizon (touched the floor: %s); is eps small "
                 "enough for the asymptotic regime? eps * delta = %g",
                 horizon, touched ? "yes" : "no", eps * x[DELTA]);
        }
    }
    add_counts(d, &counts);
    CALL(Terminate, d->c);
    const double *s = N_VGetArrayPointer(d->y);
    r->w = s[d->ix_w], r->v = s[d->ix_v], r->theta = s[d->ix_theta], r->phi = s[d->ix_phi], r->t_return = t;
    r->iwc = stuck;
    r->nsteps = counts.nst;
    r->nfev = counts.nfe + counts.nfeLS;
    r->njev = counts.nje;
    r->ngev = counts.nge;
    return 1;
}
