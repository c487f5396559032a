/* SPDX-License-Identifier: BSD-2-Clause */
/* The questions of model_structure.h, answered from the generated tables. */
#include "model_structure.h"

#include <stddef.h>

const MdVariable *md_var(int index)
{
    return index >= 1 && index <= MD_N_VARIABLES ? &MD_VARIABLES[index - 1] : NULL;
}

static const MdUnknown *find(const MdUnknown *list, int n, int index)
{
    for (int k = 0; k < n; ++k)
        if (list[k].index == index) return &list[k];
    return NULL;
}

bool md_initial_unknown(int index)
{
    return find(MD_INITIALUNKNOWNS, MD_N_INITIALUNKNOWNS, index) != NULL;
}

const MdUnknown *md_unknown_of_mode(MdMode mode, int index)
{
    const MdVariable *v = md_var(index);
    if (!v || v->type != MD_REAL) return NULL;
    if (mode == MD_MODE_INIT) return find(MD_INITIALUNKNOWNS, MD_N_INITIALUNKNOWNS, index);
    const MdUnknown *d = find(MD_DERIVATIVES, MD_N_DERIVATIVES, index);
    if (d) return d;
    const MdUnknown *o = find(MD_OUTPUTS, MD_N_OUTPUTS, index);
    if (!o) return NULL;
    if (v->variability == MD_CONTINUOUS) return o;
    return v->variability == MD_DISCRETE && mode != MD_MODE_CONTINUOUS ? o : NULL;
}

bool md_known_of_mode(MdMode mode, int index)
{
    const MdVariable *v = md_var(index);
    if (!v || v->type != MD_REAL) return false;
    if (v->causality == MD_INPUT) return true;
    return mode == MD_MODE_INIT ? v->initial == MD_INITIAL_EXACT : v->state;
}

bool md_depends(const MdUnknown *u, int index)
{
    if (u->n_deps < 0) return true;
    for (int k = 0; k < u->n_deps; ++k)
        if (u->deps[k] == index) return true;
    return false;
}

void md_mode_sets(MdMode mode, int max, int *unknowns, int *nu, int *knowns, int *nk)
{
    *nu = *nk = 0;
    for (int k = 1; k <= MD_N_VARIABLES && k <= max; ++k) {
        if (md_unknown_of_mode(mode, k)) unknowns[(*nu)++] = k;
        if (md_known_of_mode(mode, k)) knowns[(*nk)++] = k;
    }
}

int md_state_index(int i)
{
    return i >= 0 && i < MD_N_DERIVATIVES ? md_var(MD_DERIVATIVES[i].index)->derivative : 0;
}

int md_state_position(int index)
{
    for (int i = 0; i < MD_N_DERIVATIVES; ++i)
        if (md_state_index(i) == index) return i;
    return -1;
}

int md_first(MdCausality causality, MdVariability variability)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (md_var(k)->type == MD_REAL && md_var(k)->causality == causality && md_var(k)->variability == variability)
            return k;
    return 0;
}
