/* SPDX-License-Identifier: BSD-2-Clause */
/* Instances together: stepped in turn and independent, and instantiated,
 * simulated and freed in cycles with a flat resident set (the memory soak). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "robustness.h"

static const FmiApi *const f = &api;

/* --------------------------------------------------- instances together */

static bool same_state(const EulerSim *a, const EulerSim *b)
{
    return memcmp(a->x, b->x, sizeof a->x) == 0 && a->events == b->events;
}

/* Instances stepped in turn are independent: equal set-ups give equal runs. */
void test_interleaved_instances(void)
{
    enum { N = 32, STEPS = 60 };
    EulerSim s[N];
    char name[32];
    for (int k = 0; k < N; ++k) {
        snprintf(name, sizeof name, "rod%d", k);
        s[k] = (EulerSim){ .c = harness_instantiate(f, name) };
        if (!CHECK(s[k].c != NULL, "instance %d", k)) return;
        CHECK(euler_start(f, &s[k], k % 2 ? 0.1 : 0.05) == fmi2OK, "start %d", k);
    }
    for (int step = 0; step < STEPS; ++step)
        for (int k = 0; k < N; ++k) {
            if (!s[k].c) continue;
            CHECK(euler_step(f, &s[k], 5e-3) == fmi2OK, "instance %d step %d: %s", k, step, harness.last_message);
            /* Some instances leave early, in various states. */
            if (k % 5 == 4 && step == STEPS / 2 + k) {
                f->FreeInstance(s[k].c);
                s[k].c = NULL;
            }
        }
    for (int k = 2; k < N; ++k)
        if (s[k].c && s[k % 2].c)
            CHECK(same_state(&s[k], &s[k % 2]), "instance %d ended unlike instance %d", k, k % 2);
    if (MODEL_NZ > 0)
        CHECK(s[0].events > 0 && s[1].events > 0, "the runs crossed no event (%d, %d)", s[0].events, s[1].events);
    for (int k = N - 1; k >= 0; k -= 2)
        if (s[k].c) f->FreeInstance(s[k].c);
    for (int k = 0; k < N; k += 2)
        if (s[k].c) f->FreeInstance(s[k].c);
    CHECK(harness.live == 0, "%ld blocks left after freeing every instance", harness.live);
}

/* --------------------------------------------------------- memory soak */

static long resident_kb(void)
{
    long size = 0, resident = 0;
    FILE *fp = fopen("/proc/self/statm", "r");
    if (!fp) return -1;
    if (fscanf(fp, "%ld %ld", &size, &resident) != 2) resident = -1;
    fclose(fp);
    return resident < 0 ? -1 : resident * (sysconf(_SC_PAGESIZE) / 1024);
}

/* Instantiate, simulate (Model Exchange with events, or Co-Simulation every
 * fourth cycle), sometimes reset and simulate again or stop half-way, free:
 * `cycles` times, with the resident set measured after a warm-up and at the end. */
void test_cycles(long cycles, long max_growth_kb, bool cosimulation)
{
    const long warmup = cycles / 10 < 1000 ? cycles / 10 : 1000;
    long rss_before = -1, events = 0;
    for (long k = 0; k < cycles; ++k) {
        if (k == warmup) rss_before = resident_kb();
        fmi2Status st;
        fmi2Component c;
        if (cosimulation && k % 4 == 1) {
            /* Co-Simulation: CVODE's memory, made on the first step, freed with the instance. */
            c = cs_instance();
            if (!CHECK(c != NULL, "cycle %ld: fmi2Instantiate(fmi2CoSimulation) failed", k)) return;
            double t = 0;
            st = cs_start(c, 0.05);
            if (st == fmi2OK) st = cs_run(c, &t, 0.02, k % 8 == 5 ? 3 : 12);
            if (k % 3 == 0 && st == fmi2OK) st = f->Reset(c);
        } else {
            c = harness_instantiate(f, "cycling rod");
            if (!CHECK(c != NULL, "cycle %ld: fmi2Instantiate failed", k)) return;
            EulerSim s = { .c = c };
            /* 24 steps cross about three events (stick, slip, lift-off); some runs stop early. */
            st = harness_simulate(f, &s, 0.05, 1e-2, k % 7 == 3 ? 6 : 24);
            events += s.events;
            if (k % 10 == 5 && st == fmi2OK) {
                st = f->Reset(c);
                if (st == fmi2OK) st = harness_simulate(f, &s, 0.05, 5e-3, 6);
            }
        }
        if (k % 13 == 7) (void)set_one(c, PROFILE_KNOB, NAN); /* leave through the Error state */
        f->FreeInstance(c);
        if (!CHECK(st == fmi2OK, "cycle %ld: %s (%s)", k, status_name(st), harness.last_message)) return;
        if (!CHECK(harness.live == 0, "cycle %ld left %ld blocks allocated", k, harness.live)) return;
    }
    const long rss_after = resident_kb();
    printf("cycles: %ld instantiate/simulate/free cycles, %ld events, %ld allocations; resident set %ld kB "
           "after %ld warm-up cycles, %ld kB at the end\n",
           cycles, events, harness.allocations, rss_before, warmup, rss_after);
    if (MODEL_NZ > 0) CHECK(cycles == 0 || events > cycles / 2, "the cycles crossed too few events (%ld)", events);
    if (max_growth_kb >= 0 && cycles > 0)
        CHECK(rss_after - rss_before <= max_growth_kb, "resident set grew by %ld kB over %ld cycles (bound %ld kB)",
              rss_after - rss_before, cycles - warmup, max_growth_kb);
}
