/* SPDX-License-Identifier: BSD-2-Clause */
/* The event iteration of a model on the contact core: see contact_record.h. */
#include "contact_record.h"

#include <float.h>
#include <math.h>
#include <stdio.h>

ContactRecord contact_record_new(void)
{
    return (ContactRecord){ .mode = { false, +1 }, .instant = -INFINITY };
}

/* A start given on the floor at rest carries its giver's rounding as well as ours (a body whose
 * gap is no state: H from the angles, the rates from the tip's velocity, each rounded in SI and
 * scaled): the start is on y = 0 at rest within this many times the rounding the body reports. */
#define CONTACT_START_ROUNDING 8

/* On y = 0 at rest, both or neither: on the floor with w of either sign, the moves off the
 * surfaces (which turn w with the angles) would flip the decision round after round. */
static ContactSurfaces start_surfaces(const BodyState *s)
{
    const bool at_rest = fabs(s->y) <= CONTACT_START_ROUNDING * s->y_noise &&
                         fabs(s->w) <= CONTACT_START_ROUNDING * s->w_noise;
    return (ContactSurfaces){ .gap = at_rest, .still = at_rest };
}

ContactMode contact_initial_mode(const Contact *c, double x[])
{
    /* Slip follows the sign of v until the rules decide. */
    const BodyState s = contact_body(c, x);
    bool changed;
    return contact_decide_mode(c, (ContactMode){ false, (s.v > 0) - (s.v < 0) }, x, start_surfaces(&s), &changed);
}

void contact_record_start(ContactRecord *r, const Contact *c, double x[], double time)
{
    r->mode = contact_initial_mode(c, x);
    r->t_switch = r->t_stick_begin = r->t_stick_end = r->t_contact_begin = r->t_contact_end = time;
    r->switches = r->sticks = 0;
    r->initial_event = true;
    r->instant = -INFINITY;
    r->events_at_instant = 0;
    r->returns = 0;
}

void contact_record_describe_start(const ContactRecord *r, char *text, size_t size)
{
    snprintf(text, size, "initial mode contact = %d, mode = %+d", r->mode.contact, r->mode.slip);
}

/* The indicators that changed sign since integration last restarted (bit i: indicator i), or are 0. */
static unsigned crossed_since_restart(const ContactRecord *r, const double z[CONTACT_NZ])
{
    unsigned crossed = 0;
    for (int i = 0; i < CONTACT_NZ; ++i)
        if ((z[i] > 0) != (r->z_at_restart[i] > 0) || z[i] == 0) crossed |= 1u << i;
    return crossed;
}

/* Which indicators of `mode` changed sign since integration last restarted (none at the initial
 * event iteration). */
static void describe_fired(const ContactRecord *r, ContactMode mode, bool initial, const double z[CONTACT_NZ],
                           char *text, size_t size)
{
    size_t n = 0;
    if (initial) {
        snprintf(text, size, "none (initial event iteration)");
        return;
    }
    const unsigned crossed = crossed_since_restart(r, z);
    for (int i = 0; i < CONTACT_NZ && n < size; ++i)
        if (crossed & 1u << i)
            n += (size_t)snprintf(text + n, size - n, "%s'%s' = %.3g", n ? ", " : "",
                                  contact_indicator_name(mode, i), z[i]);
    if (n == 0) snprintf(text, size, "none (time or step event)");
}

static bool sticking(ContactMode mode) { return mode.contact && mode.slip == 0; }

/* The switch from `before` to the current mode, at `time`, in the record. */
static void record_switch(ContactRecord *r, ContactMode before, double time)
{
    r->t_switch = time;
    ++r->switches;
    if (sticking(r->mode) && !sticking(before)) {
        r->t_stick_begin = time;
        ++r->sticks;
    }
    if (sticking(before) && !sticking(r->mode)) r->t_stick_end = time;
    if (r->mode.contact && !before.contact) r->t_contact_begin = time;
    if (before.contact && !r->mode.contact) r->t_contact_end = time;
}

/* What one instant is at an event: its width, and what it is made of. */
typedef struct {
    double width;       /* an event within this of the one before is on the same instant */
    double time_scale;  /* the contact's fastest time scale, in the model's time */
    double resolution;  /* the time to which events at this time can be placed */
} Instant;

/* The instant at `time` with the body at x (contact_record.h): a small part of the contact's
 * own time scale, not wider than round-off of the time, not narrower than what t resolves. */
static Instant instant_at(const Contact *c, const double x[], double time, double time_unit)
{
    Instant i = { .time_scale = time_unit * contact_time_scale(c, x),
                  .resolution = CONTACT_EVENT_RESOLUTION_ULPS * DBL_EPSILON * fabs(time) };
    /* fmin drops a NaN time scale (a state no event reaches with): the round-off bound holds */
    i.width = fmax(i.resolution, fmin(CONTACT_INSTANT_RELATIVE * (1 + fabs(time)),
                                      CONTACT_INSTANT_OF_TIME_SCALE * i.time_scale));
    return i;
}

/* An event at `time` on the instant of the current run of events: no farther from the run's
 * last event than one instant (a chain, so that chatter the time cannot tell apart is one run
 * however long it goes on, and its moves off the surfaces keep growing). */
static bool same_instant(const ContactRecord *r, const Instant *i, double time)
{
    return time - r->instant <= i->width;
}

/* The time's limit at a contact faster than t resolves, after `what` happened there. */
static void describe_resolution(const ContactRecord *r, const Instant *i, double y, double time, const char *what,
                                const char *fired, ModelEvent *e)
{
    snprintf(e->text, sizeof e->text,
             "%s, to t = %.17g: t cannot resolve the contact at this time (its time scale %.3g is below the %.3g "
             "to which events at this t can be placed, %d ulps); the boundary %.300s chattered (contact = %d, "
             "mode = %+d, y = %g): start nearer t = 0, or with a softer contact",
             what, time, i->time_scale, i->resolution, CONTACT_EVENT_RESOLUTION_ULPS, fired, r->mode.contact,
             r->mode.slip, y);
}

/* The guard's message: a Zeno run, or (the contact faster than t resolves) the time's limit. */
static void describe_guard(const ContactRecord *r, const Contact *c, const double x[], const Instant *i,
                           double time, const char *fired, ModelEvent *e)
{
    const BodyState s = contact_body(c, x);
    char what[96];
    snprintf(what, sizeof what, "%d events each within %.3g of the one before", CONTACT_MAX_EVENTS_AT_ONE_INSTANT,
             i->width);
    if (i->time_scale < i->resolution)
        describe_resolution(r, i, s.y, time, what, fired, e);
    else
        snprintf(e->text, sizeof e->text,
                 "%d events at t = %.17g without progress in time (a Zeno run: the modes chatter at the boundary "
                 "%.300s, each event within %.3g of the one before, the contact's time scale %.3g; contact = %d, "
                 "mode = %+d, y = %g)",
                 CONTACT_MAX_EVENTS_AT_ONE_INSTANT, time, fired, i->width, i->time_scale, r->mode.contact,
                 r->mode.slip, s.y);
}

bool contact_record_event(ContactRecord *r, const Contact *c, double x[], const double z[CONTACT_NZ], double time,
                          double time_unit, bool floor_jumped, ModelEvent *e)
{
    /* the indicators' text costs snprintf at every event: made only for a log line or a failure */
    char fired[512] = "";
    const bool initial = r->initial_event;
    const Instant instant = instant_at(c, x, time, time_unit);
    r->initial_event = false;
    const ContactMode before = r->mode;
    const BodyState at = contact_body(c, x);
    if (floor_jumped && at.v != 0) r->mode.slip = at.v > 0 ? +1 : -1;
    /* An event that switched nothing, or another at the same instant (the chain of same_instant),
     * means the solver came straight back to a surface the state had been moved off: its error
     * exceeds the move.
     * Each such event moves twice as far, so the chatter ends where the motion goes on
     * (docs/bounded_calls.md); a physical IWC has at most 4 events at one instant. */
    const int again = r->returns + (same_instant(r, &instant, time) ? r->events_at_instant : 0);
    /* The surfaces the start sits on, or an integrator located (none for an input). An integrator
     * that came straight back to one is too coarse for the derivatives to decide there (a
     * tolerance of 10): the signs decide again, as for any other state. */
    const ContactSurfaces on = initial ? start_surfaces(&at)
                               : e->located && !floor_jumped && r->returns == 0
                                   ? contact_surfaces_of(c, before, x, crossed_since_restart(r, z),
                                                         instant.width / time_unit)
                                   : (ContactSurfaces){ 0 };
    bool moved;
    const ContactEventResult result = contact_event_update(
        c, &r->mode, x, on, ldexp(1.0, again < CONTACT_MAX_RETURNS ? again : CONTACT_MAX_RETURNS), &moved);
    e->switched = before.contact != r->mode.contact || before.slip != r->mode.slip;
    e->states_changed = moved;
    if (e->describe || result != CONTACT_SETTLED) describe_fired(r, before, initial, z, fired, sizeof fired);
    if (result != CONTACT_SETTLED && instant.time_scale < instant.resolution) {
        /* the surfaces cannot be left where the time cannot place the events that would */
        describe_resolution(r, &instant, contact_body(c, x).y, time,
                            result == CONTACT_PING_PONG ? "the mode decision does not settle"
                                                        : "the state cannot be moved off a switching surface",
                            fired, e);
        return false;
    }
    if (result != CONTACT_SETTLED) {
        snprintf(e->text, sizeof e->text, result == CONTACT_PING_PONG
                 ? "mode decision does not settle at t = %.17g (contact = %d, mode = %+d): rules ping-pong"
                 : "the state cannot be moved off a switching surface at t = %.17g (contact = %d, mode = %+d)",
                 time, r->mode.contact, r->mode.slip);
        return false;
    }
    if (e->switched) record_switch(r, before, time);
    e->fast_growth = contact_fast_growth(c, r->mode, x);
    /* a return moved the state off a surface; an update that switched and moved nothing (an input)
     * is none, nor is the start's move off the surfaces it was given on */
    r->returns = initial || e->switched || !moved ? 0 : (r->returns < CONTACT_MAX_RETURNS ? r->returns + 1 : CONTACT_MAX_RETURNS);
    if (e->describe)
        snprintf(e->text, sizeof e->text, "t = %.17g: indicator %s; contact %d -> %d, mode %+d -> %+d%s", time, fired,
                 before.contact, r->mode.contact, before.slip, r->mode.slip, moved ? "; continuous states changed" : "");
    else
        e->text[0] = '\0';
    /* Zeno guard: events that do not advance time beyond one instant. */
    if (!same_instant(r, &instant, time)) r->events_at_instant = 0;
    r->instant = time;
    if (++r->events_at_instant < CONTACT_MAX_EVENTS_AT_ONE_INSTANT) return true;
    if (!fired[0]) describe_fired(r, before, initial, z, fired, sizeof fired);
    describe_guard(r, c, x, &instant, time, fired, e);
    return false;
}

const char *contact_record_implausible(const ContactRecord *r)
{
    if (r->mode.slip < -1 || r->mode.slip > 1) return "mode";
    if (r->switches < 0 || r->sticks < 0 || r->sticks > r->switches) return "switches";
    const double times[] = { r->t_switch, r->t_stick_begin, r->t_stick_end, r->t_contact_begin, r->t_contact_end };
    for (size_t i = 0; i < sizeof times / sizeof times[0]; ++i)
        if (!isfinite(times[i])) return "t_switch";
    if (r->events_at_instant < 0 || r->events_at_instant >= CONTACT_MAX_EVENTS_AT_ONE_INSTANT) return "events_at_instant";
    if (r->returns < 0 || r->returns > CONTACT_MAX_RETURNS) return "returns";
    return NULL;
}
