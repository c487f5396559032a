/* SPDX-License-Identifier: BSD-2-Clause */
/* ShakerTable's metadata (see models/PainleveRod/config.h for the pattern): a table top
 * of mass M on a spring K and a damper C, vertical only, driven by
 * F0 sin(2 pi frequency t) and loaded by the rod's normal force F_N:
 *     M z'' = -K z - C z' + F0 sin(2 pi frequency t) - F_N,
 * z measured from the static equilibrium (gravity is in it). Its surface moves
 * horizontally at belt_speed; the rod's tangential force F_T goes into the
 * table's horizontal guide and the belt's drive. The variable list's order is
 * that of its modelDescription.xml, in this folder (tests/coupling/test_shaker_table_fmi.py
 * checks the two agree). */
#ifndef CONFIG_H
#define CONFIG_H

#define MODEL_IDENTIFIER ShakerTable
#define MODEL_NAME "ShakerTable"
#define MODEL_NX 2
#define MODEL_NZ 0 /* no modes, no events */

/* The optional parts it provides (model.h): a drive force that is a function of time,
 * the step means mount_force_mean and drive_force_mean. */
#define MODEL_SET_TIME
#define MODEL_STEP_MEANS

enum { TABLE_Z, TABLE_V };                                           /* the states */
enum { TABLE_OUT_DRIVE, TABLE_OUT_ENERGY, TABLE_OUT_BELT_POWER, TABLE_OUT_MOUNT, TABLE_OUT_MOUNT_MEAN,
       TABLE_OUT_DRIVE_MEAN, TABLE_NOUT };                           /* derived outputs */
enum { TABLE_MEAN_MOUNT, TABLE_MEAN_DRIVE };                         /* the step means' order */

/* Bounds that keep every derived value (K z^2, M v^2, F_T belt_speed) finite. */
#define STATE_BOUND 1e6
#define FORCE_BOUND 1e9

/* VARIABLE(ID, name, type, kind, field, min, max) as in models/PainleveRod/config.h;
 * INPUT: set by the master at any time (causality input). */
#define MODEL_VARIABLES(VARIABLE)                                                          \
    VARIABLE(M, "M", REAL, PARAMETER, params.M, 1e-6, 1e9)                                 \
    VARIABLE(K, "K", REAL, PARAMETER, params.K, 0, 1e12)                                   \
    VARIABLE(C, "C", REAL, PARAMETER, params.C, 0, 1e9)                                    \
    VARIABLE(F0, "F0", REAL, PARAMETER, params.F0, -FORCE_BOUND, FORCE_BOUND)              \
    VARIABLE(FREQUENCY, "frequency", REAL, PARAMETER, params.frequency, 0, 1e6)            \
    VARIABLE(BELT_SPEED, "belt_speed", REAL, PARAMETER, params.belt_speed, -1e3, 1e3)      \
    VARIABLE(F_N, "F_N", REAL, INPUT, F_N, -FORCE_BOUND, FORCE_BOUND)                      \
    VARIABLE(F_T, "F_T", REAL, INPUT, F_T, -FORCE_BOUND, FORCE_BOUND)                      \
    VARIABLE(POSITION, "position", REAL, STATE, x[TABLE_Z], -STATE_BOUND, STATE_BOUND)     \
    VARIABLE(VELOCITY, "velocity", REAL, STATE, x[TABLE_V], -STATE_BOUND, STATE_BOUND)     \
    VARIABLE(DER_POSITION, "der(position)", REAL, CALCULATED, dx[TABLE_Z], 0, 0)           \
    VARIABLE(DER_VELOCITY, "der(velocity)", REAL, CALCULATED, dx[TABLE_V], 0, 0)           \
    VARIABLE(BELT_VELOCITY, "belt_velocity", REAL, CALCULATED, params.belt_speed, 0, 0)    \
    VARIABLE(DRIVE_FORCE, "drive_force", REAL, CALCULATED, out[TABLE_OUT_DRIVE], 0, 0)     \
    VARIABLE(ENERGY, "energy", REAL, CALCULATED, out[TABLE_OUT_ENERGY], 0, 0)              \
    VARIABLE(BELT_POWER, "belt_power", REAL, CALCULATED, out[TABLE_OUT_BELT_POWER], 0, 0)   \
    VARIABLE(MOUNT_FORCE, "mount_force", REAL, CALCULATED, out[TABLE_OUT_MOUNT], 0, 0)     \
    VARIABLE(MOUNT_FORCE_MEAN, "mount_force_mean", REAL, CALCULATED, out[TABLE_OUT_MOUNT_MEAN], 0, 0) \
    VARIABLE(DRIVE_FORCE_MEAN, "drive_force_mean", REAL, CALCULATED, out[TABLE_OUT_DRIVE_MEAN], 0, 0)

/* Beyond its variables an FMU state carries the step means (Co-Simulation). */
#define MODEL_INTERNALS(INTERNAL)                                      \
    INTERNAL("step_mean_mount", step_mean[TABLE_MEAN_MOUNT], REAL) \
    INTERNAL("step_mean_drive", step_mean[TABLE_MEAN_DRIVE], REAL) \
    INTERNAL("step_time", step_time, REAL)                         \
    INTERNAL("step_velocity", step_velocity, REAL)                 \
    INTERNAL("means_held", means_held, BOOLEAN)

typedef struct {
    double M, K, C;            /* mass [kg], stiffness [N/m], damping [N s/m] */
    double F0, frequency;      /* drive amplitude [N] and frequency [Hz] */
    double belt_speed;         /* horizontal surface speed [m/s] */
} TableParams;

/* The model's data: plain, no pointers, so an FMU state may hold a copy.
 * `time` is the instance's (model_set_time); derived values are cached for
 * it and the state until a change marks them stale. */
typedef struct {
    TableParams params;
    double F_N, F_T;           /* inputs [N] */
    double x[MODEL_NX];        /* z [m], z' [m/s] */
    double time;
    double step_mean[2];       /* mount and drive force averaged over the last Co-Simulation step */
    double step_time, step_velocity; /* when the step began, and z' then */
    bool means_held;           /* Co-Simulation: the *_mean outputs are step_mean; else the forces now */
    bool stale, partials_stale; /* partials_stale: model_common.c's; the partials are not cached */
    double dx[MODEL_NX], out[TABLE_NOUT];
} Model;

#endif
