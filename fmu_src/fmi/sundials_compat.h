/* SPDX-License-Identifier: BSD-2-Clause */
/* The three places where SUNDIALS 6 and 7 differ for a CVODE user like us,
 * switched on SUNDIALS' own version macro here and nowhere else: the
 * communicator a context takes, how errors are reported (6: a handler
 * per CVODE memory; 7: a stack of handlers on the context, whose default
 * prints on stderr), and warnings (6: the same handler; 7: the context's
 * logger, whose default prints on stdout). Everything else is written against SUNDIALS 7's names
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

/* The context's logger writes nowhere: a warning ("t + h = t on the next step")
 * on the importer's stdout is noise in its output, and what matters of it comes
 * with the failure, through the handler above. (A new logger's outputs are
 * stdout and stderr, and a file name is the only way to change them.) 0 on
 * success; the logger is the caller's, freed by sundials_context_free. */
static inline int sundials_quiet_logger(SUNContext ctx)
{
#ifdef _WIN32
    const char *nowhere = "NUL";
#else
    const char *nowhere = "/dev/null";
#endif
    SUNLogger logger = NULL;
    if (SUNLogger_Create(SUN_COMM_NULL, 0, &logger) != SUN_SUCCESS) return -1;
    if (SUNLogger_SetErrorFilename(logger, nowhere) != SUN_SUCCESS ||
        SUNLogger_SetWarningFilename(logger, nowhere) != SUN_SUCCESS ||
        SUNContext_SetLogger(ctx, logger) != SUN_SUCCESS) {
        SUNLogger_Destroy(&logger);
        return -1;
    }
    return 0;
}

/* Frees the context, then the logger it holds but does not own. */
static inline void sundials_context_free(SUNContext *ctx)
{
    SUNLogger logger = NULL;
    SUNContext_GetLogger(*ctx, &logger);
    SUNContext_Free(ctx);
    if (logger) SUNLogger_Destroy(&logger);
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

/* 6 hands warnings to the handler above too (which keeps errors only). */
static inline int sundials_quiet_logger(SUNContext ctx)
{
    (void)ctx;
    return 0;
}

static inline void sundials_context_free(SUNContext *ctx)
{
    SUNContext_Free(ctx);
}
#endif

#endif
