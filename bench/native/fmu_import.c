/* SPDX-License-Identifier: BSD-2-Clause */
/* See fmu_import.h. modelDescription.xml is read by a small scanner that
 * knows the few elements it needs (comments blanked, quoted attribute values
 * skipped), not by a general XML parser. */
#include "fmu_import.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define PLATFORM "linux64"

static char *copy_string(const char *s, size_t len)
{
    char *out = malloc(len + 1);
    if (!out) return NULL;
    memcpy(out, s, len);
    out[len] = '\0';
    return out;
}

static char *join(const char *a, const char *b, const char *c)
{
    size_t na = strlen(a), nb = strlen(b), nc = strlen(c);
    char *out = malloc(na + nb + nc + 1);
    if (!out) return NULL;
    memcpy(out, a, na);
    memcpy(out + na, b, nb);
    memcpy(out + na + nb, c, nc + 1);
    return out;
}

/* The whole file, NUL-terminated, or NULL (errno set). */
static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *text = NULL;
    size_t size = 0, used = 0;
    for (;;) {
        if (used + 4096 + 1 > size) {
            size = 2 * size + 4096 + 1;
            char *bigger = realloc(text, size);
            if (!bigger) {
                free(text);
                fclose(f);
                errno = ENOMEM;
                return NULL;
            }
            text = bigger;
        }
        size_t got = fread(text + used, 1, 4096, f);
        used += got;
        if (got < 4096) break;
    }
    const int failed = ferror(f);
    fclose(f);
    if (failed) {
        free(text);
        errno = EIO;
        return NULL;
    }
    text[used] = '\0';
    return text;
}

/* Comments become blanks, so that the scanner never finds elements in them. */
static void blank_comments(char *text)
{
    char *p = text;
    while ((p = strstr(p, "<!--")) != NULL) {
        char *end = strstr(p + 4, "-->");
        char *stop = end ? end + 3 : p + strlen(p);
        memset(p, ' ', (size_t)(stop - p));
        p = stop;
    }
}

/* The '>' that closes the tag opened at `start`, quoted values skipped; NULL if none. */
static const char *tag_close(const char *start)
{
    char quote = 0;
    for (const char *p = start; *p; ++p) {
        if (quote) {
            if (*p == quote) quote = 0;
        } else if (*p == '"' || *p == '\'') {
            quote = *p;
        } else if (*p == '>') {
            return p;
        }
    }
    return NULL;
}

/* The next element `<name` (followed by a blank, '/' or '>') at or after p, before `limit` (NULL: none). */
static const char *find_element(const char *p, const char *name, const char *limit)
{
    const size_t n = strlen(name);
    while ((p = strchr(p, '<')) != NULL && (!limit || p < limit)) {
        const char c = p[1 + n];
        if (strncmp(p + 1, name, n) == 0 && (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '/' || c == '>'))
            return p;
        ++p;
    }
    return NULL;
}

/* The value of attribute `name` in the tag [start, close), entities decoded; NULL if absent (or out of memory). */
static char *attribute(const char *start, const char *close, const char *name)
{
    const size_t n = strlen(name);
    char quote = 0;
    for (const char *p = start; p < close; ++p) {
        if (quote) {
            if (*p == quote) quote = 0;
            continue;
        }
        if (*p == '"' || *p == '\'') {
            quote = *p;
            continue;
        }
        const char before = p > start ? p[-1] : ' ';
        if ((before == ' ' || before == '\t' || before == '\n' || before == '\r') && strncmp(p, name, n) == 0) {
            const char *q = p + n;
            while (*q == ' ' || *q == '\t' || *q == '\n' || *q == '\r') ++q;
            if (*q != '=') continue;
            ++q;
            while (*q == ' ' || *q == '\t' || *q == '\n' || *q == '\r') ++q;
            if (*q != '"' && *q != '\'') continue;
            const char *end = strchr(q + 1, *q);
            if (!end || end > close) return NULL;
            char *value = copy_string(q + 1, (size_t)(end - q - 1));
            if (!value) return NULL;
            static const struct { const char *entity, *text; } ENTITIES[] = {
                { "&amp;", "&" }, { "&lt;", "<" }, { "&gt;", ">" }, { "&quot;", "\"" }, { "&apos;", "'" } };
            char *w = value;
            for (const char *r = value; *r;) {
                size_t k = 0;
                while (k < sizeof ENTITIES / sizeof ENTITIES[0] &&
                       strncmp(r, ENTITIES[k].entity, strlen(ENTITIES[k].entity)) != 0)
                    ++k;
                if (k < sizeof ENTITIES / sizeof ENTITIES[0]) {
                    *w++ = ENTITIES[k].text[0];
                    r += strlen(ENTITIES[k].entity);
                } else {
                    *w++ = *r++;
                }
            }
            *w = '\0';
            return value;
        }
    }
    return NULL;
}

static bool parse_unsigned(const char *text, unsigned long *out)
{
    if (!text || !*text || *text == '-' || *text == '+') return false;
    char *end;
    errno = 0;
    *out = strtoul(text, &end, 10);
    return errno == 0 && *end == '\0';
}

/* An unsigned attribute: true and *out set, or false (absent or not a number). */
static bool unsigned_attribute(const char *start, const char *close, const char *name, unsigned long *out)
{
    char *text = attribute(start, close, name);
    const bool ok = parse_unsigned(text, out);
    free(text);
    return ok;
}

#define FAIL(...)                                \
    do {                                         \
        snprintf(err, n, __VA_ARGS__);          \
        return false;                            \
    } while (0)

static bool parse_variables(FmuImport *fmu, const char *text, const char *md_path, char *err, size_t n)
{
    const char *list = find_element(text, "ModelVariables", NULL);
    if (!list) FAIL("%s has no <ModelVariables>", md_path);
    const char *list_end = strstr(list, "</ModelVariables>");
    size_t capacity = 0;
    for (const char *p = list; (p = find_element(p, "ScalarVariable", list_end)) != NULL; ++p) ++capacity;
    fmu->variables = calloc(capacity ? capacity : 1, sizeof *fmu->variables);
    if (!fmu->variables) FAIL("out of memory reading %s", md_path);
    for (const char *p = list; (p = find_element(p, "ScalarVariable", list_end)) != NULL;) {
        const char *close = tag_close(p);
        if (!close) FAIL("%s: a <ScalarVariable> tag is not closed", md_path);
        FmuVariable *v = &fmu->variables[fmu->n_variables++];
        v->type = '?';
        v->name = attribute(p, close, "name");
        unsigned long vr;
        if (!v->name || !unsigned_attribute(p, close, "valueReference", &vr) || vr > UINT_MAX)
            FAIL("%s: ScalarVariable number %zu has no name or no valid valueReference", md_path, fmu->n_variables);
        v->vr = (unsigned int)vr;
        p = close + 1;
        if (close[-1] == '/') continue; /* no type element: left as '?' */
        const char *type = strchr(p, '<');
        if (!type) break;
        static const char *const TYPES[] = { "Real", "Integer", "Boolean", "String", "Enumeration" };
        for (size_t k = 0; k < sizeof TYPES / sizeof TYPES[0]; ++k) {
            const size_t len = strlen(TYPES[k]);
            if (strncmp(type + 1, TYPES[k], len) == 0 && strchr(" \t\r\n/>", type[1 + len])) {
                v->type = TYPES[k][0];
                const char *type_close = tag_close(type);
                if (!type_close) FAIL("%s: the type of variable %s is not closed", md_path, v->name);
                unsigned long d;
                if (unsigned_attribute(type, type_close, "derivative", &d)) {
                    if (d == 0 || d > INT_MAX) FAIL("%s: variable %s has derivative=\"%lu\"", md_path, v->name, d);
                    v->derivative = (int)d;
                }
                p = type_close + 1;
                break;
            }
        }
    }
    return true;
}

static bool parse_structure(FmuImport *fmu, const char *text, const char *md_path, char *err, size_t n)
{
    const char *derivatives = find_element(text, "Derivatives", NULL);
    size_t count = 0;
    const char *end = derivatives ? strstr(derivatives, "</Derivatives>") : NULL;
    if (derivatives && end)
        for (const char *p = derivatives; (p = find_element(p, "Unknown", end)) != NULL; ++p) ++count;
    if (count == 0) FAIL("%s declares no continuous states (<ModelStructure><Derivatives> is empty)", md_path);
    fmu->nx = count;
    fmu->state_vr = calloc(count, sizeof *fmu->state_vr);
    fmu->derivative_vr = calloc(count, sizeof *fmu->derivative_vr);
    if (!fmu->state_vr || !fmu->derivative_vr) FAIL("out of memory reading %s", md_path);
    size_t i = 0;
    for (const char *p = derivatives; (p = find_element(p, "Unknown", end)) != NULL; ++p, ++i) {
        const char *close = tag_close(p);
        unsigned long index;
        if (!close || !unsigned_attribute(p, close, "index", &index) || index == 0 || index > fmu->n_variables)
            FAIL("%s: <Derivatives> entry %zu has no valid index", md_path, i + 1);
        const FmuVariable *der = &fmu->variables[index - 1];
        if (der->type != 'R' || der->derivative == 0 || (size_t)der->derivative > fmu->n_variables)
            FAIL("%s: <Derivatives> entry %zu (%s) is not a Real with a valid derivative attribute", md_path, i + 1,
                 der->name);
        fmu->derivative_vr[i] = der->vr;
        fmu->state_vr[i] = fmu->variables[der->derivative - 1].vr;
    }
    return true;
}

static bool parse_description(FmuImport *fmu, const char *md_path, char *err, size_t n)
{
    char *text = read_text(md_path);
    if (!text)
        FAIL("cannot read %s (%s): pass an extracted FMU directory, or the library inside one "
             "(<dir>/binaries/" PLATFORM "/<modelIdentifier>.so, with <dir>/modelDescription.xml)", md_path,
             strerror(errno));
    blank_comments(text);
    bool ok = false;
    const char *root = find_element(text, "fmiModelDescription", NULL);
    const char *root_close = root ? tag_close(root) : NULL;
    const char *me = find_element(text, "ModelExchange", NULL);
    const char *me_close = me ? tag_close(me) : NULL;
    char *version = root_close ? attribute(root, root_close, "fmiVersion") : NULL;
    char *nz_text = root_close ? attribute(root, root_close, "numberOfEventIndicators") : NULL;
    unsigned long nz = 0;
    if (!root_close) {
        snprintf(err, n, "%s is not an FMI model description (no <fmiModelDescription>)", md_path);
    } else if (!version || strcmp(version, "2.0") != 0) {
        snprintf(err, n, "%s: fmiVersion is \"%s\"; this driver imports FMI 2.0", md_path, version ? version : "");
    } else if (!(fmu->guid = attribute(root, root_close, "guid"))) {
        snprintf(err, n, "%s has no guid", md_path);
    } else if (!me_close || !(fmu->model_identifier = attribute(me, me_close, "modelIdentifier"))) {
        snprintf(err, n, "%s declares no Model Exchange interface (<ModelExchange modelIdentifier=...>)", md_path);
    } else if (nz_text && !parse_unsigned(nz_text, &nz)) {
        snprintf(err, n, "%s: numberOfEventIndicators = \"%s\" is not a number", md_path, nz_text);
    } else {
        fmu->nz = nz;
        ok = parse_variables(fmu, text, md_path, err, n) && parse_structure(fmu, text, md_path, err, n);
    }
    free(nz_text);
    free(version);
    free(text);
    return ok;
}

static bool ends_with(const char *s, const char *suffix)
{
    const size_t ns = strlen(s), nf = strlen(suffix);
    return ns >= nf && strcmp(s + ns - nf, suffix) == 0;
}

/* `path` without its last `levels` components ("/" at least). */
static char *parent(const char *path, int levels)
{
    char *out = copy_string(path, strlen(path));
    if (!out) return NULL;
    for (int k = 0; k < levels; ++k) {
        char *slash = strrchr(out, '/');
        if (!slash) break;
        if (slash == out) {
            out[1] = '\0';
            break;
        }
        *slash = '\0';
    }
    return out;
}

bool fmu_import_open(FmuImport *fmu, const char *path, char *err, size_t n)
{
    memset(fmu, 0, sizeof *fmu);
    struct stat st;
    char resolved[PATH_MAX];
    if (!path || stat(path, &st) != 0 || !realpath(path, resolved))
        FAIL("%s: %s (give an extracted FMU directory or its binaries/" PLATFORM "/<id>.so)", path ? path : "(none)",
             strerror(errno));
    char *md_path = NULL;
    if (S_ISDIR(st.st_mode)) {
        fmu->fmu_dir = copy_string(resolved, strlen(resolved));
    } else if (ends_with(resolved, ".fmu")) {
        FAIL("%s is a zipped FMU: extract it first (unzip -d DIR, or fmpy.extract) and pass the directory", path);
    } else {
        fmu->library_path = copy_string(resolved, strlen(resolved));
        fmu->fmu_dir = parent(resolved, 3); /* <dir>/binaries/linux64/<id>.so */
    }
    if (!fmu->fmu_dir || !(md_path = join(fmu->fmu_dir, "/", "modelDescription.xml"))) FAIL("out of memory");
    const bool parsed = parse_description(fmu, md_path, err, n);
    free(md_path);
    if (!parsed) return false;
    if (!fmu->library_path) {
        fmu->library_path = join(fmu->fmu_dir, "/binaries/" PLATFORM "/", fmu->model_identifier);
        char *with_suffix = fmu->library_path ? join(fmu->library_path, ".so", "") : NULL;
        free(fmu->library_path);
        fmu->library_path = with_suffix;
        if (!fmu->library_path) FAIL("out of memory");
    }
    if (!(fmu->resource_uri = join("file://", fmu->fmu_dir, "/resources"))) FAIL("out of memory");
    return fmi2_functions_load(&fmu->fmi, fmu->library_path, true, false, err, n);
}

void fmu_import_close(FmuImport *fmu)
{
    fmi2_functions_unload(&fmu->fmi);
    for (size_t i = 0; i < fmu->n_variables; ++i) free(fmu->variables[i].name);
    free(fmu->variables);
    free(fmu->state_vr);
    free(fmu->derivative_vr);
    free(fmu->guid);
    free(fmu->model_identifier);
    free(fmu->fmu_dir);
    free(fmu->library_path);
    free(fmu->resource_uri);
    memset(fmu, 0, sizeof *fmu);
}

const FmuVariable *fmu_import_variable(const FmuImport *fmu, const char *name, char type)
{
    for (size_t i = 0; i < fmu->n_variables; ++i)
        if (fmu->variables[i].type == type && strcmp(fmu->variables[i].name, name) == 0) return &fmu->variables[i];
    return NULL;
}
