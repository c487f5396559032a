/* SPDX-License-Identifier: BSD-2-Clause */
/* An instance's FMU state under any FMI version (instance_state.c): the
 * snapshot the FMI layers hand out as fmi2FMUstate or fmi3FMUState, and its
 * versioned, checksummed byte layout. */
#ifndef INSTANCE_STATE_H
#define INSTANCE_STATE_H

#include <stddef.h>

#include "instance.h"

/* Bytes to allocate for one snapshot. */
size_t instance_snapshot_size(void);

/* Takes the instance's state into snapshot (Co-Simulation's solver restarts). */
void instance_snapshot_take(Instance *in, void *snapshot);

/* The instance becomes snapshot; STATUS_ERROR if it is the other interface's. */
Status instance_snapshot_restore(Instance *in, const char *call, const void *snapshot);

/* Writes the serialized form to out (if not NULL); returns its length. */
size_t instance_snapshot_serialize(const void *snapshot, unsigned char *out);

/* Reads bytes into snapshot, checking every part; STATUS_ERROR naming what is wrong. */
Status instance_snapshot_deserialize(Instance *in, const char *call, const unsigned char *bytes, size_t size,
                                     void *snapshot);

#endif
