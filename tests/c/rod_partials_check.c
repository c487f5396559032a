/* SPDX-License-Identifier: BSD-2-Clause */
/* rod_partials against central finite differences of the functions it
 * differentiates (the contact core's contact_derivatives, contact_normal_force,
 * contact_friction_force, contact_energy on the rod), at random states, parameters and applied loads, in every mode: flight (both
 * slip signs), contact slipping forward and backward, sticking. The mode is
 * held fixed, so each function is one smooth branch and the differences
 * never cross a switching surface. Also: dx_x is rod_jacobian, bit for bit.
 *
 * Built and run by tests/fmu/test_rod_partials.py. Prints every disagreement and
 * exits 1 if there is any. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rod_partials.h"

#define NF (ROD_NX + ROD_NOUT) /* state derivatives, then F_N, F_T, energy, the coefficients a .. S_w */
#define NK (ROD_NX + ROD_NP + ROD_NL) /* states, alpha, mu, delta, epsilon, kappa, beta, then f_x, f_y, tau */
#define POINTS_PER_MODE 400
#define REL_TOL 1e-6

static unsigned long long rng_state = 0x9E3779B97F4A7C15ull;

static double uniform(double lo, double hi)
{
    rng_state ^= rng_state << 13; /* xorshift64 */
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) / 9007199254740992.0;
}

static double *param(RodParams *p, int j)
{
    switch (j) {
    case ROD_P_ALPHA: return &p->alpha;
    case ROD_P_MU: return &p->mu;
    case ROD_P_DELTA: return &p->delta;
    case ROD_P_EPSILON: return &p->epsilon;
    case ROD_P_KAPPA: return &p->kappa;
    case ROD_P_BETA: return &p->beta;
    case ROD_NP + ROD_L_FX: return &p->f_x;
    case ROD_NP + ROD_L_FY: return &p->f_y;
    default: return &p->tau;
    }
}

static void values(const RodParams *p, ContactMode m, const double x[ROD_NX], double f[NF])
{
    const Contact c = rod_contact(p);
    contact_derivatives(&c, m, x, f);
    f[ROD_NX + ROD_OUT_F_N] = contact_normal_force(&c, m, x);
    f[ROD_NX + ROD_OUT_F_T] = contact_friction_force(&c, m, x);
    f[ROD_NX + ROD_OUT_ENERGY] = contact_energy(&c, m, x);
    rod_coefficient_outputs(p, x, f + ROD_NX);
}

static double analytic(const RodPartials *d, int i, int j)
{
    const int l = j - ROD_NX - ROD_NP;   /* a load's column */
    if (i < ROD_NX) return j < ROD_NX ? d->dx_x[i][j] : l < 0 ? d->dx_p[i][j - ROD_NX] : d->dx_l[i][l];
    i -= ROD_NX;
    return j < ROD_NX ? d->out_x[i][j] : l < 0 ? d->out_p[i][j - ROD_NX] : d->out_l[i][l];
}

/* Column j of the central difference with step h, in the known's own scale n:
 * FD[i] = n (f(k + h) - f(k - h)) / (2 h). */
static void central_difference(RodParams p, ContactMode m, const double x0[ROD_NX], int j, double n, double FD[NF])
{
    double x[ROD_NX], fp[NF], fm[NF];
    const double h = 1e-5 * n;
    double *k = x + j;
    memcpy(x, x0, sizeof x);
    if (j >= ROD_NX) k = param(&p, j - ROD_NX);
    const double k0 = *k;
    *k = k0 + h;
    values(&p, m, x, fp);
    *k = k0 - h;
    values(&p, m, x, fm);
    for (int i = 0; i < NF; ++i) FD[i] = n * (fp[i] - fm[i]) / (2 * h);
}

static const char *const ROW[NF] = { "der(x)", "der(v)", "der(y)", "der(w)", "der(theta)", "der(phi)",
                                     "F_N", "F_T", "energy" };
static const char *const COL[NK] = { "x", "v", "y", "w", "theta", "phi", "alpha", "mu", "delta", "epsilon",
                                     "kappa", "beta", "f_x", "f_y", "tau" };

/* One random point: every entry, scaled by its known's scale n_j, within REL_TOL of the
 * difference, plus a floor far above the differences' round-off (~1e-11 |f|). */
static int check_point(ContactMode m, const char *mode_name, long *entries)
{
    /* kappa, beta up to 30: at penetrations d = -y/eps ~ 3 eps their terms are O(1) parts of h */
    RodParams p = { .alpha = uniform(0.3, 6), .mu = uniform(0, 3), .delta = uniform(0, 3), .epsilon = uniform(1e-3, 0.3),
                    .kappa = uniform(0, 30), .beta = uniform(0, 30) };
    if (uniform(0, 1) < 0.1) p.delta = 0; /* undamped contacts too */
    if (uniform(0, 1) < 0.2) p.kappa = p.beta = 0; /* the paper's linear law too */
    if (uniform(0, 1) < 0.7) {                       /* applied loads (the SI model's inputs) */
        p.f_x = uniform(-2, 2);
        p.f_y = uniform(-2, 2);
        p.tau = uniform(-2, 2);
    }
    const double eps = p.epsilon;
    double x[ROD_NX] = { uniform(-5, 5), uniform(-2, 2), eps * eps * uniform(-3, 3), eps * uniform(-3, 3),
                         uniform(-3.2, 3.2), uniform(-2.5, 2.5) };
    if (!m.contact) x[ROD_Y] = uniform(-0.5, 1); /* flight, after lift-off with y < 0 too */
    if (m.contact && m.slip == 0) x[ROD_V] = 0;

    RodPartials d;
    rod_partials(&p, m, x, &d);
    double J[ROD_NX][ROD_NX];
    rod_jacobian(&p, m, x, J);
    int failed = 0;
    if (memcmp(J, d.dx_x, sizeof J) != 0) {
        printf("FAIL %s: dx_x is not rod_jacobian\n", mode_name);
        ++failed;
    }
    double nominal[ROD_NX], n[NK], FD[NK][NF], f[NF], scale[NF] = { 0 };
    const Contact c = rod_contact(&p);
    c.body->nominals(c.params, c.law.epsilon, nominal);
    for (int j = 0; j < NK; ++j) {
        const double k = j < ROD_NX ? x[j] : *param(&p, j - ROD_NX);
        n[j] = fmax(fabs(k), j < ROD_NX ? nominal[j] : 1e-2);
        central_difference(p, m, x, j, n[j], FD[j]);
    }
    values(&p, m, x, f);
    for (int i = 0; i < NF; ++i) {
        scale[i] = fabs(f[i]);
        for (int j = 0; j < NK; ++j) scale[i] = fmax(scale[i], fabs(FD[j][i]));
    }
    for (int i = 0; i < NF; ++i)
        for (int j = 0; j < NK; ++j) {
            const double a = n[j] * analytic(&d, i, j), fd = FD[j][i];
            ++*entries;
            if (!(fabs(a - fd) <= REL_TOL * fabs(fd) + 1e-8 * scale[i])) {
                printf("FAIL %s: d %s / d %s = %.12g, central difference %.12g (x = %g %g %g %g %g %g; alpha %g mu %g "
                       "delta %g eps %g kappa %g beta %g; loads %g %g %g)\n", mode_name, ROW[i], COL[j], a / n[j],
                       fd / n[j], x[0], x[1], x[2], x[3], x[4], x[5], p.alpha, p.mu, p.delta, p.epsilon, p.kappa, p.beta,
                       p.f_x, p.f_y, p.tau);
                ++failed;
            }
        }
    return failed;
}

int main(void)
{
    static const struct { ContactMode m; const char *name; } MODES[] = {
        { { false, +1 }, "flight (+1)" }, { { false, -1 }, "flight (-1)" }, { { true, +1 }, "slip forward" },
        { { true, -1 }, "slip backward" }, { { true, 0 }, "stick" },
    };
    long entries = 0;
    int failed = 0;
    for (size_t k = 0; k < sizeof MODES / sizeof MODES[0]; ++k)
        for (int i = 0; i < POINTS_PER_MODE; ++i) failed += check_point(MODES[k].m, MODES[k].name, &entries);
    printf("rod_partials: %ld entries at %d points in each of 5 modes, %d failed\n", entries, POINTS_PER_MODE,
           failed);
    return failed ? 1 : 0;
}
