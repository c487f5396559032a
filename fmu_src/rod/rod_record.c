/* The event iteration of a rod model: see rod_record.h. */
#include "rod_record.h"

#include <math.h>
#include <stdio.h>

RodRecord rod_record_new(void)
{
    return (RodRecord){ .mode = { false, +1 }, .instant = -INFINITY };
}

RodMode rod_initial_mode(const RodParams *p, double x[ROD_NX])
{
    /* Slip follows the sign of v until the rules decide. */
    const double v = x[ROD_V];
    bool changed;
    return rod_decide_mode(p, (RodMode){ false, (v > 0) - (v < 0) }, x, &changed);
}

void rod_record_start(RodRecord *r, const RodParams *p, double x[ROD_NX], double time)
{
    r->mode = rod_initial_mode(p, x);
    r->t_switch = r->t_stick_begin = r->t_stick_end = r->t_contact_begin = r->t_contact_end = time;
    r->switches = r->sticks = 0;
    r->initial_event = true;
    r->instant = -INFINITY;
    r->events_at_instant = 0;
    r->returns = 0;
}

void rod_record_describe_start(const RodRecord *r, char *text, size_t size)
{
    snprintf(text, size, "initial mode contact = %d, mode = %+d", r->mode.contact, r->mode.slip);
}

/* Which indicators changed sign since integration last restarted. */
static void describe_fired(const RodRecord *r, const double z[ROD_NZ], char *text, size_t size)
{
    size_t n = 0;
    if (r->initial_event) {
        snprintf(text, size, "none (initial event iteration)");
        return;
    }
    for (int i = 0; i < ROD_NZ && n < size; ++i)
        if ((z[i] > 0) != (r->z_at_restart[i] > 0) || z[i] == 0)
            n += (size_t)snprintf(text + n, size - n, "%s'%s' = %.3g", n ? ", " : "",
                                  rod_indicator_name(r->mode, i), z[i]);
    if (n == 0) snprintf(text, size, "none (time or step event)");
}

static bool sticking(RodMode mode) { return mode.contact && mode.slip == 0; }

/* The switch from `before` to the current mode, at `time`, in the record. */
static void record_switch(RodRecord *r, RodMode before, double time)
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

/* An event at `time` on the instant of the current run of events (round-off apart). */
static bool same_instant(const RodRecord *r, double time)
{
    return time - r->instant <= 1e-12 * (1 + fabs(time));
}

bool rod_record_event(RodRecord *r, const RodParams *p, double x[ROD_NX], const double z[ROD_NZ], double time,
                      bool floor_jumped, ModelEvent *e)
{
    char fired[512];
    describe_fired(r, z, fired, sizeof fired);
    r->initial_event = false;
    const RodMode before = r->mode;
    if (floor_jumped && x[ROD_V] != 0) r->mode.slip = x[ROD_V] > 0 ? +1 : -1;
    /* An event that switched nothing, or another at the same instant, means the solver came
     * straight back to a surface the state had been moved off: its error exceeds the move.
     * Each such event moves twice as far, so the chatter ends where the motion goes on
     * (docs/bounded_calls.md); a physical IWC has at most 4 events at one instant. */
    const int again = r->returns + (same_instant(r, time) ? r->events_at_instant : 0);
    bool moved;
    const RodEventResult result =
        rod_event_update(p, &r->mode, x, ldexp(1.0, again < ROD_MAX_RETURNS ? again : ROD_MAX_RETURNS), &moved);
    e->switched = before.contact != r->mode.contact || before.slip != r->mode.slip;
    e->states_changed = moved;
    if (result != ROD_SETTLED) {
        snprintf(e->text, sizeof e->text, result == ROD_PING_PONG
                 ? "mode decision does not settle at t = %.17g (contact = %d, mode = %+d): rules ping-pong"
                 : "the state cannot be moved off a switching surface at t = %.17g (contact = %d, mode = %+d)",
                 time, r->mode.contact, r->mode.slip);
        return false;
    }
    if (e->switched) record_switch(r, before, time);
    /* a return moved the state off a surface; an update that switched and moved nothing (an input) is none */
    r->returns = e->switched || !moved ? 0 : (r->returns < ROD_MAX_RETURNS ? r->returns + 1 : ROD_MAX_RETURNS);
    snprintf(e->text, sizeof e->text, "t = %.17g: indicator %s; contact %d -> %d, mode %+d -> %+d%s", time, fired,
             before.contact, r->mode.contact, before.slip, r->mode.slip, moved ? "; continuous states changed" : "");
    /* Zeno guard: events that do not advance time beyond round-off. */
    if (!same_instant(r, time)) {
        r->instant = time;
        r->events_at_instant = 0;
    }
    if (++r->events_at_instant < ROD_MAX_EVENTS_AT_ONE_INSTANT) return true;
    snprintf(e->text, sizeof e->text,
             "%d events at t = %.17g without progress in time (a Zeno run: the modes chatter at the boundary %s; "
             "contact = %d, mode = %+d, theta = %g)",
             ROD_MAX_EVENTS_AT_ONE_INSTANT, time, fired, r->mode.contact, r->mode.slip, x[ROD_THETA]);
    return false;
}

const char *rod_record_implausible(const RodRecord *r)
{
    if (r->mode.slip < -1 || r->mode.slip > 1) return "mode";
    if (r->switches < 0 || r->sticks < 0 || r->sticks > r->switches) return "switches";
    const double times[] = { r->t_switch, r->t_stick_begin, r->t_stick_end, r->t_contact_begin, r->t_contact_end };
    for (size_t i = 0; i < sizeof times / sizeof times[0]; ++i)
        if (!isfinite(times[i])) return "t_switch";
    if (r->events_at_instant < 0 || r->events_at_instant >= ROD_MAX_EVENTS_AT_ONE_INSTANT) return "events_at_instant";
    if (r->returns < 0 || r->returns > ROD_MAX_RETURNS) return "returns";
    return NULL;
}
