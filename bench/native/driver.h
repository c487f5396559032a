/* SPDX-License-Identifier: BSD-2-Clause */
/* One instance of the PainleveRod FMU under FMI 2.0 Model Exchange, integrated
 * case by case by SUNDIALS CVODE set up as fmpy's CVodeSolver (native_me.c). */
#ifndef DRIVER_H
#define DRIVER_H

#include <stddef.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "cases.h"
#include "fmu_import.h"
#include "sundials_compat.h" /* fmu_src/fmi's: SUNDIALS 6 or 7 */

/* The FMU variables a case sets, in this order (fmpy's start_values of Case). */
enum { P_ALPHA, P_MU, P_DELTA, P_EPSILON, P_X, P_V, P_Y, P_W, P_THETA, P_PHI, N_SET };
static const char *const SET_NAME[N_SET] = { "alpha", "mu", "delta", "epsilon", "x", "v", "y", "w", "theta", "phi" };

typedef struct {
    double w, v, theta, phi, t_return;
    int iwc;
    long nsteps, nfev, njev, ngev, nevents;
} Result;


typedef struct {
    FmuImport fmu;
    fmi2CallbackFunctions callbacks;
    fmi2Component c;
    int used; /* the instance has run a case: the next one starts with fmi2Reset */
    unsigned int vr_set[N_SET], vr_contact, vr_mode;
    size_t ix_y, ix_w, ix_v, ix_theta, ix_phi; /* in the state vector */
    char fmu_message[1024];                    /* the FMU's last error message */
    /* CVODE, made once and re-initialized for every case and event */
    SUNContext ctx;
    N_Vector y, abstol;
    SUNMatrix A;
    SUNLinearSolver solver;
    void *cvode;
    int analytic;
    SundialsError cvode_error; /* CVODE's last error */
    const char *failed_call; /* the FMI call a CVODE callback saw fail */
    double *nominal;
} Driver;

/* Loads the FMU at path (an extracted FMU or its library), instantiates it and
 * sets CVODE up; 0 with a message otherwise (driver_close is safe in both cases). */
int driver_open(Driver *d, const char *path, int analytic, char *err, size_t n);
void driver_close(Driver *d);

/* Case k at relative tolerance rtol, as the harness's fast loop runs it: fmi2Reset
 * between runs, stopped where the rod is back at y = 0 moving up. */
int run_case(Driver *d, const Case *k, double rtol, Result *r, char *err, size_t n);

#endif
