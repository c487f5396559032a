/* SPDX-License-Identifier: BSD-2-Clause */
/* Co-Simulation's fast integrator: the explicit embedded Runge-Kutta pair of
 * Dormand and Prince, 5(4), with its continuous extension (dense output),
 * over the model of model.h. Between events a body in flight or in a short
 * contact is smooth on the contact's own time scale eps, stiff only while the
 * contact lasts (O(eps ln 1/eps) in an IWC): steps of O(eps) cross it in tens
 * of steps, each six right-hand sides and no linear algebra. Events are
 * located on the dense output; a sustained contact (stiffness test) or
 * anything the pair cannot do is handed over to CVODE (cosim.c), which
 * integrates as before. Knows the model, not FMI nor CVODE. */
#ifndef EXPLICIT_RK_H
#define EXPLICIT_RK_H

#include <stdbool.h>
#include <stddef.h>

#include "model.h"

/* ERK_REACHED: at t_end; ERK_EVENT: at the first root of an event indicator
 * (the model's state is there); ERK_BUDGET: the steps allowed ran out;
 * ERK_HAND_OVER: the trajectory needs the implicit solver from the time reached
 * (a sustained stiff phase, a step below the time's resolution, a value not
 * finite): the model's state is valid there. */
typedef enum { ERK_REACHED, ERK_EVENT, ERK_BUDGET, ERK_HAND_OVER } ErkResult;

typedef struct {
    double rtol, atol[MODEL_NX];
    double y[MODEL_NX], f[MODEL_NX]; /* state and right-hand side at the time reached (first same as last) */
    double z[MODEL_NZ + 1];          /* the indicators there (+1: a model may have none) */
    double h;                        /* the step to try next; 0 after a start: chosen from the scales */
    int stiff_steps;                 /* accepted steps held at the stability bound, net of easy ones */
    const char *why;                 /* ERK_HAND_OVER's reason, for the event log */
    long steps, rhs;                 /* counts since the instance was made (diagnostics) */
    long flight_samples;             /* closed-form flight: samples and root-finding evaluations */
} Erk;

/* (Re)starts at time t from the model's state, with tolerances rtol and
 * 0.1 rtol * nominal (a tenth of CVODE's absolute part: explicit_rk.c says why). */
void erk_start(Erk *e, const Model *m, double t, double rtol);

/* Integrates from *t towards t_end as cosim_advance does (stopping exactly at
 * t_end, at the first root of an indicator, or when *steps_left runs out),
 * the model's state and *t following. */
ErkResult erk_advance(Erk *e, Model *m, double *t, double t_end, long *steps_left);

/* True if the n values are all finite (a right-hand side, a state). */
bool erk_all_finite(const double *v, int n);

/* ERK_HAND_OVER from the state e->y (the last one reached), `why` kept for the event log. */
ErkResult erk_hand_over(Erk *e, Model *m, const char *why);

/* A path through one interval (t, t + h]: the state at th in [0, 1], exactly the interval's
 * end at th = 1 (a step's dense output, a closed-form flight). */
typedef void (*ErkStateAt)(const void *path, double th, double x[MODEL_NX]);

/* True if an indicator has a root between the values lo and hi (CVODE's rule: a change of
 * sign, or a 0 reached from a value that was not 0). */
bool erk_any_crossed(const double lo[], const double hi[]);

/* The first root of the model's indicators on `path` over (t, t + h] where they go from z_lo
 * to z_hi (erk_any_crossed), located to 100 ulps of the time by the Illinois method over all
 * indicators at once (as CVODE's cvRootfind), within a bound: *t_root is the bracket's right
 * end, where an indicator has changed sign, and x its state. */
void erk_locate_root(const Model *m, double t, double h, const double z_lo[], const double z_hi[],
                     ErkStateAt path_at, const void *path, double *t_root, double x[MODEL_NX]);

#endif
