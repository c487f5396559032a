/* painleve_native_me: the PainleveRod FMU integrated as FMI 2.0 Model
 * Exchange by SUNDIALS CVODE with no Python in the loop -- the measured lower
 * limit of what an importer pays per impact-without-collision run.
 *
 *   painleve_native_me FMU_DIR|LIBRARY.so [--rtol X] [--repeat N] [--jacobian dq|analytic] < cases
 *
 * Each line of stdin is one case, "theta0 phi0 v0 delta epsilon w10 alpha mu"
 * (blank lines and lines starting with '#' are skipped). Each case runs as the
 * harness's fmpy fast loop runs it (python_harness/painleve/experiment.py):
 * on one instance, fmi2Reset between runs, the rod on the floor at t = 0
 * (x = 0, y = 0, w = epsilon w10), stopped at the event where the rod, having
 * touched, is back at y = 0 moving up (contact false, y >= 0).
 *
 * CVODE is set up as fmpy 0.3.32's CVodeSolver sets it up: BDF, Newton with
 * the dense linear solver, a difference-quotient Jacobian (or, with
 * --jacobian analytic, fmi2GetDirectionalDerivative), relative tolerance rtol
 * and absolute tolerance rtol * nominal per state, maximum step horizon / 50,
 * root finding on every event indicator, CVodeReInit after every event. The
 * horizon and default rtol are Experiment._solver_settings's: eps (10
 * ln(1/eps) / lambda_+ + 50 (1 + delta)) and min(1e-6, eps / 100).
 *
 * Output (stdout, TSV): a header, one line per case, then "# peak_rss_kib N"
 * (VmHWM: this program's own peak) and "# ru_maxrss_kib N" (getrusage, which
 * on Linux also counts the parent's RSS at fork).
 * wall_seconds is the median over --repeat runs of one case, measured with
 * CLOCK_MONOTONIC from fmi2Reset to fmi2Terminate. Any failure -- bad input,
 * a value the FMU refuses, a run that fails -- prints a message naming what
 * to fix on stderr and exits nonzero (2 for usage and input, 1 otherwise). */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "fmu_import.h"
#include "sundials_compat.h" /* fmu_src/fmi's: SUNDIALS 6 or 7 */

#define MAX_EVENT_ITERATIONS 1000 /* fmi2NewDiscreteStates calls at one event */

/* ------------------------------------------------------------------ cases */

enum { THETA0, PHI0, V0, DELTA, EPSILON, W10, ALPHA, MU, N_FIELDS };
static const char *const FIELD[N_FIELDS] = { "theta0", "phi0", "v0", "delta", "epsilon", "w10", "alpha", "mu" };

typedef struct {
    double value[N_FIELDS];
    long line; /* in stdin, for messages */
} Case;

/* The FMU variables a case sets, in this order (fmpy's start_values of Case). */
enum { P_ALPHA, P_MU, P_DELTA, P_EPSILON, P_X, P_V, P_Y, P_W, P_THETA, P_PHI, N_SET };
static const char *const SET_NAME[N_SET] = { "alpha", "mu", "delta", "epsilon", "x", "v", "y", "w", "theta", "phi" };

typedef struct {
    double w, v, theta, phi, t_return;
    int iwc;
    long nsteps, nfev, njev, ngev, nevents;
} Result;

/* --------------------------------------------------------------- the driver */

typedef struct {
    FmuImport fmu;
    fmi2CallbackFunctions callbacks;
    fmi2Component c;
    int used; /* the instance has run a case: the next one starts with fmi2Reset */
    unsigned int vr_set[N_SET], vr_contact, vr_mode;
    size_t ix_y, ix_w, ix_v, ix_theta, ix_phi; /* in the state vector */
    char fmu_message[1024];                    /* the FMU's last error message */
    /* CVODE, made once and re-initialized for every case and event */
    SUNContext ctx;
    N_Vector y, abstol;
    SUNMatrix A;
    SUNLinearSolver solver;
    void *cvode;
    int analytic;
    SundialsError cvode_error; /* CVODE's last error */
    const char *failed_call; /* the FMI call a CVODE callback saw fail */
    double *nominal;
} Driver;

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

/* ------------------------------------------------------------- set-up */

#define FAIL(...)                       \
    do {                                \
        snprintf(err, n, __VA_ARGS__); \
        return 0;                       \
    } while (0)

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

static int driver_open(Driver *d, const char *path, int analytic, char *err, size_t n)
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

static void driver_close(Driver *d)
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

/* lambda_+ of eq lambdapm with p = p_+(theta0); NaN unless p_+ < 0. */
static double lambda_plus(const Case *k)
{
    const double *x = k->value, s = sin(x[THETA0]), c = cos(x[THETA0]);
    const double p = 1 + x[ALPHA] * c * c - x[MU] * x[ALPHA] * s * c, delta = x[DELTA];
    if (!(p < 0)) return NAN;
    return -delta * p / 2 + sqrt(delta * delta * p * p - 4 * p) / 2;
}

/* Experiment._solver_settings: fast time 10 ln(1/eps)/lambda_+ + 50 (1 + delta), times eps. */
static double horizon_of(const Case *k)
{
    const double eps = k->value[EPSILON];
    return eps * (10 * log(1 / eps) / lambda_plus(k) + 50 * (1 + k->value[DELTA]));
}

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

static int run_case(Driver *d, const Case *k, double rtol, Result *r, char *err, size_t n)
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

/* ------------------------------------------------------------- input */

static int parse_case(const char *text, long line, Case *k, char *err, size_t n)
{
    const char *p = text;
    k->line = line;
    for (int i = 0; i < N_FIELDS; ++i) {
        while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
        if (*p == '\0' || *p == '\n')
            FAIL("line %ld: %d numbers given, 8 needed: theta0 phi0 v0 delta epsilon w10 alpha mu", line, i);
        char *end;
        errno = 0;
        k->value[i] = strtod(p, &end);
        if (end == p || (*end && !strchr(" \t\r\n", *end))) {
            const size_t len = strcspn(p, " \t\r\n");
            FAIL("line %ld: %s = '%.*s' is not a number", line, FIELD[i], (int)(len < 40 ? len : 40), p);
        }
        if (!isfinite(k->value[i]) || errno == ERANGE)
            FAIL("line %ld: %s = '%.*s' is not a finite double", line, FIELD[i], (int)(end - p < 40 ? end - p : 40), p);
        p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
    if (*p) FAIL("line %ld: more than 8 fields (theta0 phi0 v0 delta epsilon w10 alpha mu)", line);
    return 1;
}

/* Every case of stdin, or 0 with a message. */
static int read_cases(Case **cases, size_t *count, char *err, size_t n)
{
    char *line = NULL;
    size_t cap = 0, size = 0;
    long number = 0;
    int ok = 1;
    *cases = NULL;
    *count = 0;
    while (ok && getline(&line, &cap, stdin) != -1) {
        ++number;
        const char *p = line + strspn(line, " \t\r\n");
        if (*p == '\0' || *p == '#') continue;
        if (*count == size) {
            size = 2 * size + 16;
            Case *bigger = realloc(*cases, size * sizeof **cases);
            if (!bigger) {
                snprintf(err, n, "out of memory reading the cases");
                ok = 0;
                break;
            }
            *cases = bigger;
        }
        ok = parse_case(line, number, &(*cases)[*count], err, n);
        *count += (size_t)ok;
    }
    if (ok && ferror(stdin)) {
        snprintf(err, n, "reading stdin: %s", strerror(errno));
        ok = 0;
    }
    free(line);
    if (ok && *count == 0) {
        snprintf(err, n, "no cases on stdin: give lines 'theta0 phi0 v0 delta epsilon w10 alpha mu'");
        ok = 0;
    }
    return ok;
}

/* ------------------------------------------------------------- main */

static const char USAGE[] =
    "usage: painleve_native_me FMU_DIR|LIBRARY.so [--rtol X] [--repeat N] [--jacobian dq|analytic] < cases\n"
    "  FMU_DIR      an extracted PainleveRod.fmu (or its binaries/linux64/PainleveRod.so)\n"
    "  cases        lines 'theta0 phi0 v0 delta epsilon w10 alpha mu' on stdin\n"
    "  --rtol X     CVODE's relative tolerance (default per case: min(1e-6, epsilon/100))\n"
    "  --repeat N   run each case N times and report the median wall time (default 1)\n"
    "  --jacobian   dq: CVODE's difference quotients, as fmpy (default); analytic: fmi2GetDirectionalDerivative\n";

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, size_t count)
{
    qsort(v, count, sizeof *v, compare_doubles);
    return count % 2 ? v[count / 2] : (v[count / 2 - 1] + v[count / 2]) / 2;
}

/* VmHWM of /proc/self/status, KiB, or -1. Linux's ru_maxrss keeps the maximum
 * across exec, so a driver started from a large process (Python) would report
 * that process's RSS at fork; VmHWM belongs to this program's image alone. */
static long peak_rss_of_this_image(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    long kib = -1;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, "VmHWM:", 6) == 0) {
            kib = strtol(line + 6, NULL, 10);
            break;
        }
    fclose(f);
    return kib;
}

typedef struct {
    const char *path;
    double rtol; /* 0: the per-case default */
    long repeat;
    int analytic;
} Options;

static int parse_options(int argc, char **argv, Options *o, char *err, size_t n)
{
    *o = (Options){ NULL, 0.0, 1, 0 };
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (strcmp(a, "--rtol") == 0) {
            if (!value) FAIL("--rtol needs a value");
            o->rtol = strtod(value, &end);
            if (*end || end == value || !(o->rtol > 0) || !isfinite(o->rtol) || o->rtol >= 1)
                FAIL("--rtol %s: give a number in (0, 1)", value);
            ++i;
        } else if (strcmp(a, "--repeat") == 0) {
            if (!value) FAIL("--repeat needs a value");
            errno = 0;
            o->repeat = strtol(value, &end, 10);
            if (*end || end == value || errno || o->repeat < 1 || o->repeat > 1000000)
                FAIL("--repeat %s: give a whole number from 1 to 1000000", value);
            ++i;
        } else if (strcmp(a, "--jacobian") == 0) {
            if (!value || (strcmp(value, "dq") != 0 && strcmp(value, "analytic") != 0))
                FAIL("--jacobian %s: give dq or analytic", value ? value : "(nothing)");
            o->analytic = strcmp(value, "analytic") == 0;
            ++i;
        } else if (a[0] == '-' && a[1] != '\0') {
            FAIL("unknown option %s", a);
        } else if (o->path) {
            FAIL("one FMU path only (got %s and %s)", o->path, a);
        } else {
            o->path = a;
        }
    }
    if (!o->path) FAIL("no FMU given");
    return 1;
}

int main(int argc, char **argv)
{
    char err[2048];
    Options opt;
    if (argc > 1 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        fputs(USAGE, stdout);
        return 0;
    }
    if (!parse_options(argc, argv, &opt, err, sizeof err)) {
        fprintf(stderr, "painleve_native_me: %s\n%s", err, USAGE);
        return 2;
    }
    Driver d;
    if (!driver_open(&d, opt.path, opt.analytic, err, sizeof err)) {
        fprintf(stderr, "painleve_native_me: cannot load the FMU from %s: %s\n", opt.path, err);
        driver_close(&d);
        return 1;
    }
    Case *cases;
    size_t count;
    if (!read_cases(&cases, &count, err, sizeof err)) {
        fprintf(stderr, "painleve_native_me: bad input on stdin: %s\n", err);
        driver_close(&d);
        free(cases);
        return 2;
    }
    double *walls = calloc((size_t)opt.repeat, sizeof *walls);
    int status = 0;
    if (!walls) {
        fprintf(stderr, "painleve_native_me: out of memory\n");
        driver_close(&d);
        free(cases);
        return 1;
    }
    printf("theta0\tphi0\tv0\tdelta\tepsilon\tw10\talpha\tmu\trtol\tw\tv\ttheta\tphi\tt_return\tiwc\tnsteps\tnfev\t"
           "njev\tngev\tnevents\twall_seconds\n");
    for (size_t i = 0; i < count && status == 0; ++i) {
        const Case *k = &cases[i];
        const double rtol = opt.rtol > 0 ? opt.rtol : fmin(1e-6, k->value[EPSILON] / 100);
        Result r;
        for (long rep = 0; rep < opt.repeat; ++rep) {
            const double start = seconds();
            const int ok = run_case(&d, k, rtol, &r, err, sizeof err);
            walls[rep] = seconds() - start;
            if (!ok) {
                fprintf(stderr, "painleve_native_me: case on line %ld (", k->line);
                for (int f = 0; f < N_FIELDS; ++f)
                    fprintf(stderr, "%s%s = %.17g", f ? ", " : "", FIELD[f], k->value[f]);
                fprintf(stderr, "): %s\n", err);
                status = 1;
                break;
            }
        }
        if (status) break;
        for (int f = 0; f < N_FIELDS; ++f) printf("%.17g\t", k->value[f]);
        printf("%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%d\t%ld\t%ld\t%ld\t%ld\t%ld\t%.9g\n", rtol, r.w, r.v,
               r.theta, r.phi, r.t_return, r.iwc, r.nsteps, r.nfev, r.njev, r.ngev, r.nevents,
               median(walls, (size_t)opt.repeat));
        fflush(stdout);
    }
    driver_close(&d);
    free(walls);
    free(cases);
    if (status == 0) {
        struct rusage usage;
        getrusage(RUSAGE_SELF, &usage);
        const long own = peak_rss_of_this_image();
        printf("# peak_rss_kib\t%ld\n# ru_maxrss_kib\t%ld\n", own >= 0 ? own : usage.ru_maxrss, usage.ru_maxrss);
    }
    return status;
}
