/* SPDX-License-Identifier: BSD-2-Clause */
/* painleve_native_me: the PainleveRod FMU integrated as FMI 2.0 Model
 * Exchange by SUNDIALS CVODE with no Python in the loop -- the measured lower
 * limit of what an importer pays per impact-without-collision run.
 *
 *   painleve_native_me FMU_DIR|LIBRARY.so [--rtol X] [--repeat N] [--jacobian dq|analytic] < cases
 *
 * Each line of stdin is one case, "theta0 phi0 v0 delta epsilon w10 alpha mu"
 * (blank lines and lines starting with '#' are skipped). Each case runs as the
 * harness's fmpy fast loop runs it (python_harness/painleve/fmu/experiment.py):
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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "cases.h"
#include "driver.h"
#include "measure.h"
#include "native_fail.h"

static const char USAGE[] =
    "usage: painleve_native_me FMU_DIR|LIBRARY.so [--rtol X] [--repeat N] [--jacobian dq|analytic] < cases\n"
    "  FMU_DIR      an extracted PainleveRod.fmu (or its binaries/linux64/PainleveRod.so)\n"
    "  cases        lines 'theta0 phi0 v0 delta epsilon w10 alpha mu' on stdin\n"
    "  --rtol X     CVODE's relative tolerance (default per case: min(1e-6, epsilon/100))\n"
    "  --repeat N   run each case N times and report the median wall time (default 1)\n"
    "  --jacobian   dq: CVODE's difference quotients, as fmpy (default); analytic: fmi2GetDirectionalDerivative\n";

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
