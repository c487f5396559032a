/* SPDX-License-Identifier: BSD-2-Clause */
/* What a model's event update did (model.h), in a header of its own so that a
 * model's shared parts (contact_record.h), which config.h includes before model.h
 * is complete, can fill it in. */
#ifndef MODEL_EVENT_H
#define MODEL_EVENT_H

#include <stdbool.h>

typedef struct {
    bool describe;       /* in: the caller logs events, so text says what happened (a failure's always) */
    bool states_changed; /* the state was moved: integration must restart */
    bool switched;       /* the mode changed */
    char text[768];      /* what happened, for the event log (if describe); or why it failed */
} ModelEvent;

#endif
