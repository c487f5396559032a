/* SPDX-License-Identifier: BSD-2-Clause */
/* One FMU binary, FMI 2.0 or 3.0, behind the few calls the platform driver
 * makes (platform_driver.c), loaded as an importer on that platform loads it:
 * LoadLibrary on Windows, dlopen elsewhere. */
#ifndef PLATFORM_FMI_H
#define PLATFORM_FMI_H

#include <stdbool.h>
#include <stddef.h>

typedef struct Fmu Fmu;

/* Loads the library at PATH (FMI VERSION 2 or 3); NULL with a message on stderr. */
Fmu *fmu_load(const char *path, int version);
void fmu_unload(Fmu *fmu);

/* Each call returns the FMI status (0 OK, 1 Warning, 2 Discard, 3 Error, 4 Fatal). */
int fmu_instantiate(Fmu *fmu, const char *token, bool cosimulation);
void fmu_free_instance(Fmu *fmu);
int fmu_initialize(Fmu *fmu, double start, double stop);
int fmu_set_reals(Fmu *fmu, const unsigned *vr, size_t n, const double *values);
int fmu_get_reals(Fmu *fmu, const unsigned *vr, size_t n, double *values);
int fmu_do_step(Fmu *fmu, double t, double h);

/* Model Exchange. After fmu_initialize the instance is in Event Mode. */
int fmu_update_discrete(Fmu *fmu, bool *again, bool *terminate);
int fmu_enter_continuous(Fmu *fmu);
int fmu_enter_event(Fmu *fmu);
int fmu_set_time(Fmu *fmu, double t);
int fmu_set_states(Fmu *fmu, const double *x, size_t n);
int fmu_get_states(Fmu *fmu, double *x, size_t n);
int fmu_get_derivatives(Fmu *fmu, double *dx, size_t n);
int fmu_get_indicators(Fmu *fmu, double *z, size_t n);
int fmu_completed_step(Fmu *fmu, bool *enter_event, bool *terminate);

#endif
