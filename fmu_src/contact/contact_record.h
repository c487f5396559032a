/* SPDX-License-Identifier: BSD-2-Clause */
/* The event iteration of a model built on the contact core (contact.c), shared by every
 * such model (PainleveRod, PainleveRodSI, TwoLinkArm): the mode, the record of its switches,
 * the indicators where integration last restarted, and the Zeno guard. The
 * models differ in bodies, units and inputs, not in when and how the contact switches. */
#ifndef CONTACT_RECORD_H
#define CONTACT_RECORD_H

#include <stdbool.h>
#include <stddef.h>

#include "model_event.h"
#include "contact.h"

/* A run of this many events at one instant (no progress in time beyond
 * what the physics and the time's resolution tell apart) is a Zeno run, not a fast
 * one: a physical IWC has at most four switches at one instant, and a fast body's
 * events advance time. */
#define CONTACT_MAX_EVENTS_AT_ONE_INSTANT 100

/* One instant: a chain of events, each within this fraction of the contact's fastest
 * time scale (contact_time_scale) of the one before, where the state moves by a
 * thousandth of its contact scales; and never more than 1e-12 relative (round-off of
 * a time as masters and solvers add steps to it: the instant before the time scale
 * entered, which it still is at the paper's eps and times). */
#define CONTACT_INSTANT_OF_TIME_SCALE 1e-3
#define CONTACT_INSTANT_RELATIVE 1e-12

/* Nor less than the time to which events can be placed at time t: CVODE's root
 * finding and the explicit pair's stop at 100 ulps of |t| + |h| (explicit_rk.c's
 * ROOT_TOLERANCE_ULPS), so two events closer than 256 ulps of t cannot be told apart
 * (at t = 1e6 s: 5.7e-8 s). A contact faster than this is one t cannot resolve. */
#define CONTACT_EVENT_RESOLUTION_ULPS 256

/* Returns to a surface in a row (events that switched nothing) after which the
 * move off it stops growing: the first trial move is then 2^40 1e-15 = 1e-3 of
 * the state's nominal, which leaves room below the nominal to double in. */
#define CONTACT_MAX_RETURNS 40

typedef struct {
    ContactMode mode;
    double t_switch, t_stick_begin, t_stick_end; /* times of the last switch, stick start, stick end */
    double t_contact_begin, t_contact_end;       /* times the last contact began and ended */
    int switches, sticks;                        /* mode switches and sticks since initialization */
    double z_at_restart[CONTACT_NZ];                 /* indicators where integration last (re)started */
    bool initial_event;                          /* the event iteration right after initialization */
    double instant;                              /* time of the last event of the current run at one instant */
    int events_at_instant;
    int returns;                                 /* events in a row that switched nothing */
} ContactRecord;

/* The coefficients of eq Painleve and eq Sw at the current state, in the paper's scaled
 * form (ContactCoeffs), for a model whose outputs array `OUT` holds them at `FIRST`
 * (the index of a). */
#define CONTACT_COEFFICIENT_VARIABLES(VARIABLE, OUT, FIRST)                                            \
    VARIABLE(A, "a", REAL, CALCULATED, OUT[(FIRST)], 0, 0)                                         \
    VARIABLE(B, "b", REAL, CALCULATED, OUT[(FIRST) + 1], 0, 0)                                     \
    VARIABLE(P_PLUS, "p_plus", REAL, CALCULATED, OUT[(FIRST) + 2], 0, 0)                           \
    VARIABLE(P_MINUS, "p_minus", REAL, CALCULATED, OUT[(FIRST) + 3], 0, 0)                         \
    VARIABLE(Q_PLUS, "q_plus", REAL, CALCULATED, OUT[(FIRST) + 4], 0, 0)                           \
    VARIABLE(Q_MINUS, "q_minus", REAL, CALCULATED, OUT[(FIRST) + 5], 0, 0)                         \
    VARIABLE(S_W, "S_w", REAL, CALCULATED, OUT[(FIRST) + 6], 0, 0)

/* The record's variables and internals for a model's config.h lists (the
 * Model's ContactRecord field is `run`): the times of the last switches (Reals),
 * the mode and counts (Integers, Boolean), what an FMU state carries beyond. */
#define CONTACT_RECORD_TIMES(VARIABLE)                                                                 \
    VARIABLE(T_SWITCH, "t_switch", REAL, DISCRETE, run.t_switch, 0, 0)                             \
    VARIABLE(T_STICK_BEGIN, "t_stick_begin", REAL, DISCRETE, run.t_stick_begin, 0, 0)              \
    VARIABLE(T_STICK_END, "t_stick_end", REAL, DISCRETE, run.t_stick_end, 0, 0)                    \
    VARIABLE(T_CONTACT_BEGIN, "t_contact_begin", REAL, DISCRETE, run.t_contact_begin, 0, 0)        \
    VARIABLE(T_CONTACT_END, "t_contact_end", REAL, DISCRETE, run.t_contact_end, 0, 0)
#define CONTACT_RECORD_MODES(VARIABLE)                                                                 \
    VARIABLE(MODE, "mode", INTEGER, DISCRETE, run.mode.slip, 0, 0)                                 \
    VARIABLE(SWITCHES, "switches", INTEGER, DISCRETE, run.switches, 0, 0)                          \
    VARIABLE(STICKS, "sticks", INTEGER, DISCRETE, run.sticks, 0, 0)                                \
    VARIABLE(CONTACT, "contact", BOOLEAN, DISCRETE, run.mode.contact, 0, 0)
#define CONTACT_RECORD_INTERNALS(INTERNAL)                            \
    INTERNAL("z_at_restart0", run.z_at_restart[0], REAL)          \
    INTERNAL("z_at_restart1", run.z_at_restart[1], REAL)          \
    INTERNAL("z_at_restart2", run.z_at_restart[2], REAL)          \
    INTERNAL("z_at_restart3", run.z_at_restart[3], REAL)          \
    INTERNAL("initial_event", run.initial_event, BOOLEAN)         \
    INTERNAL("instant", run.instant, REAL)                        \
    INTERNAL("events_at_instant", run.events_at_instant, INTEGER) \
    INTERNAL("returns", run.returns, INTEGER)

/* Before initialization: the default mode, no record. */
ContactRecord contact_record_new(void);

/* The mode decided from the state alone (nothing is remembered before the start). */
ContactMode contact_initial_mode(const Contact *c, double x[]);

/* Initialization ends at `time`: the initial mode, an empty record. */
void contact_record_start(ContactRecord *r, const Contact *c, double x[], double time);

/* The initial mode, for the event log. */
void contact_record_describe_start(const ContactRecord *r, char *text, size_t size);

/* The event update at `time` (contact_event_update), recorded; z holds the indicators
 * at the event, time_unit the model's time per scaled time unit (1 for a scaled model,
 * sqrt(L/g) in SI), by which the contact's time scale enters the model's time. With
 * `floor_jumped` (the floor's speed changed by an input, not at a located v = 0) the
 * body slips the way its new relative velocity points, as at the start, and the rules
 * go on from there. False, with the reason in e->text, if the modes do not settle or
 * too many events fall on one instant. */
bool contact_record_event(ContactRecord *r, const Contact *c, double x[], const double z[CONTACT_NZ], double time,
                          double time_unit, bool floor_jumped, ModelEvent *e);

/* NULL if r (restored from bytes) is a record this model can have, else the
 * name of the first variable that is not. */
const char *contact_record_implausible(const ContactRecord *r);

#endif
