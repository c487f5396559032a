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
} Erk;

/* (Re)starts at time t from the model's state, with tolerances rtol and
 * rtol * nominal (CVODE's meaning: cosim_start). */
void erk_start(Erk *e, const Model *m, double t, double rtol);

/* Integrates from *t towards t_end as cosim_advance does (stopping exactly at
 * t_end, at the first root of an indicator, or when *steps_left runs out),
 * the model's state and *t following. */
ErkResult erk_advance(Erk *e, Model *m, double *t, double t_end, long *steps_left);

#endif
