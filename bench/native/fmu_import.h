/* SPDX-License-Identifier: BSD-2-Clause */
/* Loading an FMI 2.0 Model Exchange FMU as an importer does: the facts the
 * driver needs from modelDescription.xml (GUID, model identifier, value
 * references by name, states and derivatives in state order, the number of
 * event indicators) and the fmi2* functions from the shared library (dlopen, by
 * importer/fmi2_functions.c, as the tests' C driver does). */
#ifndef FMU_IMPORT_H
#define FMU_IMPORT_H

#include <stdbool.h>
#include <stddef.h>

#include "fmi2FunctionTypes.h"
#include "fmi2_functions.h"

typedef struct {
    char *name;
    unsigned int vr;
    char type;      /* 'R'eal, 'I'nteger, 'B'oolean, 'S'tring, 'E'num, '?' */
    int derivative; /* 1-based index of the state this variable is the derivative of; 0: none */
} FmuVariable;

typedef struct {
    /* from modelDescription.xml */
    char *guid;
    char *model_identifier; /* of <ModelExchange> */
    FmuVariable *variables; /* in the order of <ModelVariables> */
    size_t n_variables;
    size_t nx, nz;
    unsigned int *state_vr, *derivative_vr; /* nx each, in state order (<Derivatives>) */
    /* the files */
    char *fmu_dir;         /* the extracted FMU's root, or NULL */
    char *library_path;
    char *resource_uri;    /* file:// URI of fmu_dir/resources (or of the library's folder) */
    /* the library's functions (the project's one C loader, importer/) */
    Fmi2Functions fmi;
} FmuImport;

/* `path` is an extracted FMU directory or the shared library itself, inside
 * an extracted FMU (binaries/<platform>/<id>.so: modelDescription.xml is two
 * folders up). Fills `fmu` and returns true, or false with a message naming
 * what to fix in err; fmu_import_close is safe in both cases. */
bool fmu_import_open(FmuImport *fmu, const char *path, char *err, size_t n);
void fmu_import_close(FmuImport *fmu);

/* The variable named `name` of type `type` ('R', 'I', 'B'), or NULL. */
const FmuVariable *fmu_import_variable(const FmuImport *fmu, const char *name, char type);

#endif
