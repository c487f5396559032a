/* FMI 2.0 FMU state: get, set, free, serialize, deserialize.
 *
 * A state is a Snapshot: the instance's own fields and a copy of the model
 * (plain data, no pointers). Co-Simulation restarts CVODE wherever a state is
 * taken or restored, so the snapshot holds everything either interface needs
 * to continue identically.
 *
 * Serialized form (little endian), self-describing and versioned:
 *   "PRODSTAT" | u32 version | u32 guid length | guid | u32 field count |
 *   fields: u8 name length, name, u8 type ('d' double, 'i' int32, 'b' bool as
 *   int32 0 or 1), value | u32 FNV-1a checksum of everything before it.
 * The fields are the instance's, then the model's (model.h, model_fields).
 * Deserializing checks every part and names what is wrong. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fmi2_instance.h"
#include "model_description.h"

#define MAGIC "PRODSTAT"
#define FORMAT_VERSION 2u

typedef struct {
    double time, tolerance, last_successful_time;
    int type, state;
    Model model;
} Snapshot;

static const ModelField INSTANCE_FIELDS[] = {
    { "time", offsetof(Snapshot, time), TYPE_REAL },
    { "tolerance", offsetof(Snapshot, tolerance), TYPE_REAL },
    { "last_successful_time", offsetof(Snapshot, last_successful_time), TYPE_REAL },
    { "interface", offsetof(Snapshot, type), TYPE_INTEGER },
    { "instance_state", offsetof(Snapshot, state), TYPE_INTEGER },
};
#define N_INSTANCE_FIELDS (sizeof INSTANCE_FIELDS / sizeof INSTANCE_FIELDS[0])
#define N_FIELDS (N_INSTANCE_FIELDS + model_n_fields)

/* Field i of a snapshot, its offset counted from the snapshot's start. */
static ModelField field(size_t i)
{
    if (i < N_INSTANCE_FIELDS) return INSTANCE_FIELDS[i];
    ModelField f = model_fields[i - N_INSTANCE_FIELDS];
    f.offset += offsetof(Snapshot, model);
    return f;
}

static const char TYPE_CODE[] = { [TYPE_REAL] = 'd', [TYPE_INTEGER] = 'i', [TYPE_BOOLEAN] = 'b' };

static Snapshot take(const Instance *in)
{
    return (Snapshot){ .time = in->time, .tolerance = in->tolerance, .last_successful_time = in->last_successful_time,
                       .type = (int)in->type, .state = (int)in->state, .model = in->model };
}

static void restore(Instance *in, const Snapshot *s)
{
    in->time = s->time;
    in->tolerance = s->tolerance;
    in->last_successful_time = s->last_successful_time;
    in->state = (InstanceState)s->state;
    model_restore(&in->model, &s->model);
    /* Co-Simulation restarts CVODE from the restored state. */
    in->solver_live = false;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    BEGIN("fmi2GetFMUstate", ANY_BUT_FATAL & ~Error);
    REQUIRE("fmi2GetFMUstate", state, "FMUstate pointer is NULL");
    Snapshot *s = *state ? (Snapshot *)*state : in->cb.allocateMemory(1, sizeof(Snapshot));
    REQUIRE("fmi2GetFMUstate", s, "out of memory");
    *s = take(in);
    *state = s;
    /* Co-Simulation restarts CVODE here, as a run restored from this state will:
     * both continue from the same solver state, bit for bit. */
    in->solver_live = false;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    BEGIN("fmi2SetFMUstate", ANY_BUT_FATAL);
    REQUIRE("fmi2SetFMUstate", state, "FMUstate is NULL");
    const Snapshot *s = state;
    REQUIRE("fmi2SetFMUstate", s->type == (int)in->type, "the state was taken from an instance of the other interface");
    restore(in, s);
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    BEGIN("fmi2FreeFMUstate", ANY_BUT_FATAL);
    REQUIRE("fmi2FreeFMUstate", state, "FMUstate pointer is NULL");
    if (*state) in->cb.freeMemory(*state);
    *state = NULL;
    return fmi2OK;
}

/* --- byte layout */

static uint32_t fnv1a(const unsigned char *b, size_t n)
{
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 16777619u;
    return h;
}

typedef struct {
    unsigned char *out; /* NULL: only count */
    const unsigned char *in;
    size_t at, size;
} Cursor;

static void put(Cursor *k, const void *p, size_t n)
{
    if (k->out) memcpy(k->out + k->at, p, n);
    k->at += n;
}

static void put_u32(Cursor *k, uint32_t v)
{
    const unsigned char b[4] = { (unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                                 (unsigned char)(v >> 24) };
    put(k, b, 4);
}

static void put_u64(Cursor *k, uint64_t v)
{
    put_u32(k, (uint32_t)v);
    put_u32(k, (uint32_t)(v >> 32));
}

static size_t write_state(const Snapshot *s, unsigned char *out)
{
    Cursor k = { .out = out };
    put(&k, MAGIC, 8);
    put_u32(&k, FORMAT_VERSION);
    put_u32(&k, (uint32_t)strlen(MODEL_GUID));
    put(&k, MODEL_GUID, strlen(MODEL_GUID));
    put_u32(&k, (uint32_t)N_FIELDS);
    for (size_t i = 0; i < N_FIELDS; ++i) {
        const ModelField f = field(i);
        const unsigned char len = (unsigned char)strlen(f.name), type = (unsigned char)TYPE_CODE[f.type];
        put(&k, &len, 1);
        put(&k, f.name, len);
        put(&k, &type, 1);
        const char *at = (const char *)s + f.offset;
        if (f.type == TYPE_REAL) {
            uint64_t bits;
            memcpy(&bits, at, 8);
            put_u64(&k, bits);
        } else if (f.type == TYPE_INTEGER) {
            int v;
            memcpy(&v, at, sizeof v);
            put_u32(&k, (uint32_t)(int32_t)v);
        } else {
            bool b;
            memcpy(&b, at, sizeof b);
            put_u32(&k, b ? 1u : 0u);
        }
    }
    if (out) put_u32(&k, fnv1a(out, k.at));
    else k.at += 4;
    return k.at;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size)
{
    BEGIN("fmi2SerializedFMUstateSize", ANY_BUT_FATAL);
    REQUIRE("fmi2SerializedFMUstateSize", state && size, "FMUstate or size is NULL");
    *size = write_state(state, NULL);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size)
{
    BEGIN("fmi2SerializeFMUstate", ANY_BUT_FATAL);
    REQUIRE("fmi2SerializeFMUstate", state && bytes, "FMUstate or bytes is NULL");
    const size_t needed = write_state(state, NULL);
    REQUIRE("fmi2SerializeFMUstate", size >= needed, "%zu bytes given, the state needs %zu", size, needed);
    write_state(state, (unsigned char *)bytes);
    return fmi2OK;
}

static bool take_bytes(Cursor *k, void *p, size_t n)
{
    if (n > k->size - k->at) return false;
    memcpy(p, k->in + k->at, n);
    k->at += n;
    return true;
}

static bool take_u32(Cursor *k, uint32_t *v)
{
    unsigned char b[4];
    if (!take_bytes(k, b, 4)) return false;
    *v = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    return true;
}

/* Reads field f into s; NULL on success, else what is wrong. */
static const char *read_field(Cursor *k, const ModelField *f, Snapshot *s)
{
    unsigned char len, type;
    char name[256];
    if (!take_bytes(k, &len, 1) || !take_bytes(k, name, len) || !take_bytes(k, &type, 1)) return "truncated";
    name[len] = '\0';
    if (strcmp(name, f->name) != 0 || type != (unsigned char)TYPE_CODE[f->type]) return "unexpected field";
    uint32_t lo, hi = 0;
    if (!take_u32(k, &lo) || (f->type == TYPE_REAL && !take_u32(k, &hi))) return "truncated";
    char *at = (char *)s + f->offset;
    if (f->type == TYPE_REAL) {
        const uint64_t bits = (uint64_t)hi << 32 | lo;
        memcpy(at, &bits, 8);
    } else if (f->type == TYPE_INTEGER) {
        const int v = (int32_t)lo;
        memcpy(at, &v, sizeof v);
    } else {
        if (lo > 1) return "a Boolean that is neither 0 nor 1";
        const bool b = lo == 1;
        memcpy(at, &b, sizeof b);
    }
    return NULL;
}

/* Values a state of this instance can hold; NULL if all are. */
static const char *implausible(const Snapshot *s)
{
    if (!isfinite(s->time)) return "time";
    if (!isfinite(s->tolerance) || s->tolerance <= 0) return "tolerance";
    if (s->type != fmi2ModelExchange && s->type != fmi2CoSimulation) return "interface";
    if (s->state <= 0 || s->state > Error || (s->state & (s->state - 1))) return "instance_state";
    return model_implausible(&s->model);
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate *state)
{
    static const char call[] = "fmi2DeSerializeFMUstate";
    BEGIN(call, ANY_BUT_FATAL);
    REQUIRE(call, bytes && state, "bytes or FMUstate pointer is NULL");
    Cursor k = { .in = (const unsigned char *)bytes, .size = size };
    char magic[8], guid[64];
    uint32_t version = 0, guid_len = 0, n_fields = 0, checksum = 0;
    REQUIRE(call, take_bytes(&k, magic, 8) && memcmp(magic, MAGIC, 8) == 0,
            "not a PainleveRod FMU state (%zu bytes, no 'PRODSTAT' header)", size);
    /* The checksum first: any damage is named as such, wherever it is. */
    Cursor tail = { .in = k.in, .at = size - 4, .size = size };
    REQUIRE(call, size >= 12 && take_u32(&tail, &checksum) && checksum == fnv1a(k.in, size - 4),
            "checksum mismatch: the bytes are truncated or corrupted");
    REQUIRE(call, take_u32(&k, &version) && version == FORMAT_VERSION,
            "state format version %u, this binary reads version %u", version, FORMAT_VERSION);
    REQUIRE(call, take_u32(&k, &guid_len) && guid_len < sizeof guid && take_bytes(&k, guid, guid_len),
            "truncated or corrupted GUID");
    guid[guid_len] = '\0';
    REQUIRE(call, strcmp(guid, MODEL_GUID) == 0, "state of model %s, this FMU is %s", guid, MODEL_GUID);
    REQUIRE(call, take_u32(&k, &n_fields) && n_fields == N_FIELDS, "%u fields, expected %zu", n_fields,
            (size_t)N_FIELDS);
    Snapshot s;
    memset(&s, 0, sizeof s);
    model_reset(&s.model);
    for (size_t i = 0; i < N_FIELDS; ++i) {
        const ModelField f = field(i);
        const char *wrong = read_field(&k, &f, &s);
        REQUIRE(call, !wrong, "field %zu ('%s'): %s", i, f.name, wrong);
    }
    REQUIRE(call, k.at == size - 4, "%zu bytes after the end of the state", size - 4 - k.at);
    const char *bad = implausible(&s);
    REQUIRE(call, !bad, "field '%s' holds a value this model cannot have", bad);
    Snapshot *out = *state ? (Snapshot *)*state : in->cb.allocateMemory(1, sizeof(Snapshot));
    REQUIRE(call, out, "out of memory");
    *out = s;
    *state = out;
    return fmi2OK;
}
