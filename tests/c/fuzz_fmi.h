/* SPDX-License-Identifier: BSD-2-Clause */
/* What the files of the FMI 2.0 fuzz target (fuzz_fmi.c) share: the loaded FMU,
 * the input being decoded, the three instances, the checked call, and the calls
 * that the opcodes name. */
#ifndef FUZZ_FMI_H
#define FUZZ_FMI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define FUZZ_NAME "fuzz_fmi"
#include "fuzz_bytes.h"
#include "fmi_harness.h"
#include "model_structure.h"

extern FmiApi api; /* loaded by LLVMFuzzerInitialize */

#define CAP 8 /* capacity of every array handed to the FMU */

typedef struct {
    EulerSim sim;  /* sim.c is the instance, NULL if none */
    bool logs;     /* instantiated with a logger */
    bool cs;       /* instantiated for Co-Simulation */
    double time;   /* where the next fmi2DoStep starts */
    bool in_error; /* an fmi2Error since the last instantiate or reset */
} Slot;

extern Slot slots[3];
extern Bytes fuzz_input;  /* the rest of this input's bytes */
extern double span_left;  /* time that fmi2DoStep may still integrate in this input */

/* fuzz_fmi_instances.c: a value reference (mostly near the valid ones,
 * sometimes far out); a count and whether the arrays are passed (NULL). */
fmi2ValueReference take_vr(Bytes *b);
size_t take_count(Bytes *b, bool *null_arrays);
void free_slot(Slot *s);

/* Checks a status and the Error state's rules. `may_pass_in_error`: calls the
 * Error state allows (getters, logging, FMU state, status queries). */
fmi2Status checked(Slot *s, const char *call, fmi2Status st, long errors_before, bool may_pass_in_error);
#define CALL(slot, may_pass_in_error, expr) \
    checked((slot), #expr, (expr), errors_before, (may_pass_in_error))

void require_finite(const char *what, const double *v, size_t n);

/* The calls, one per opcode (`which` picks among a group's calls). */
void op_instantiate(Slot *s);                  /* fuzz_fmi_instances.c */
void op_get(Slot *s, uint8_t which);           /* fuzz_fmi_values.c */
void op_set(Slot *s, uint8_t which);
void op_arrays(Slot *s, uint8_t which);
void op_directional_derivative(Slot *s);
void op_event(Slot *s, uint8_t which);         /* fuzz_fmi_modes.c */
void op_lifecycle(Slot *s, uint8_t which);
void op_debug_logging(Slot *s);
void op_fmu_state(Slot *s);                    /* fuzz_fmi_fmu_state.c */
void op_deserialize_raw(Slot *s);
void op_optional(Slot *s, uint8_t which);      /* fuzz_fmi_steps.c */
void op_simulate(Slot *s, uint8_t which);

#endif
