/* SPDX-License-Identifier: BSD-2-Clause */
/* painleve_native_cs: an IWC case through the PainleveRod FMU's own
 * Co-Simulation from C, one fmi2DoStep over the whole case -- what a case
 * costs where no master's work is in the loop.
 *
 *   painleve_native_cs FMU_DIR|LIBRARY.so [--rtol X] [--repeat N] < cases
 *
 * Cases as painleve_native_me reads them (cases.h). Each run, on one instance:
 * fmi2Reset (after the first), fmi2SetupExperiment with the tolerance, the
 * case's values set, initialization, one fmi2DoStep from 0 to the case's
 * horizon (Experiment's), the state and the record read. wall_seconds: the
 * median over --repeat runs of all of that; fixed_seconds: the same run with
 * the step left out (reset, set values, initialization, the reads), the cost
 * per run that is not integration. One more run, untimed, with the FMU's log category
 * logStatistics on, gives the integrators' work over the step (explicit steps, right-hand
 * sides, closed-form flight evaluations, CVODE steps and right-hand sides, events: the
 * FMU's log line). The state at the horizon is in flight;
 * bench/native_driver.py runs the flight back to the floor in closed form
 * (as the harness's Co-Simulation fast loop does).
 *
 * Output (stdout, TSV): a header and one line per case. Failures print a
 * message on stderr and exit nonzero (2 usage and input, 1 a failed run). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cases.h"
#include "fmu_import.h"
#include "measure.h"
#include "native_fail.h"

enum { P_ALPHA, P_MU, P_DELTA, P_EPSILON, P_X, P_V, P_Y, P_W, P_THETA, P_PHI, N_SET };
static const char *const SET[N_SET] = { "alpha", "mu", "delta", "epsilon", "x", "v", "y", "w", "theta", "phi" };
enum { R_V, R_Y, R_W, R_THETA, R_PHI, R_CONTACT_END, N_READ };
static const char *const READ[N_READ] = { "v", "y", "w", "theta", "phi", "t_contact_end" };

/* The integrators' work over a step, as the FMU's logStatistics line gives it. */
enum { S_STEPS, S_RHS, S_FLIGHT, S_CVODE_STEPS, S_CVODE_RHS, S_EVENTS, N_STATS };

typedef struct {
    FmuImport fmu;
    fmi2CallbackFunctions callbacks;
    fmi2Component c;
    int used;
    fmi2ValueReference set[N_SET], read[N_READ], switches, contact;
    long stats[N_STATS]; /* from the last logStatistics line; -1 if none came */
} Cs;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                   fmi2String message, ...)
{
    (void)name;
    if (status >= fmi2Warning) fprintf(stderr, "painleve_native_cs: FMU: %s\n", message);
    const char *counts = strstr(message, ": explicit steps ");
    if (!env || !category || strcmp(category, "logStatistics") || !counts) return;
    long *st = ((Cs *)env)->stats;   /* the FMU doubles a '%' for the format: there is none in this line */
    if (sscanf(counts, ": explicit steps %ld, right-hand sides %ld, closed-form flight evaluations %ld, CVODE steps "
               "%ld, CVODE right-hand sides %ld, events %ld", &st[S_STEPS], &st[S_RHS], &st[S_FLIGHT],
               &st[S_CVODE_STEPS], &st[S_CVODE_RHS], &st[S_EVENTS]) != N_STATS)
        for (int i = 0; i < N_STATS; ++i) st[i] = -1;
}

static int cs_open(Cs *s, const char *path, char *err, size_t n)
{
    memset(s, 0, sizeof *s);
    if (!fmu_import_open(&s->fmu, path, err, n)) return 0;
    for (int i = 0; i < N_SET; ++i) {
        const FmuVariable *v = fmu_import_variable(&s->fmu, SET[i], 'R');
        if (!v) FAIL("the FMU has no Real variable %s", SET[i]);
        s->set[i] = v->vr;
    }
    for (int i = 0; i < N_READ; ++i) {
        const FmuVariable *v = fmu_import_variable(&s->fmu, READ[i], 'R');
        if (!v) FAIL("the FMU has no Real variable %s", READ[i]);
        s->read[i] = v->vr;
    }
    const FmuVariable *sw = fmu_import_variable(&s->fmu, "switches", 'I');
    const FmuVariable *ct = fmu_import_variable(&s->fmu, "contact", 'B');
    if (!sw || !ct) FAIL("the FMU has no Integer switches or Boolean contact");
    s->switches = sw->vr;
    s->contact = ct->vr;
    s->callbacks = (fmi2CallbackFunctions){ logger, calloc, free, NULL, s };
    s->c = s->fmu.fmi.Instantiate("native_cs", fmi2CoSimulation, s->fmu.guid, s->fmu.resource_uri, &s->callbacks,
                                  fmi2False, fmi2False);
    if (!s->c) FAIL("fmi2Instantiate(fmi2CoSimulation) failed");
    return 1;
}

static void cs_close(Cs *s)
{
    if (s->c) s->fmu.fmi.FreeInstance(s->c);
    fmu_import_close(&s->fmu);
}

typedef struct {
    double x[N_READ];
    int switches, contact;
} Run;

/* One run of case k; `step` 0 leaves the fmi2DoStep out (the fixed cost). */
static int run(Cs *s, const Case *k, double rtol, int step, Run *r, char *err, size_t n)
{
    const Fmi2Functions *f = &s->fmu.fmi;
    const double *p = k->value, eps = p[EPSILON];
    const double values[N_SET] = { p[ALPHA], p[MU], p[DELTA], eps, 0, p[V0], 0, eps * p[W10], p[THETA0], p[PHI0] };
    if (s->used && f->Reset(s->c) != fmi2OK) FAIL("fmi2Reset failed");
    s->used = 1;
    if (f->SetupExperiment(s->c, fmi2True, rtol, 0, fmi2False, 0) != fmi2OK) FAIL("fmi2SetupExperiment failed");
    if (f->SetReal(s->c, s->set, N_SET, values) != fmi2OK) FAIL("fmi2SetReal of the case failed");
    if (f->EnterInitializationMode(s->c) != fmi2OK || f->ExitInitializationMode(s->c) != fmi2OK)
        FAIL("initialization failed");
    if (step && f->DoStep(s->c, 0, horizon_of(k), fmi2True) != fmi2OK) FAIL("fmi2DoStep failed");
    fmi2Integer sw = 0;
    fmi2Boolean ct = 0;
    if (f->GetReal(s->c, s->read, N_READ, r->x) != fmi2OK || f->GetInteger(s->c, &s->switches, 1, &sw) != fmi2OK ||
        f->GetBoolean(s->c, &s->contact, 1, &ct) != fmi2OK)
        FAIL("reading the outcome failed");
    r->switches = (int)sw;
    r->contact = (int)ct;
    return 1;
}

int main(int argc, char **argv)
{
    char err[2048] = "";
    const char *path = NULL;
    double rtol = 0;
    long repeat = 1;
    for (int i = 1; i < argc; ++i) {
        char *end;
        if (!strcmp(argv[i], "--rtol") && i + 1 < argc) {
            rtol = strtod(argv[++i], &end);
            if (*end || !(rtol > 0 && rtol < 1)) return fprintf(stderr, "--rtol: give a number in (0, 1)\n"), 2;
        } else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) {
            errno = 0;
            repeat = strtol(argv[++i], &end, 10);
            if (*end || errno || repeat < 1 || repeat > 1000000) return fprintf(stderr, "--repeat: 1 to 1e6\n"), 2;
        } else if (!path && argv[i][0] != '-') {
            path = argv[i];
        } else {
            return fprintf(stderr, "usage: painleve_native_cs FMU_DIR|LIBRARY.so [--rtol X] [--repeat N] < cases\n"), 2;
        }
    }
    if (!path) return fprintf(stderr, "usage: painleve_native_cs FMU_DIR|LIBRARY.so [--rtol X] [--repeat N]\n"), 2;
    static Cs s; /* zero: cs_close is safe whatever failed */
    Case *cases = NULL;
    size_t count = 0;
    double *walls = calloc((size_t)repeat, sizeof *walls), *fixed = calloc((size_t)repeat, sizeof *fixed);
    int status = 0;
    if (!walls || !fixed || !cs_open(&s, path, err, sizeof err) || !read_cases(&cases, &count, err, sizeof err)) {
        fprintf(stderr, "painleve_native_cs: %s\n", walls && fixed ? err : "out of memory");
        status = 1;
    }
    if (!status) printf("theta0\tphi0\tv0\tdelta\tepsilon\tw10\talpha\tmu\trtol\tv\ty\tw\ttheta\tphi\tt_contact_end\t"
                        "switches\tcontact\twall_seconds\tfixed_seconds\tsteps\trhs\tflight_evaluations\tcvode_steps\t"
                        "cvode_rhs\tevents\n");
    for (size_t i = 0; i < count && !status; ++i) {
        const Case *k = &cases[i];
        const double tol = rtol > 0 ? rtol : fmin(1e-6, k->value[EPSILON] / 100);
        Run r;
        for (long rep = 0; rep < repeat && !status; ++rep) {
            double t0 = seconds();
            status = !run(&s, k, tol, 1, &r, err, sizeof err);
            walls[rep] = seconds() - t0;
            Run skip;
            t0 = seconds();
            status = status || !run(&s, k, tol, 0, &skip, err, sizeof err);
            fixed[rep] = seconds() - t0;
        }
        /* the work, from one more run with the statistics logged (not timed: the log line costs) */
        /* (an FMU without the category refuses it, once: its counts are -1; the next run resets it) */
        static const fmi2String STATISTICS[] = { "logStatistics" };
        static int has_statistics = 1;
        for (int q = 0; q < N_STATS; ++q) s.stats[q] = -1;
        if (!status && has_statistics && s.fmu.fmi.SetDebugLogging(s.c, fmi2True, 1, STATISTICS) != fmi2OK)
            has_statistics = 0;
        else if (!status && has_statistics) {
            Run counted;
            status = !run(&s, k, tol, 1, &counted, err, sizeof err) ||
                     s.fmu.fmi.SetDebugLogging(s.c, fmi2False, 1, STATISTICS) != fmi2OK;
            if (status && !err[0]) snprintf(err, sizeof err, "fmi2SetDebugLogging(logStatistics) failed");
        }
        if (status) {
            fprintf(stderr, "painleve_native_cs: case on line %ld: %s\n", k->line, err);
            break;
        }
        for (int f = 0; f < N_FIELDS; ++f) printf("%.17g\t", k->value[f]);
        printf("%.17g", tol);
        for (int q = 0; q < N_READ; ++q) printf("\t%.17g", r.x[q]);
        printf("\t%d\t%d\t%.9g\t%.9g", r.switches, r.contact, median(walls, (size_t)repeat),
               median(fixed, (size_t)repeat));
        for (int q = 0; q < N_STATS; ++q) printf("\t%ld", s.stats[q]);
        printf("\n");
    }
    if (path) cs_close(&s);
    free(cases);
    free(walls);
    free(fixed);
    return status;
}
