/* The two places where SUNDIALS 6 and 7 differ for a CVODE user like us,
 * switched on SUNDIALS' own version macro here and nowhere else: the
 * communicator a context takes, and how errors are reported (6: a handler
 * per CVODE memory; 7: a stack of handlers on the context, whose default
 * prints on stderr). Everything else is written against SUNDIALS 7's names
 * (sunrealtype, SUNComm, SUN_COMM_NULL), which 6.4 has or gets here. */
#ifndef SUNDIALS_COMPAT_H
#define SUNDIALS_COMPAT_H

#include <stdio.h>

#include <cvode/cvode.h>
#include <sundials/sundials_config.h>

/* CVODE's last error, kept for the caller's own log instead of stderr. */
typedef struct {
    char text[256];
} SundialsError;

static inline void sundials_error_keep(SundialsError *e, int code, const char *function, const char *msg)
{
    if (code < 0) snprintf(e->text, sizeof e->text, "%s (%d): %s", function, code, msg);
}

#if SUNDIALS_VERSION_MAJOR >= 7
static inline void sundials_error_handler(int line, const char *function, const char *file, const char *msg,
                                          SUNErrCode code, void *error, SUNContext ctx)
{
    (void)line, (void)file, (void)ctx;
    sundials_error_keep(error, code, function, msg);
}

/* Errors of everything made in ctx go to *error only. 0 on success. */
static inline int sundials_catch_errors(SUNContext ctx, void *cvode, SundialsError *error)
{
    (void)cvode;
    return SUNContext_ClearErrHandlers(ctx) == SUN_SUCCESS &&
                   SUNContext_PushErrHandler(ctx, sundials_error_handler, error) == SUN_SUCCESS
               ? 0
               : -1;
}
#else
typedef void *SUNComm; /* 6: the context's communicator is a void * */
#define SUN_COMM_NULL NULL

static inline void sundials_error_handler(int code, const char *module, const char *function, char *msg, void *error)
{
    (void)module;
    sundials_error_keep(error, code, function, msg);
}

/* Errors of this CVODE memory go to *error only. 0 on success. */
static inline int sundials_catch_errors(SUNContext ctx, void *cvode, SundialsError *error)
{
    (void)ctx;
    return CVodeSetErrHandlerFn(cvode, sundials_error_handler, error) == CV_SUCCESS ? 0 : -1;
}
#endif

#endif
