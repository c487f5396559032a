/* The event iteration of a model built on rod.c, shared by every such model
 * (PainleveRod, models/PainleveRodSI): the mode, the record of its switches,
 * the indicators where integration last restarted, and the Zeno guard. The
 * models differ in units and inputs, not in when and how the rod switches. */
#ifndef ROD_RECORD_H
#define ROD_RECORD_H

#include <stdbool.h>
#include <stddef.h>

#include "rod.h"

/* A run of this many events at one instant (no progress in time beyond
 * round-off) is a Zeno run, not a fast one: a physical IWC has at most four
 * switches at one instant, and a fast rod's events advance time. */
#define ROD_MAX_EVENTS_AT_ONE_INSTANT 100

typedef struct {
    RodMode mode;
    double t_switch, t_stick_begin, t_stick_end; /* times of the last switch, stick start, stick end */
    double t_contact_begin, t_contact_end;       /* times the last contact began and ended */
    int switches, sticks;                        /* mode switches and sticks since initialization */
    double z_at_restart[ROD_NZ];                 /* indicators where integration last (re)started */
    bool initial_event;                          /* the event iteration right after initialization */
    double instant;                              /* time of the current run of events at one instant */
    int events_at_instant;
} RodRecord;

/* Before initialization: the default mode, no record. */
RodRecord rod_record_new(void);

/* The mode decided from the state alone (nothing is remembered before the start). */
RodMode rod_initial_mode(const RodParams *p, double x[ROD_NX]);

/* Initialization ends at `time`: the initial mode, an empty record. */
void rod_record_start(RodRecord *r, const RodParams *p, double x[ROD_NX], double time);

/* What an event update did (model.h's ModelEvent, filled by the model). */
typedef struct {
    bool states_changed, switched;
    char text[768];
} RodEvent;

/* The event update at `time` (rod_event_update), recorded; z holds the indicators
 * at the event. With `floor_jumped` (the floor's speed changed by an input, not
 * at a located v = 0) the rod slips the way its new relative velocity points,
 * as at the start, and the rules go on from there. False, with the reason in
 * e->text, if the modes do not settle or too many events fall on one instant. */
bool rod_record_event(RodRecord *r, const RodParams *p, double x[ROD_NX], const double z[ROD_NZ], double time,
                      bool floor_jumped, RodEvent *e);

/* NULL if r (restored from bytes) is a record this model can have, else the
 * name of the first variable that is not. */
const char *rod_record_implausible(const RodRecord *r);

#endif
