/* SPDX-License-Identifier: BSD-2-Clause */
/* See fmi2_functions.h. */
#include "fmi2_functions.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

/* POSIX's way from dlsym's void * to a function pointer; false if a required one is missing. */
static bool look_up(void *handle, const char *name, void *field, size_t size, bool required, const char *path,
                    char *err, size_t n)
{
    void *sym = dlsym(handle, name);
    if (!sym && required) {
        snprintf(err, n, "%s does not export %s", path, name);
        return false;
    }
    memcpy(field, &sym, size);
    return true;
}

bool fmi2_functions_load(Fmi2Functions *f, const char *path, bool model_exchange, bool co_simulation, char *err,
                         size_t n)
{
    memset(f, 0, sizeof *f);
    f->handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!f->handle) {
        snprintf(err, n, "dlopen failed: %s", dlerror());
        return false;
    }
    bool ok = true;
#define FMI2_LOOK_UP(name, required) \
    ok = ok && look_up(f->handle, "fmi2" #name, &f->name, sizeof f->name, required, path, err, n);
#define FMI2_COMMON(name) FMI2_LOOK_UP(name, true)
#define FMI2_MODEL_EXCHANGE(name) FMI2_LOOK_UP(name, model_exchange)
#define FMI2_CO_SIMULATION(name) FMI2_LOOK_UP(name, co_simulation)
    FMI2_COMMON_FUNCTIONS(FMI2_COMMON)
    FMI2_MODEL_EXCHANGE_FUNCTIONS(FMI2_MODEL_EXCHANGE)
    FMI2_CO_SIMULATION_FUNCTIONS(FMI2_CO_SIMULATION)
#undef FMI2_COMMON
#undef FMI2_MODEL_EXCHANGE
#undef FMI2_CO_SIMULATION
#undef FMI2_LOOK_UP
    if (!ok) fmi2_functions_unload(f);
    return ok;
}

void fmi2_functions_unload(Fmi2Functions *f)
{
#ifndef FMI2_FUNCTIONS_KEEP_LOADED
    if (f->handle) dlclose(f->handle);
#endif
    memset(f, 0, sizeof *f);
}
