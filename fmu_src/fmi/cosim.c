/* SPDX-License-Identifier: BSD-2-Clause */
/* CVODE over the model (see cosim.h), SUNDIALS 6 or 7 (sundials_compat.h).
 * Without HAVE_CVODE (SUNDIALS not linked) this file is empty and
 * Co-Simulation steps say so. */
#include "cosim.h"
#include "cvode_build.h" /* HAVE_CVODE also where a source FMU carries CVODE */

#ifdef HAVE_CVODE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "step_end.h"
#include "sundials_compat.h"

struct CoSim {
    SUNContext ctx;
    N_Vector y, abstol;
    SUNMatrix A;
    SUNLinearSolver solver;
    void *cvode;
    const Model *model;  /* parameters and mode for the callbacks */
    SundialsError error; /* CVODE's last error */
    bool started;        /* cosim_start succeeded: cosim_advance may run */
    long steps, rhs;     /* counted over every advance (cosim_counts) */
};

static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    const Model *m = ((CoSim *)data)->model;
    double *dx = N_VGetArrayPointer(ydot);
    model_derivatives_at(m, t, N_VGetArrayPointer(y), dx);
    for (int i = 0; i < MODEL_NX; ++i)
        if (!isfinite(dx[i])) return -1;
    return 0;
}

static int roots(sunrealtype t, N_Vector y, sunrealtype *z, void *data)
{
    const Model *m = ((CoSim *)data)->model;
    model_indicators_at(m, t, N_VGetArrayPointer(y), z);
    return 0;
}

static int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *data, N_Vector t1, N_Vector t2,
                    N_Vector t3)
{
    (void)fy, (void)t1, (void)t2, (void)t3;
    const Model *m = ((CoSim *)data)->model;
    double Jr[MODEL_NX][MODEL_NX];
    model_jacobian_at(m, t, N_VGetArrayPointer(y), Jr);
    for (int i = 0; i < MODEL_NX; ++i)
        for (int j = 0; j < MODEL_NX; ++j) SM_ELEMENT_D(J, i, j) = Jr[i][j];
    return 0;
}

CoSim *cosim_new(void)
{
    return calloc(1, sizeof(CoSim));
}

/* Frees whatever was made (all of it or part of a failed set-up), leaving an
 * empty CoSim that the next cosim_start sets up afresh. */
static void destroy(CoSim *cs)
{
    if (cs->cvode) CVodeFree(&cs->cvode);
    if (cs->solver) SUNLinSolFree(cs->solver);
    if (cs->A) SUNMatDestroy(cs->A);
    if (cs->y) N_VDestroy(cs->y);
    if (cs->abstol) N_VDestroy(cs->abstol);
    if (cs->ctx) sundials_context_free(&cs->ctx); /* last: the others were made in it */
    memset(cs, 0, sizeof *cs);
}

void cosim_free(CoSim *cs)
{
    if (!cs) return;
    destroy(cs);
    free(cs);
}

/* Makes and configures CVODE; NULL on success, else the call that failed
 * (what was made by then stays in cs for destroy). */
static const char *create(CoSim *cs, double t)
{
    if (SUNContext_Create(SUN_COMM_NULL, &cs->ctx) != 0) return "SUNContext_Create";
    if (sundials_quiet_logger(cs->ctx)) return "SUNLogger_Create";
    /* Adams, not BDF: between events the rod is smooth on the contact's own time
     * scale eps (stiff only across it), where Adams' higher orders (to 12, BDF 5)
     * take fewer steps for the same error (docs/fmu.md); Newton with the Jacobian
     * keeps large delta stable. */
    if (!(cs->cvode = CVodeCreate(CV_ADAMS, cs->ctx))) return "CVodeCreate";
    if (sundials_catch_errors(cs->ctx, cs->cvode, &cs->error)) return "setting CVODE's error handler";
    if (!(cs->y = N_VNew_Serial(MODEL_NX, cs->ctx))) return "N_VNew_Serial";
    if (!(cs->abstol = N_VNew_Serial(MODEL_NX, cs->ctx))) return "N_VNew_Serial";
    if (!(cs->A = SUNDenseMatrix(MODEL_NX, MODEL_NX, cs->ctx))) return "SUNDenseMatrix";
    if (!(cs->solver = SUNLinSol_Dense(cs->y, cs->A, cs->ctx))) return "SUNLinSol_Dense";
    N_VConst(0.0, cs->y); /* CVodeInit copies it; cosim_start sets the state */
    if (CVodeInit(cs->cvode, rhs, t, cs->y) != CV_SUCCESS) return "CVodeInit";
    if (CVodeSetUserData(cs->cvode, cs) != CV_SUCCESS) return "CVodeSetUserData";
    if (CVodeRootInit(cs->cvode, MODEL_NZ, roots) != CV_SUCCESS) return "CVodeRootInit";
    if (CVodeSetLinearSolver(cs->cvode, cs->solver, cs->A) != CV_SUCCESS) return "CVodeSetLinearSolver";
    if (CVodeSetJacFn(cs->cvode, jacobian) != CV_SUCCESS) return "CVodeSetJacFn";
    if (CVodeSetNoInactiveRootWarn(cs->cvode) != CV_SUCCESS) return "CVodeSetNoInactiveRootWarn";
    return NULL;
}

bool cosim_start(CoSim *cs, Model *m, double t, double rtol, char *err, size_t n)
{
    cs->model = m;
    cs->started = false;
    cs->error.text[0] = '\0';
    if (!cs->cvode) { /* first start, or the last one failed and destroyed what it made */
        const char *failed = create(cs, t);
        if (failed) {
            snprintf(err, n, "CVODE could not be set up: %s failed (%s)", failed,
                     cs->error.text[0] ? cs->error.text : "out of memory");
            destroy(cs);
            return false;
        }
    }
    double nominal[MODEL_NX];
    model_get_nominals(m, nominal);
    double *y = N_VGetArrayPointer(cs->y), *abstol = N_VGetArrayPointer(cs->abstol);
    model_get_states(m, y);
    for (int i = 0; i < MODEL_NX; ++i) abstol[i] = rtol * nominal[i];
    if (CVodeReInit(cs->cvode, t, cs->y) != CV_SUCCESS || CVodeSVtolerances(cs->cvode, rtol, cs->abstol) != CV_SUCCESS) {
        snprintf(err, n, "CVODE could not restart at t = %g: %s", t, cs->error.text);
        return false;
    }
    cs->started = true;
    return true;
}

/* CVODE's step and right-hand side counts so far; false, with a message, if it cannot say. */
static bool count_steps(CoSim *cs, long *steps, long *rhs, char *err, size_t n)
{
    if (CVodeGetNumSteps(cs->cvode, steps) == CV_SUCCESS && CVodeGetNumRhsEvals(cs->cvode, rhs) == CV_SUCCESS)
        return true;
    snprintf(err, n, "CVODE could not count its steps: CVodeGetNumSteps or CVodeGetNumRhsEvals failed (%s)", cs->error.text);
    return false;
}

void cosim_counts(const CoSim *cs, long *steps, long *rhs)
{
    *steps = cs ? cs->steps : 0;
    *rhs = cs ? cs->rhs : 0;
}

CoSimResult cosim_advance(CoSim *cs, Model *m, double *t, double t_end, long *steps_left, char *err, size_t n)
{
    cs->model = m;
    cs->error.text[0] = '\0';
    if (!cs->started) {
        snprintf(err, n, "CVODE is not set up (its last start failed)");
        return COSIM_FAILED;
    }
    /* CVODE's own time is where its start or last advance left it: a hand-over or a restart may
     * have put it on t_end, and a master's communication point (*t) may lie a few ulps behind it.
     * CVODE refuses a stop time it has reached; the step has nothing left to integrate. */
    sunrealtype own = *t;
    if (CVodeGetCurrentTime(cs->cvode, &own) != CV_SUCCESS) {
        snprintf(err, n, "CVODE could not say its time: CVodeGetCurrentTime failed (%s)", cs->error.text);
        return COSIM_FAILED;
    }
    if (step_end_reached(fmax(*t, own), t_end)) {
        *t = t_end;
        return COSIM_REACHED;
    }
    if (*steps_left <= 0) return COSIM_BUDGET;
    sunrealtype reached = *t;
    if (CVodeSetStopTime(cs->cvode, t_end) != CV_SUCCESS) {
        snprintf(err, n, "CVODE refused the stop time %.17g: %s", t_end, cs->error.text);
        return COSIM_FAILED;
    }
    if (CVodeSetMaxNumSteps(cs->cvode, *steps_left) != CV_SUCCESS) {
        snprintf(err, n, "CVODE refused its step budget: CVodeSetMaxNumSteps failed (%s)", cs->error.text);
        return COSIM_FAILED;
    }
    long before = 0, after = 0, rhs_before = 0, rhs_after = 0;
    if (!count_steps(cs, &before, &rhs_before, err, n)) return COSIM_FAILED;
    const int flag = CVode(cs->cvode, t_end, cs->y, &reached, CV_NORMAL);
    if (!count_steps(cs, &after, &rhs_after, err, n)) return COSIM_FAILED;
    *steps_left -= after - before;
    cs->steps += after - before;
    cs->rhs += rhs_after - rhs_before;
    /* CV_TOO_MUCH_WORK: the budget is spent, and CVODE stands at `reached` with a valid state */
    const bool spent = flag == CV_TOO_MUCH_WORK;
    if (flag < 0 && !spent) {
        snprintf(err, n, "CVODE failed at t = %.17g: %s", reached, cs->error.text);
        return COSIM_FAILED;
    }
    model_set_states(m, N_VGetArrayPointer(cs->y));
    *t = spent || flag == CV_ROOT_RETURN ? reached : t_end;
    return spent ? COSIM_BUDGET : flag == CV_ROOT_RETURN ? COSIM_EVENT : COSIM_REACHED;
}
#else
typedef int cosim_needs_HAVE_CVODE; /* ISO C wants something in a translation unit */
#endif
