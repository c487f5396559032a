/* SPDX-License-Identifier: BSD-2-Clause */
/* The platform driver: runs cases on one FMU binary and prints its outputs bit
 * for bit, so that tests/platforms/test_platforms.py compares every platform's
 * binary (win64 under wine, aarch64 under qemu) with x86_64-linux's. It is
 * cross-compiled per target with the FMU (platform_fmi.c loads it) and does
 * its own arithmetic without fused multiply-add (-ffp-contract=off), so two
 * platforms that round alike print alike.
 *
 * stdin, whitespace-separated, every double as the 16 hex digits of its bits:
 *   VERSION(2|3) LIBRARY TOKEN NX NZ
 *   case ME|CS START STOP H NP (VR VALUE)*NP NO VR*NO      (any number of cases)
 *   end
 * stdout, per case: "case K", then at each communication point "at T OUT...",
 * or "status WHERE S" where a call returned more than Warning (the case ends).
 * Model Exchange integrates with SUBSTEPS explicit Euler steps per
 * communication step and handles state events at the end of the step. */
#include <inttypes.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "platform_fmi.h"

enum { MAX_VALUES = 64, SUBSTEPS = 20, MAX_EVENT_ITERATIONS = 100, MAX_POINTS = 100000 };

typedef struct {
    bool cosimulation;
    double start, stop, h;
    size_t np, no;
    unsigned pvr[MAX_VALUES], ovr[MAX_VALUES];
    double pvalue[MAX_VALUES];
} Case;

static double read_double(void)
{
    char text[32];
    if (scanf("%31s", text) != 1) return 0.0;
    const uint64_t bits = strtoull(text, NULL, 16);
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

static void print_double(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    printf(" %016" PRIx64, bits);
}

static bool read_count(size_t *n)
{
    unsigned long v;
    if (scanf("%lu", &v) != 1 || v > MAX_VALUES) return false;
    *n = v;
    return true;
}

static bool read_case(Case *c)
{
    char kind[8];
    if (scanf("%7s", kind) != 1) return false;
    c->cosimulation = strcmp(kind, "CS") == 0;
    c->start = read_double();
    c->stop = read_double();
    c->h = read_double();
    if (!read_count(&c->np)) return false;
    for (size_t i = 0; i < c->np; ++i) {
        if (scanf("%u", &c->pvr[i]) != 1) return false;
        c->pvalue[i] = read_double();
    }
    if (!read_count(&c->no)) return false;
    for (size_t i = 0; i < c->no; ++i)
        if (scanf("%u", &c->ovr[i]) != 1) return false;
    return c->h > 0 && c->stop >= c->start && (c->stop - c->start) / c->h < MAX_POINTS;
}

#define CALL(where, call)                                                                                 \
    do {                                                                                                   \
        const int status_ = (call);                                                                        \
        if (status_ > 1) {                                                                                 \
            printf("status %s %d\n", where, status_);                                                      \
            return false;                                                                                  \
        }                                                                                                  \
    } while (0)

static bool print_outputs(Fmu *fmu, const Case *c, double t)
{
    double out[MAX_VALUES];
    CALL("get", fmu_get_reals(fmu, c->ovr, c->no, out));
    printf("at");
    print_double(t);
    for (size_t i = 0; i < c->no; ++i) print_double(out[i]);
    printf("\n");
    return true;
}

/* Event Mode until the model needs no more iterations, then Continuous-Time Mode. */
static bool handle_events(Fmu *fmu, bool *terminate)
{
    for (int i = 0; i < MAX_EVENT_ITERATIONS; ++i) {
        bool again = false;
        CALL("update", fmu_update_discrete(fmu, &again, terminate));
        if (!again || *terminate) return fmu_enter_continuous(fmu) <= 1;
    }
    printf("status event-iterations 3\n");
    return false;
}

/* One communication step of explicit Euler with state events at substep ends. */
static bool me_step(Fmu *fmu, size_t nx, size_t nz, double *x, double *z, double t0, double h, bool *terminate)
{
    double dx[MAX_VALUES], znew[MAX_VALUES];
    for (int k = 1; k <= SUBSTEPS && !*terminate; ++k) {
        const double t = t0 + h * (k - 1) / SUBSTEPS, tnew = t0 + h * k / SUBSTEPS;
        CALL("set-time", fmu_set_time(fmu, t));
        CALL("set-states", fmu_set_states(fmu, x, nx));
        CALL("derivatives", fmu_get_derivatives(fmu, dx, nx));
        for (size_t i = 0; i < nx; ++i) x[i] += (tnew - t) * dx[i];
        CALL("set-time", fmu_set_time(fmu, tnew));
        CALL("set-states", fmu_set_states(fmu, x, nx));
        CALL("indicators", fmu_get_indicators(fmu, znew, nz));
        bool event = false;
        CALL("completed", fmu_completed_step(fmu, &event, terminate));
        for (size_t i = 0; i < nz; ++i) event = event || (z[i] > 0) != (znew[i] > 0);
        memcpy(z, znew, nz * sizeof *z);
        if (event) {
            CALL("enter-event", fmu_enter_event(fmu));
            if (!handle_events(fmu, terminate)) return false;
            CALL("states", fmu_get_states(fmu, x, nx));
            CALL("indicators", fmu_get_indicators(fmu, z, nz));
        }
    }
    return true;
}

static bool run_case(Fmu *fmu, const char *token, size_t nx, size_t nz, const Case *c)
{
    CALL("instantiate", fmu_instantiate(fmu, token, c->cosimulation));
    CALL("set", fmu_set_reals(fmu, c->pvr, c->np, c->pvalue));
    CALL("initialize", fmu_initialize(fmu, c->start, c->stop));
    double x[MAX_VALUES], z[MAX_VALUES];
    bool terminate = false;
    if (!c->cosimulation) {
        if (!handle_events(fmu, &terminate)) return false;
        CALL("states", fmu_get_states(fmu, x, nx));
        CALL("indicators", fmu_get_indicators(fmu, z, nz));
    }
    if (!print_outputs(fmu, c, c->start)) return false;
    const long points = (long)((c->stop - c->start) / c->h + 0.5);
    for (long k = 0; k < points && !terminate; ++k) {
        const double t = c->start + (double)k * c->h, tnext = c->start + (double)(k + 1) * c->h;
        if (c->cosimulation)
            CALL("do-step", fmu_do_step(fmu, t, tnext - t));
        else if (!me_step(fmu, nx, nz, x, z, t, tnext - t, &terminate))
            return false;
        if (!print_outputs(fmu, c, tnext)) return false;
    }
    return true;
}

int main(void)
{
    int version;
    char library[4096], token[256];
    size_t nx, nz;
    if (scanf("%d %4095s %255s", &version, library, token) != 3 || (version != 2 && version != 3) ||
        !read_count(&nx) || !read_count(&nz)) {
        fprintf(stderr, "usage: stdin VERSION LIBRARY TOKEN NX NZ, then cases (platform_driver.c)\n");
        return 2;
    }
    Fmu *fmu = fmu_load(library, version);
    if (!fmu) return 1;
    char word[8];
    int k = 0;
    while (scanf("%7s", word) == 1 && strcmp(word, "case") == 0) {
        Case c;
        if (!read_case(&c)) {
            fprintf(stderr, "case %d: malformed\n", k);
            fmu_unload(fmu);
            return 2;
        }
        printf("case %d\n", k++);
        run_case(fmu, token, nx, nz, &c);
        fmu_free_instance(fmu);
    }
    fmu_unload(fmu);
    return 0;
}
