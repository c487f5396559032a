/* SPDX-License-Identifier: BSD-2-Clause */
/* Linked into a test build of the FMU with -Wl,--wrap=NAME for each SUNDIALS
 * call below: the call chosen by fault_fail_sundials_call returns the failure
 * SUNDIALS documents for it (NULL, or a negative flag) instead of running.
 * The only symbol of that build besides the fmi2* functions.
 *
 * Why not fail malloc itself: SUNDIALS does not survive that. 6.4's N_VClone
 * and 7.1's SUNMatClone dereference the NULL a failed clone returns, and both
 * versions' SUNHashMap_New (the context's logger) tests map for NULL where it
 * means *map; so the failures are injected where cosim.c meets SUNDIALS. */
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "sundials_compat.h"

static long count, fail_at;

/* From now on the wrapped call numbered n (1: the next) fails, none if n = 0.
 * Returns how many wrapped calls were made since the last call. */
__attribute__((visibility("default"))) long fault_fail_sundials_call(long n)
{
    const long made = count;
    count = 0;
    fail_at = n;
    return made;
}

static int fails(void)
{
    return ++count == fail_at;
}

/* NAME's wrapper: FAILURE if chosen, else the real NAME(ARGS). */
#define WRAP(type, name, params, args, failure)     \
    type __real_##name params;                      \
    type __wrap_##name params;                      \
    type __wrap_##name params                       \
    {                                               \
        return fails() ? (failure) : __real_##name args; \
    }

static int no_context(SUNContext *ctx)
{
    *ctx = NULL;
    return -1;
}

WRAP(int, SUNContext_Create, (SUNComm comm, SUNContext *ctx), (comm, ctx), no_context(ctx))
WRAP(void *, CVodeCreate, (int lmm, SUNContext ctx), (lmm, ctx), NULL)
WRAP(N_Vector, N_VNew_Serial, (sunindextype n, SUNContext ctx), (n, ctx), NULL)
WRAP(SUNMatrix, SUNDenseMatrix, (sunindextype m, sunindextype n, SUNContext ctx), (m, n, ctx), NULL)
WRAP(SUNLinearSolver, SUNLinSol_Dense, (N_Vector y, SUNMatrix A, SUNContext ctx), (y, A, ctx), NULL)
WRAP(int, CVodeInit, (void *cv, CVRhsFn f, sunrealtype t0, N_Vector y0), (cv, f, t0, y0), CV_MEM_FAIL)
WRAP(int, CVodeSetUserData, (void *cv, void *data), (cv, data), CV_MEM_NULL)
WRAP(int, CVodeRootInit, (void *cv, int nrtfn, CVRootFn g), (cv, nrtfn, g), CV_MEM_FAIL)
WRAP(int, CVodeSetLinearSolver, (void *cv, SUNLinearSolver LS, SUNMatrix A), (cv, LS, A), CVLS_MEM_FAIL)
WRAP(int, CVodeSetJacFn, (void *cv, CVLsJacFn jac), (cv, jac), CVLS_LMEM_NULL)
WRAP(int, CVodeSetMaxNumSteps, (void *cv, long mxsteps), (cv, mxsteps), CV_ILL_INPUT)
WRAP(int, CVodeSetNoInactiveRootWarn, (void *cv), (cv), CV_MEM_NULL)
WRAP(int, CVodeReInit, (void *cv, sunrealtype t0, N_Vector y0), (cv, t0, y0), CV_ILL_INPUT)
WRAP(int, CVodeSVtolerances, (void *cv, sunrealtype rtol, N_Vector atol), (cv, rtol, atol), CV_ILL_INPUT)
WRAP(int, CVodeSetStopTime, (void *cv, sunrealtype tstop), (cv, tstop), CV_ILL_INPUT)
WRAP(int, CVodeGetNumSteps, (void *cv, long *nsteps), (cv, nsteps), CV_MEM_NULL)
