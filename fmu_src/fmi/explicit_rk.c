/* SPDX-License-Identifier: BSD-2-Clause */
/* The Dormand-Prince 5(4) pair over the model (explicit_rk.h). Coefficients
 * from J. R. Dormand and P. J. Prince, "A family of embedded Runge-Kutta
 * formulae", J. Comput. Appl. Math. 6 (1980) 19-26; the continuous extension
 * and the stiffness test from Hairer, Norsett and Wanner, Solving Ordinary
 * Differential Equations I (2nd ed.), II.6 and IV.2; step control there, II.4. */
#include "explicit_rk.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "step_end.h"

enum { NX = MODEL_NX, NZ = MODEL_NZ };

/* The tableau: nodes c, stages a, the fifth-order weights b (the last stage's
 * row: first same as last), e = b - b^ (the fourth-order error estimate) and
 * the dense output's d. */
static const double C2 = 1.0 / 5, C3 = 3.0 / 10, C4 = 4.0 / 5, C5 = 8.0 / 9;
static const double A21 = 1.0 / 5;
static const double A31 = 3.0 / 40, A32 = 9.0 / 40;
static const double A41 = 44.0 / 45, A42 = -56.0 / 15, A43 = 32.0 / 9;
static const double A51 = 19372.0 / 6561, A52 = -25360.0 / 2187, A53 = 64448.0 / 6561, A54 = -212.0 / 729;
static const double A61 = 9017.0 / 3168, A62 = -355.0 / 33, A63 = 46732.0 / 5247, A64 = 49.0 / 176,
                    A65 = -5103.0 / 18656;
static const double B1 = 35.0 / 384, B3 = 500.0 / 1113, B4 = 125.0 / 192, B5 = -2187.0 / 6784, B6 = 11.0 / 84;
static const double E1 = 71.0 / 57600, E3 = -71.0 / 16695, E4 = 71.0 / 1920, E5 = -17253.0 / 339200,
                    E6 = 22.0 / 525, E7 = -1.0 / 40;
static const double D1 = -12715105075.0 / 11282082432, D3 = 87487479700.0 / 32700410799,
                    D4 = -10690763975.0 / 1880347072, D5 = 701980252875.0 / 199316789632,
                    D6 = -1453857185.0 / 822651844, D7 = 69997945.0 / 29380423;

/* Step control (HNW II.4): a new step is h (SAFETY / err)^(1/5), within these factors of the last. */
#define SAFETY 0.9
#define GROW_MAX 10.0
#define SHRINK_MAX 0.2
/* The stiffness test (HNW IV.2): h |lambda| estimated from the last two stages. On the real axis
 * the pair is stable to 3.3; where a contact's spring and damper hold the step, the estimate
 * scatters widely about that bound, so a step counts as held by stability when its estimate
 * passes 1, and the count is net of the steps that do not. An IWC's contact holds O(ln 1/eps)
 * such steps; a contact that holds hundreds is sustained (a rod resting or sliding, a rod on
 * the shaker table): CVODE integrates it, after at most a few hundred explicit steps
 * (docs/fmu.md gives the measurements). */
#define STABILITY_MARK 1.0
#define STIFF_STEPS_TO_HAND_OVER 300
/* Root location to CVODE's resolution (100 units in the last place of the time) within a bound:
 * Illinois steps, every fourth a bisection, halve the bracket at least every fourth try. */
#define ROOT_TOLERANCE_ULPS 100
#define MAX_ROOT_ITERATIONS 200

/* The absolute tolerance is this share of rtol x nominal: a state that passes through values
 * below its nominal (a lift-off's w, of the order eps/2 where w's nominal is eps) would otherwise
 * be held to its nominal's rtol, not its own, and an outcome such as w at the return would miss
 * rtol relative by the ratio of the two; with a tenth, the absolute part no longer decides it. */
#define ABSOLUTE_SHARE 0.1

void erk_start(Erk *e, const Model *m, double t, double rtol)
{
    double nominal[NX];
    model_get_nominals(m, nominal);
    e->rtol = rtol;
    for (int i = 0; i < NX; ++i) e->atol[i] = ABSOLUTE_SHARE * rtol * nominal[i];
    model_get_states(m, e->y);
    model_indicators_at(m, t, e->y, e->z);
    e->h = 0;
    e->stiff_steps = 0;
    e->why = "";
}

bool erk_all_finite(const double *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i])) return false;
    return true;
}

static bool rhs(Erk *e, const Model *m, double t, const double x[NX], double dx[NX])
{
    ++e->rhs;
    model_derivatives_at(m, t, x, dx);
    return erk_all_finite(dx, NX);
}

/* The weighted RMS norm of v, weights atol + rtol max(|y0|, |y1|) (CVODE's, with the larger end). */
static double norm(const Erk *e, const double v[NX], const double y0[NX], const double y1[NX])
{
    double sum = 0;
    for (int i = 0; i < NX; ++i) {
        const double s = e->atol[i] + e->rtol * fmax(fabs(y0[i]), fabs(y1[i]));
        sum += (v[i] / s) * (v[i] / s);
    }
    return sqrt(sum / NX);
}

#ifdef MODEL_GAP_ROWS
/* norm() with the model's gap and normal rate (rows r at y0) as two more components, weighted
 * as a state is: ABSOLUTE_SHARE rtol nominal + rtol max of their values at y0 and, linearized,
 * at y1. */
static double norm_with_rows(const Erk *e, const double v[NX], const double y0[NX], const double y1[NX],
                             const ModelGapRows *r)
{
    const double n = norm(e, v, y0, y1);
    double sum = n * n * NX;
    for (int k = 0; k < 2; ++k) {
        double dv = 0, dy = 0;
        for (int i = 0; i < NX; ++i) {
            dv += r->row[k][i] * v[i];
            dy += r->row[k][i] * (y1[i] - y0[i]);
        }
        const double size = fmax(fabs(r->value[k]), fabs(r->value[k] + dy));
        const double s = e->rtol * (ABSOLUTE_SHARE * r->nominal[k] + size);
        sum += (dv / s) * (dv / s);
    }
    return sqrt(sum / (NX + 2));
}
#endif

/* A trial step's error norm: its error err from y0 to y1 (with the model's rows where it has them). */
static double step_error(const Erk *e, const Model *m, double t, const double err[NX], const double y0[NX],
                         const double y1[NX])
{
#ifdef MODEL_GAP_ROWS
    ModelGapRows r;
    model_gap_rows_at(m, t, y0, &r);
    return norm_with_rows(e, err, y0, y1, &r);
#else
    (void)m, (void)t;
    return norm(e, err, y0, y1);
#endif
}

/* The next step's factor SAFETY err^(-1/5), within SHRINK_MAX and GROW_MAX: err^(-1/5) as
 * exp(-log(err)/5), which libm computes in a fraction of pow's time (the controller needs the
 * factor to a few ulps, not pow's correct rounding), and neither where the bounds decide. */
static double step_factor(double err)
{
    static const double GROWS = (SAFETY / GROW_MAX) * (SAFETY / GROW_MAX) * (SAFETY / GROW_MAX) *
                                (SAFETY / GROW_MAX) * (SAFETY / GROW_MAX);         /* (SAFETY/GROW_MAX)^5 */
    static const double SHRINKS = (SAFETY / SHRINK_MAX) * (SAFETY / SHRINK_MAX) * (SAFETY / SHRINK_MAX) *
                                  (SAFETY / SHRINK_MAX) * (SAFETY / SHRINK_MAX);   /* (SAFETY/SHRINK_MAX)^5 */
    if (!(err > GROWS)) return GROW_MAX;        /* err <= (SAFETY/GROW_MAX)^5, or not a number */
    if (err >= SHRINKS) return SHRINK_MAX;
    return fmin(GROW_MAX, fmax(SHRINK_MAX, SAFETY * exp(-0.2 * log(err))));
}

/* The first step from the scales of y and f (HNW II.4, "starting step size"), at most `span`;
 * 0 if a right-hand side is not finite. */
static double first_step(Erk *e, const Model *m, double t, double span)
{
    double y1[NX], f1[NX], df[NX];
    const double d0 = norm(e, e->y, e->y, e->y), d1 = norm(e, e->f, e->y, e->y);
    double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 * span : 0.01 * d0 / d1;
    h0 = fmin(h0, span);
    for (int i = 0; i < NX; ++i) y1[i] = e->y[i] + h0 * e->f[i];
    if (!rhs(e, m, t + h0, y1, f1)) return 0;
    for (int i = 0; i < NX; ++i) df[i] = f1[i] - e->f[i];
    const double d2 = norm(e, df, e->y, e->y) / h0, dmax = fmax(d1, d2);
    const double h1 = dmax <= 1e-15 ? fmax(1e-6 * span, h0 * 1e-3) : pow(0.01 / dmax, 1.0 / 5);
    return fmin(fmin(100 * h0, h1), span);
}

typedef struct {
    double k[7][NX]; /* the stages; k[6] = f(t + h, y1) */
    double y1[NX];   /* the fifth-order solution */
    double y6[NX];   /* the sixth stage's argument (the stiffness test) */
} Trial;

/* One trial step of size h from (t, e->y, e->f): its error norm, infinite if a value is not finite. */
static double try_step(Erk *e, const Model *m, double t, double h, Trial *s)
{
    double (*k)[NX] = s->k, x[NX], err[NX];
    memcpy(k[0], e->f, sizeof k[0]);
    for (int i = 0; i < NX; ++i) x[i] = e->y[i] + h * A21 * k[0][i];
    if (!rhs(e, m, t + C2 * h, x, k[1])) return INFINITY;
    for (int i = 0; i < NX; ++i) x[i] = e->y[i] + h * (A31 * k[0][i] + A32 * k[1][i]);
    if (!rhs(e, m, t + C3 * h, x, k[2])) return INFINITY;
    for (int i = 0; i < NX; ++i) x[i] = e->y[i] + h * (A41 * k[0][i] + A42 * k[1][i] + A43 * k[2][i]);
    if (!rhs(e, m, t + C4 * h, x, k[3])) return INFINITY;
    for (int i = 0; i < NX; ++i)
        x[i] = e->y[i] + h * (A51 * k[0][i] + A52 * k[1][i] + A53 * k[2][i] + A54 * k[3][i]);
    if (!rhs(e, m, t + C5 * h, x, k[4])) return INFINITY;
    for (int i = 0; i < NX; ++i)
        s->y6[i] = e->y[i] + h * (A61 * k[0][i] + A62 * k[1][i] + A63 * k[2][i] + A64 * k[3][i] + A65 * k[4][i]);
    if (!rhs(e, m, t + h, s->y6, k[5])) return INFINITY;
    for (int i = 0; i < NX; ++i)
        s->y1[i] = e->y[i] + h * (B1 * k[0][i] + B3 * k[2][i] + B4 * k[3][i] + B5 * k[4][i] + B6 * k[5][i]);
    if (!rhs(e, m, t + h, s->y1, k[6]) || !erk_all_finite(s->y1, NX)) return INFINITY;
    for (int i = 0; i < NX; ++i)
        err[i] = h * (E1 * k[0][i] + E3 * k[2][i] + E4 * k[3][i] + E5 * k[4][i] + E6 * k[5][i] + E7 * k[6][i]);
    return step_error(e, m, t, err, e->y, s->y1);
}

/* h |lambda| along the step's last two stages (HNW IV.2 (2.26)). */
static double stiffness(const Trial *s, double h)
{
    double num = 0, den = 0;
    for (int i = 0; i < NX; ++i) {
        num += (s->k[6][i] - s->k[5][i]) * (s->k[6][i] - s->k[5][i]);
        den += (s->y1[i] - s->y6[i]) * (s->y1[i] - s->y6[i]);
    }
    return den > 0 ? h * sqrt(num / den) : 0;
}

/* The dense output's coefficients (HNW II.6): y(t + th h) = r0 + th (r1 + (1-th) (r2 + th (r3 + (1-th) r4))). */
typedef struct {
    double r[5][NX];
} Dense;

static void dense_of(const Erk *e, const Trial *s, double h, Dense *d)
{
    for (int i = 0; i < NX; ++i) {
        const double dy = s->y1[i] - e->y[i], b = h * s->k[0][i] - dy;
        d->r[0][i] = e->y[i];
        d->r[1][i] = dy;
        d->r[2][i] = b;
        d->r[3][i] = dy - h * s->k[6][i] - b;
        d->r[4][i] = h * (D1 * s->k[0][i] + D3 * s->k[2][i] + D4 * s->k[3][i] + D5 * s->k[4][i] +
                          D6 * s->k[5][i] + D7 * s->k[6][i]);
    }
}

static void dense_at(const Dense *d, double th, double x[NX])
{
    const double th1 = 1 - th;
    for (int i = 0; i < NX; ++i)
        x[i] = d->r[0][i] + th * (d->r[1][i] + th1 * (d->r[2][i] + th * (d->r[3][i] + th1 * d->r[4][i])));
}

/* Indicator i has a root in (lo, hi] (CVODE's rule): it changed sign, or became 0, from a value
 * that was not 0 (one that starts at 0, on a surface at a restart, is not watched until it leaves). */
static bool crossed(double lo, double hi)
{
    return lo != 0 && (hi == 0 || (hi > 0) != (lo > 0));
}

bool erk_any_crossed(const double lo[], const double hi[])
{
    for (int i = 0; i < NZ; ++i)
        if (crossed(lo[i], hi[i])) return true;
    return false;
}

void erk_locate_root(const Model *m, double t, double h, const double z_lo[], const double z_hi[],
                     ErkStateAt state_at, const void *path, double *t_root, double x[NX])
{
    double glo[NZ + 1], ghi[NZ + 1], gmid[NZ + 1];
    memcpy(glo, z_lo, sizeof glo);
    memcpy(ghi, z_hi, sizeof ghi);
    double lo = 0, hi = 1, alpha = 1;
    int last_side = 0;
    const double resolution = ROOT_TOLERANCE_ULPS * DBL_EPSILON * (fabs(t + h) + fabs(h)) / fabs(h);
    for (int it = 0; it < MAX_ROOT_ITERATIONS && hi - lo > resolution; ++it) {
        /* the secant of the indicator whose root the secants put first */
        double mid = hi;
        for (int i = 0; i < NZ; ++i)
            if (crossed(glo[i], ghi[i])) mid = fmin(mid, hi - (hi - lo) * ghi[i] / (ghi[i] - alpha * glo[i]));
        if (it % 4 == 3 || !(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
        mid = fmin(fmax(mid, lo + 0.5 * resolution), hi - 0.5 * resolution);
        state_at(path, mid, x);
        model_indicators_at(m, t + mid * h, x, gmid);
        const int side = erk_any_crossed(glo, gmid) ? 1 : 2;   /* 1: the root is in (lo, mid] */
        if (side == 1) {
            hi = mid;
            memcpy(ghi, gmid, sizeof ghi);
        } else {
            lo = mid;
            memcpy(glo, gmid, sizeof glo);
        }
        /* Illinois: an end kept twice has its value halved in the next secant */
        alpha = side != last_side ? 1 : side == 1 ? alpha * 0.5 : alpha * 2;
        last_side = side;
    }
    *t_root = hi >= 1 ? t + h : t + hi * h;
    state_at(path, hi, x);
}

/* The accepted step's dense output as an ErkStateAt: its end exactly y1. */
typedef struct {
    Dense d;
    const double *y1;
} DensePath;

static void dense_path_at(const void *path, double th, double x[NX])
{
    const DensePath *p = path;
    if (th >= 1) memcpy(x, p->y1, sizeof(double) * NX);
    else dense_at(&p->d, th, x);
}

/* The first root in the accepted step (t, t + h], located on the dense output. */
static void locate_root(Erk *e, const Model *m, const Trial *s, double t, double h, const double z1[], double *t_root,
                        double x[NX])
{
    DensePath p = { .y1 = s->y1 };
    dense_of(e, s, h, &p.d);
    erk_locate_root(m, t, h, e->z, z1, dense_path_at, &p, t_root, x);
}

ErkResult erk_hand_over(Erk *e, Model *m, const char *why)
{
    e->why = why;
    model_set_states(m, e->y);
    return ERK_HAND_OVER;
}

static ErkResult advance(Erk *e, Model *m, double *t, double t_end, long *steps_left)
{
    if (step_end_reached(*t, t_end)) {   /* the model's state is the one reached */
        *t = t_end;
        return ERK_REACHED;
    }
    if (e->h == 0) {   /* a start: the state is the model's */
        model_get_states(m, e->y);   /* e->z is the indicators there (erk_start, a flight) */
        model_anchor(m, e->y, true);
        if (!rhs(e, m, *t, e->y, e->f)) return erk_hand_over(e, m, "a right-hand side is not finite");
        e->h = first_step(e, m, *t, t_end - *t);
        if (!(e->h > 0)) return erk_hand_over(e, m, "a right-hand side is not finite");
    }
    bool rejected = false;
    Trial s;
    while (!step_end_reached(*t, t_end)) {
        if (*steps_left <= 0) {
            model_set_states(m, e->y);
            return ERK_BUDGET;
        }
        /* the last step reaches the end, or leaves of it what counts as reached (step_end.h) */
        const bool last = step_end_reached(*t + e->h, t_end);
        /* a step the time cannot resolve short of the end: the implicit solver decides (and says) what follows */
        if (!last && !(e->h > 16 * DBL_EPSILON * fmax(fabs(*t), fabs(t_end))))
            return erk_hand_over(e, m, "the step fell below the time's resolution");
        const double h = last ? t_end - *t : e->h;
        --*steps_left;
        ++e->steps;
        model_anchor(m, e->y, true);
        const double err = try_step(e, m, *t, h, &s);
        if (!isfinite(err)) return erk_hand_over(e, m, "a value is not finite");
        const double factor = step_factor(err);
        if (err > 1) {
            e->h = h * factor;
            rejected = true;
            continue;
        }
        /* accepted */
        e->stiff_steps = stiffness(&s, h) > STABILITY_MARK ? e->stiff_steps + 1
                                                            : e->stiff_steps > 0 ? e->stiff_steps - 1 : 0;
        const double next = h * (rejected ? fmin(1, factor) : factor);
        if (!last || next > e->h) e->h = next;   /* a step cut short at t_end leaves the natural one */
        rejected = false;
        double z1[NZ + 1];
        model_indicators_at(m, *t + h, s.y1, z1);
        if (erk_any_crossed(e->z, z1)) {
            double x[NX];
            locate_root(e, m, &s, *t, h, z1, t, x);
            model_set_states(m, x);
            return ERK_EVENT;
        }
        *t = last ? t_end : *t + h;
        memcpy(e->y, s.y1, sizeof e->y);
        memcpy(e->f, s.k[6], sizeof e->f);
        memcpy(e->z, z1, sizeof e->z);
        if (e->stiff_steps >= STIFF_STEPS_TO_HAND_OVER) return erk_hand_over(e, m, "a sustained stiff phase");
    }
    model_set_states(m, e->y);
    return ERK_REACHED;
}

ErkResult erk_advance(Erk *e, Model *m, double *t, double t_end, long *steps_left)
{
    const ErkResult r = advance(e, m, t, t_end, steps_left);
    model_anchor(m, e->y, false);
    return r;
}
