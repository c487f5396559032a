/* SPDX-License-Identifier: BSD-2-Clause */
/* What a model's event update did (model.h), in a header of its own so that a
 * model's shared parts (contact_record.h), which config.h includes before model.h
 * is complete, can fill it in. */
#ifndef MODEL_EVENT_H
#define MODEL_EVENT_H

#include <stdbool.h>

typedef struct {
    bool describe;       /* in: the caller logs events, so text says what happened (a failure's always) */
    bool located;        /* in: an integrator located this event: the indicators that changed sign since
                          * model_begin_integration sit on their surfaces (not an input's nor the start's event) */
    bool states_changed; /* the state was moved: integration must restart */
    bool switched;       /* the mode changed */
    bool fast_growth;    /* the new mode's fast motion grows (a contact in the paradox, p < 0): an
                          * explicit integrator follows it, where an implicit one's large steps damp it */
    char text[768];      /* what happened, for the event log (if describe); or why it failed */
} ModelEvent;

#endif
