/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRodSI's partial derivatives: its SI unknowns with respect to its SI
 * parameters, inputs and states, by the chain rule through the scaling of
 * rod_si.c from the rod's own analytic partials (rod_partials.c), or directly
 * where the unknown is SI kinematics (energy, centre of mass, gap, slip). */
#ifndef ROD_SI_PARTIALS_H
#define ROD_SI_PARTIALS_H

#include "model.h"

/* *value = d unknown / d known at m (derived values and m->partials up to date); NULL on
 * success, else why the pair has none (a variable the SI rod's partials do not know). */
const char *si_partial(const Model *m, unsigned int unknown, unsigned int known, double *value);

#endif
