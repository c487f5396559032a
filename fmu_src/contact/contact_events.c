/* SPDX-License-Identifier: BSD-2-Clause */
/* The contact core's event update (contact.h): the mode decision iterated to a
 * fixpoint, and the move of the state off every switching surface it sits on, so
 * that no importer restarts integration on a root. Over any body. */
#include "contact.h"

#include <float.h>
#include <math.h>

static int sign_of(double f) { return (f > 0) - (f < 0); }

static bool sticking(ContactMode m) { return m.contact && m.slip == 0; }

/* The side of indicator i on which mode m lives (0: nothing to keep). */
static int wanted_side(const Contact *c, ContactMode m, int i, const double x[])
{
    switch (i) {
    case CONTACT_Z_Y: return m.contact ? -1 : +1;
    case CONTACT_Z_FORCE: return m.contact ? +1 : -1;
    case CONTACT_Z_SLIP: return sticking(m) ? -1 : m.contact ? m.slip : 0;
    case CONTACT_Z_AUX:
        if (m.contact) return m.slip == 0 ? +1 : 0;
        return contact_body(c, x).b >= 0 ? +1 : -1;
    default: return 0;
    }
}

/* The state whose smallest relative move changes indicator i most, and the
 * direction of that move that raises it; -1 if no state moves it. */
static int steepest_state(const Contact *c, ContactMode m, int i, const double x[], const double nominal[],
                          int *direction)
{
    const int n = contact_nx(c->body);
    double z0[CONTACT_NZ], z[CONTACT_NZ], trial[CONTACT_MAX_NX];
    contact_event_indicators(c, m, x, z0);
    int best = -1;
    double largest = 0;
    for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) trial[k] = x[k];
        trial[j] += fmax(1e-6 * nominal[j], 1e-9 * fabs(x[j]));  /* seen above the rounding of a deep state */
        contact_event_indicators(c, m, trial, z);
        const double change = z[i] - z0[i];
        if (fabs(change) > largest) {
            largest = fabs(change);
            best = j;
            *direction = sign_of(change);
        }
    }
    return best;
}

/* The rounding errors of the indicators at x, and, where the importer's solver came straight back
 * to a surface (margin > 1), for y at least an ulp of its own scale eps^2: y computed exactly (the
 * rod's state) has no rounding error, so without this floor no margin would ever move the state
 * off y = 0, and a solver that keeps returning to y = -1e-28 would end in the Zeno guard
 * (docs/general_body.md). Not for v and w: a floor there moves a fast-spinning rod's rates at
 * each of the h events of its flight through the floor, which then never ends (the flat spin of
 * tests/fmu/test_cosimulation.py). */
static void surface_noise(const Contact *c, ContactMode m, const double x[], double margin, double noise[CONTACT_NZ])
{
    contact_indicator_noise(c, m, x, noise);
    if (!(margin > 1)) return;
    const double eps = c->law.epsilon;
    const double floor[CONTACT_NZ] = { DBL_EPSILON * eps * eps, 0, 0, 0 };
    for (int i = 0; i < CONTACT_NZ; ++i) noise[i] = fmax(noise[i], floor[i]);
}

/* Whether indicator i, at z with rounding error `noise`, is clear of its surface on `side`. */
static bool clear_of(double z, double noise, int side)
{
    return sign_of(z) == side && fabs(z) > noise;
}

/* Moves x[state] by the smallest step, doubling from 1e-15 margin nominal up to the
 * nominal (or 1e-6 of the state, deep in the floor where the nominal is below its
 * rounding), that leaves indicator i clear of margin times its rounding error on `side`. */
static bool leave_surface(const Contact *c, ContactMode m, double x[], int i, int side, int state, int direction,
                          double nominal, double margin)
{
    double z[CONTACT_NZ], noise[CONTACT_NZ];
    const double start = x[state], largest = fmax(nominal, 1e-6 * fabs(start));
    for (double step = 1e-15 * margin * nominal; step < largest; step *= 2) {
        x[state] = start + side * direction * step;
        contact_event_indicators(c, m, x, z);
        surface_noise(c, m, x, margin, noise);
        if (clear_of(z[i], margin * noise[i], side)) return true;
    }
    x[state] = start;
    return false;
}

bool contact_move_off_surfaces(const Contact *c, ContactMode m, double x[], ContactSurfaces on, double margin,
                               bool *moved)
{
    double z[CONTACT_NZ], nominal[CONTACT_MAX_NX], noise[CONTACT_NZ];
    *moved = false;
    c->body->nominals(c->params, c->law.epsilon, nominal);
    for (int i = 0; i < CONTACT_NZ; ++i) {
        contact_event_indicators(c, m, x, z);
        surface_noise(c, m, x, margin, noise);
        const int side = wanted_side(c, m, i, x);
        /* A located surface is left on the mode's side, as far as the root finder overshot it
         * within the state's nominal (beyond it, the overshoot stays: the time cannot place the
         * event finer, and the record's guard judges what follows). */
        const bool on_surface = fabs(z[i]) <= margin * noise[i];
        const bool overshot = !on_surface && ((i == CONTACT_Z_Y && on.gap) || (i == CONTACT_Z_FORCE && on.force)) &&
                              !clear_of(z[i], margin * noise[i], side);
        if (side == 0 || !(on_surface || overshot)) continue;
        int direction = 0;
        const int state = steepest_state(c, m, i, x, nominal, &direction);
        if (state < 0) return false;
        /* A margin the nominal cannot reach falls back to the plain one (clear of the rounding). */
        const bool left = leave_surface(c, m, x, i, side, state, direction, nominal[state], margin) ||
                          (margin > 1 && leave_surface(c, m, x, i, side, state, direction, nominal[state], 1));
        if (!left && overshot) continue;   /* leave_surface restored x */
        *moved = true;
        if (!left) return false;
    }
    return true;
}

ContactEventResult contact_event_update(const Contact *c, ContactMode *m, double x[], ContactSurfaces on,
                                        double margin, bool *x_changed)
{
    *x_changed = false;
    /* decide and move-off must reach a fixpoint; a few rounds always do
     * unless the rules ping-pong, which is reported, never looped on. */
    for (int round = 0; round < 8; ++round) {
        bool changed, moved;
        const ContactMode n = contact_decide_mode(c, *m, x, on, &changed);
        *x_changed |= changed;
        const bool same = n.contact == m->contact && n.slip == m->slip;
        *m = n;
        if (!same || changed) continue;
        const bool off = contact_move_off_surfaces(c, *m, x, on, margin, &moved);
        margin = 1;   /* a later round moves only what the decision moved back onto a surface */
        *x_changed |= moved;
        if (!off) return CONTACT_STUCK_ON_SURFACE;
        if (!moved) return CONTACT_SETTLED;
    }
    return CONTACT_PING_PONG;
}
