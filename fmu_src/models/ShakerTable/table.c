/* SPDX-License-Identifier: BSD-2-Clause */
/* ShakerTable on the model interface (model.h): a linear, time-driven
 * oscillator with no modes and no events,
 *     z' = v,   M v' = -K z - C v + F0 sin(2 pi frequency t) - F_N.
 * Knows the table, not FMI. */
#include "model.h"

#include <math.h>
#include <stdio.h>

/* 2 pi (C99 has no M_PI): the drive's angular frequency is TWO_PI * frequency. */
#define TWO_PI 6.283185307179586476925286766559

/* ------------------------------------------------------------ variables */

/* The variable table, field access, states and the FMU state's fields are
 * model_common.c's, from config.h's list. */

void model_reset(Model *m)
{
    /* A 10 kg top on 40 kN/m (10.07 Hz, damping ratio 0.032), shaken at 5 Hz. */
    *m = (Model){ .params = { .M = 10, .K = 4e4, .C = 40, .F0 = 50, .frequency = 5, .belt_speed = 0 },
                  .stale = true,
                  .partials_stale = true };
}

/* The physics at a time and state: the drive force and the accelerations. */
static double drive(const TableParams *p, double time)
{
    return p->F0 * sin(TWO_PI * p->frequency * time);
}

/* The spring's and the damper's force on the top: what its mount takes up. */
static double mount(const TableParams *p, const double x[MODEL_NX])
{
    return -p->K * x[TABLE_Z] - p->C * x[TABLE_V];
}

static void derivatives(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    const TableParams *p = &m->params;
    dx[TABLE_Z] = x[TABLE_V];
    dx[TABLE_V] = (mount(p, x) + drive(p, time) - m->F_N) / p->M;
}

void model_update(Model *m)
{
    if (!m->stale) return;
    const TableParams *p = &m->params;
    derivatives(m, m->time, m->x, m->dx);
    m->out[TABLE_OUT_DRIVE] = drive(p, m->time);
    /* Kinetic and spring energy about the static equilibrium (gravity's share is in it). */
    m->out[TABLE_OUT_ENERGY] = 0.5 * p->M * m->x[TABLE_V] * m->x[TABLE_V] + 0.5 * p->K * m->x[TABLE_Z] * m->x[TABLE_Z];
    /* The surface takes +F_T along x (the paper's sign): holding belt_speed, the drive does -F_T belt_speed. */
    m->out[TABLE_OUT_BELT_POWER] = -m->F_T * p->belt_speed;
    m->out[TABLE_OUT_MOUNT] = mount(p, m->x);
    m->out[TABLE_OUT_MOUNT_MEAN] = m->means_held ? m->step_mean[TABLE_MEAN_MOUNT] : m->out[TABLE_OUT_MOUNT];
    m->out[TABLE_OUT_DRIVE_MEAN] = m->means_held ? m->step_mean[TABLE_MEAN_DRIVE] : m->out[TABLE_OUT_DRIVE];
    m->stale = false;
}

/* ---------------------------------------------------- continuous states */

void model_get_nominals(const Model *m, double nominal[MODEL_NX])
{
    /* modelDescription.xml's nominals: a table shaken by some mm at some Hz
     * (the defaults: 1.66 mm, 0.05 m/s); CVODE's absolute tolerance is
     * rtol times these. */
    (void)m;
    nominal[TABLE_Z] = 1e-4;
    nominal[TABLE_V] = 1e-2;
}

void model_step_begin(Model *m, double time)
{
    m->step_time = time;   /* model_step_end's balance over the step */
    m->step_velocity = m->x[TABLE_V];
}

void model_set_time(Model *m, double time)
{
    if (time == m->time) return;
    m->time = time;
    model_touch(m);
}

void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    derivatives(m, time, x, dx);
}

void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX])
{
    (void)time, (void)x;
    const TableParams *p = &m->params;
    J[TABLE_Z][TABLE_Z] = 0;
    J[TABLE_Z][TABLE_V] = 1;
    J[TABLE_V][TABLE_Z] = -p->K / p->M;
    J[TABLE_V][TABLE_V] = -p->C / p->M;
}

/* ------------------------------------------- step means (Co-Simulation) */

/* Over a step from t0 to t1 = t0 + elapsed, with F_N held: the drive's impulse in
 * closed form, F0 (cos(w t0) - cos(w t1))/w, and the mount's as the solver
 * realized it, by the top's momentum, M dz' = int mount + int drive - F_N elapsed.
 * With the rod's impulses (its own momentum's) the two bodies' momentum then
 * balances to rounding; how close the mount's is to int(-K z - C z') is the
 * solver's accuracy (docs/coupling.md). */
void model_step_end(Model *m, double elapsed)
{
    const TableParams *p = &m->params;
    const double omega = TWO_PI * p->frequency, t0 = m->step_time, t1 = t0 + elapsed;
    double drive_mean = 0, mount_mean = 0;
    if (elapsed > 0) {
        /* omega elapsed may underflow to 0 for a tiny step: the mean is then the drive at t0,
         * the quotient's limit (0 when omega = 0), not a division by zero */
        const double phase = omega * elapsed;
        drive_mean = phase > 0 ? p->F0 * (cos(omega * t0) - cos(omega * t1)) / phase : p->F0 * sin(omega * t0);
        mount_mean = p->M * (m->x[TABLE_V] - m->step_velocity) / elapsed - drive_mean + m->F_N;
    }
    m->step_mean[TABLE_MEAN_MOUNT] = mount_mean;
    m->step_mean[TABLE_MEAN_DRIVE] = drive_mean;
    m->means_held = true;
    model_touch(m);
}

/* ------------------------------------------------------- modes, events */

void model_start(Model *m, double time, char *text, size_t size)
{
    (void)time;   /* no modes, no event record */
    snprintf(text, size, "table starts at position = %g m, velocity = %g m/s (no modes)", m->x[TABLE_Z],
             m->x[TABLE_V]);
}

/* ------------------------------------------------ partial derivatives */

/* d der(velocity) / d known: the acceleration a = (-K z - C v + F0 s - F_N) / M
 * with s = sin(2 pi f t). */
static double acceleration_partial(const Model *m, unsigned int known)
{
    const TableParams *p = &m->params;
    const double omega = TWO_PI * p->frequency, t = m->time;
    switch (known) {
    case VR_POSITION: return -p->K / p->M;
    case VR_VELOCITY: return -p->C / p->M;
    case VR_F_N: return -1 / p->M;
    case VR_M: return -m->dx[TABLE_V] / p->M;
    case VR_K: return -m->x[TABLE_Z] / p->M;
    case VR_C: return -m->x[TABLE_V] / p->M;
    case VR_F0: return sin(omega * t) / p->M;
    case VR_FREQUENCY: return p->F0 * cos(omega * t) * TWO_PI * t / p->M;
    default: return 0;   /* F_T, belt_speed */
    }
}

/* d drive_force / d known, drive_force = F0 sin(2 pi f t). */
static double drive_partial(const Model *m, unsigned int known)
{
    const TableParams *p = &m->params;
    const double omega = TWO_PI * p->frequency, t = m->time;
    return known == VR_F0 ? sin(omega * t) : known == VR_FREQUENCY ? p->F0 * cos(omega * t) * TWO_PI * t : 0;
}

/* d mount_force / d known, mount_force = -K z - C v. */
static double mount_partial(const Model *m, unsigned int known)
{
    const TableParams *p = &m->params;
    switch (known) {
    case VR_POSITION: return -p->K;
    case VR_VELOCITY: return -p->C;
    case VR_K: return -m->x[TABLE_Z];
    case VR_C: return -m->x[TABLE_V];
    default: return 0;
    }
}

const char *model_calculated_partial(Model *m, unsigned int unknown, unsigned int known, double *value)
{
    model_update(m);
    const TableParams *p = &m->params;
    const double z = m->x[TABLE_Z], v = m->x[TABLE_V];
    double d = 0;
    switch (unknown) {
    case VR_DER_POSITION: d = known == VR_VELOCITY; break;
    case VR_DER_VELOCITY: d = acceleration_partial(m, known); break;
    case VR_BELT_VELOCITY: d = known == VR_BELT_SPEED; break;
    case VR_DRIVE_FORCE: d = drive_partial(m, known); break;
    case VR_ENERGY:
        d = known == VR_POSITION ? p->K * z
            : known == VR_VELOCITY ? p->M * v
            : known == VR_M ? 0.5 * v * v
            : known == VR_K ? 0.5 * z * z
            : 0;
        break;
    case VR_BELT_POWER: d = known == VR_F_T ? -p->belt_speed : known == VR_BELT_SPEED ? -m->F_T : 0; break;
    case VR_MOUNT_FORCE: d = mount_partial(m, known); break;
    /* a step mean is the past's in Co-Simulation; in Model Exchange the force itself */
    case VR_MOUNT_FORCE_MEAN: d = m->means_held ? 0 : mount_partial(m, known); break;
    case VR_DRIVE_FORCE_MEAN: d = m->means_held ? 0 : drive_partial(m, known); break;
    default: return "the unknown has no partial derivative";
    }
    *value = d;
    return NULL;
}

/* ------------------------------------------------------ FMU state fields */

const char *model_internals_implausible(const Model *m)
{
    if (!isfinite(m->step_mean[TABLE_MEAN_MOUNT])) return "step_mean_mount";
    if (!isfinite(m->step_mean[TABLE_MEAN_DRIVE])) return "step_mean_drive";
    if (!isfinite(m->step_time) || !isfinite(m->step_velocity)) return "step_time";
    return NULL;
}
