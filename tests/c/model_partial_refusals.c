/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRod's own partial derivatives (model_calculated_partial) over its whole variable
 * list and beyond: every calculated Real unknown by every settable known answers a finite
 * number; a known or an unknown the rod's partials do not know (a calculated variable as
 * known, a value reference past the list) is refused with a reason, never answered with
 * another variable's column. Built and run by tests/fmu/test_model_partial_refusals.py;
 * exit status 0 only if every check passed. */
#include <math.h>
#include <stdio.h>

#include "model.h"

/* What model_common.c hands the model: a calculated Real (not settable, not discrete). */
static bool calculated_real(unsigned int vr)
{
    const VariableInfo *v = model_variable(vr);
    return v && v->type == TYPE_REAL && !model_settable(v) && v->kind != KIND_DISCRETE;
}

int main(void)
{
    Model m;
    model_reset(&m);
    int failures = 0, answered = 0, refused = 0;
    for (unsigned int u = 0; u < VR_COUNT + 3; ++u) {
        if (u < VR_COUNT && !calculated_real(u)) continue;
        for (unsigned int k = 0; k < VR_COUNT + 3; ++k) {
            const VariableInfo *known = model_variable(k);
            const bool pair = u < VR_COUNT && known && model_settable(known);
            double value = NAN;
            const char *why = model_calculated_partial(&m, u, k, &value);
            if (pair && (why || !isfinite(value))) {
                printf("FAIL %u by %u: %s (%g)\n", u, k, why ? why : "answered", value);
                ++failures;
            } else if (!pair && !why) {
                printf("FAIL %u by %u: answered %g, wanted a refusal\n", u, k, value);
                ++failures;
            }
            pair ? ++answered : ++refused;
        }
    }
    printf("%d pairs answered, %d refused, %d failed\n", answered, refused, failures);
    return failures != 0;
}
