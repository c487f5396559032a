/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRodSI's moving floor, in a header of its own below rod_si.c (the
 * scaling, the inputs) and rod_si_partials.c (d / d w_floor), so that neither
 * calls the other. */
#ifndef SI_FLOOR_H
#define SI_FLOOR_H

#include "model.h"

/* How long the floor has moved at w_floor since y_floor was set: in
 * Co-Simulation from the first step on (model_step_begin), 0 in Model Exchange. */
static inline double si_floor_elapsed(const Model *m, double time)
{
    return m->floor_moves ? time - m->t_floor : 0.0;
}

#endif
