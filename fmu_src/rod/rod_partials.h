/* SPDX-License-Identifier: BSD-2-Clause */
/* Analytic partial derivatives of the rod's smooth branches:
 * what fmi2GetDirectionalDerivative answers, for every (unknown, known) pair
 * that modelDescription.xml's ModelStructure declares. Physics only, no FMI. */
#ifndef ROD_PARTIALS_H
#define ROD_PARTIALS_H

#include "rod.h"

enum { ROD_P_ALPHA, ROD_P_MU, ROD_P_DELTA, ROD_P_EPSILON, ROD_P_KAPPA, ROD_P_BETA, ROD_NP };  /* parameters */
enum { ROD_L_FX, ROD_L_FY, ROD_L_TAU, ROD_NL };  /* applied loads (RodParams f_x, f_y, tau) */

/* Partial derivatives of mode m's smooth branch at x: of the state derivatives and of the
 * outputs, with respect to the states, the parameters and the applied loads. */
typedef struct {
    double dx_x[ROD_NX][ROD_NX], dx_p[ROD_NX][ROD_NP], dx_l[ROD_NX][ROD_NL];
    double out_x[ROD_NOUT][ROD_NX], out_p[ROD_NOUT][ROD_NP], out_l[ROD_NOUT][ROD_NL];
} RodPartials;

void rod_partials(const RodParams *p, ContactMode m, const double x[ROD_NX], RodPartials *d);

#endif
