/* SPDX-License-Identifier: BSD-2-Clause */
/* An instance's FMU state under any FMI version: a snapshot, its checked
 * byte layout. The FMI layers allocate, hand over and free the snapshots.
 *
 * A snapshot holds the instance's own fields and a copy of the model (plain
 * data, no pointers). Co-Simulation restarts its integrator (the one the
 * trajectory has: the explicit pair, or CVODE after a hand-over) wherever a
 * state is taken or restored, so the snapshot holds everything either
 * interface needs to continue identically.
 *
 * Serialized form (little endian), self-describing and versioned:
 *   "PRODSTAT" | u32 version | u32 guid length | guid | u32 field count |
 *   fields: u8 name length, name, u8 type ('d' double, 'i' int32, 'b' bool as
 *   int32 0 or 1), value | u32 FNV-1a checksum of everything before it.
 * The fields are the instance's, then the model's (model.h, model_fields).
 * Deserializing checks every part and names what is wrong. */
#include "instance_state.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "model_description.h"

/* Fails the call with a message unless cond holds. */
#define CHECK(call, cond, ...) \
    if (!(cond)) return instance_fail(in, call, __VA_ARGS__)

#define MAGIC "PRODSTAT"
#define FORMAT_VERSION 3u   /* 3: the record holds solver_implicit */

typedef struct {
    double time, tolerance, last_successful_time;
    int interface, state;
    bool solver_implicit; /* Co-Simulation's trajectory is CVODE's: a restored run goes on with it */
    Model model;
} Snapshot;

static const ModelField INSTANCE_FIELDS[] = {
    { "time", offsetof(Snapshot, time), TYPE_REAL },
    { "tolerance", offsetof(Snapshot, tolerance), TYPE_REAL },
    { "last_successful_time", offsetof(Snapshot, last_successful_time), TYPE_REAL },
    { "interface", offsetof(Snapshot, interface), TYPE_INTEGER },
    { "instance_state", offsetof(Snapshot, state), TYPE_INTEGER },
    { "solver_implicit", offsetof(Snapshot, solver_implicit), TYPE_BOOLEAN },
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

size_t instance_snapshot_size(void)
{
    return sizeof(Snapshot);
}

void instance_snapshot_take(Instance *in, void *snapshot)
{
    *(Snapshot *)snapshot = (Snapshot){ .time = in->time, .tolerance = in->tolerance,
                                        .last_successful_time = in->last_successful_time,
                                        .interface = (int)in->interface, .state = (int)in->state,
                                        .solver_implicit = in->solver_implicit, .model = in->model };
    /* Co-Simulation restarts its integrator here, as a run restored from this state will:
     * both continue from the same solver state, bit for bit. */
    in->solver_live = false;
}

Status instance_snapshot_restore(Instance *in, const char *call, const void *snapshot)
{
    const Snapshot *s = snapshot;
    if (s->interface != (int)in->interface)
        return instance_fail(in, call, "the state was taken from an instance of the other interface");
    in->time = s->time;
    in->tolerance = s->tolerance;
    in->last_successful_time = s->last_successful_time;
    in->state = (InstanceState)s->state;
    model_restore(&in->model, &s->model);
    in->solver_live = false;    /* Co-Simulation restarts its integrator from the restored state */
    in->solver_implicit = s->solver_implicit;
    return STATUS_OK;
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

size_t instance_snapshot_serialize(const void *snapshot, unsigned char *out)
{
    const Snapshot *s = snapshot;
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
    if (s->interface != MODEL_EXCHANGE && s->interface != CO_SIMULATION) return "interface";
    if (s->state <= 0 || s->state > Error || (s->state & (s->state - 1))) return "instance_state";
    return model_implausible(&s->model);
}

Status instance_snapshot_deserialize(Instance *in, const char *call, const unsigned char *bytes, size_t size,
                                     void *snapshot)
{
    Cursor k = { .in = bytes, .size = size };
    char magic[8], guid[64];
    uint32_t version = 0, guid_len = 0, n_fields = 0, checksum = 0;
    CHECK(call, take_bytes(&k, magic, 8) && memcmp(magic, MAGIC, 8) == 0,
            "not a %s FMU state (%zu bytes, no 'PRODSTAT' header)", MODEL_NAME, size);
    /* The checksum first: any damage is named as such, wherever it is. */
    Cursor tail = { .in = k.in, .at = size - 4, .size = size };
    CHECK(call, size >= 12 && take_u32(&tail, &checksum) && checksum == fnv1a(k.in, size - 4),
            "checksum mismatch: the bytes are truncated or corrupted");
    CHECK(call, take_u32(&k, &version) && version == FORMAT_VERSION,
            "state format version %u, this binary reads version %u", version, FORMAT_VERSION);
    CHECK(call, take_u32(&k, &guid_len) && guid_len < sizeof guid && take_bytes(&k, guid, guid_len),
            "truncated or corrupted GUID");
    guid[guid_len] = '\0';
    CHECK(call, strcmp(guid, MODEL_GUID) == 0, "state of model %s, this FMU is %s", guid, MODEL_GUID);
    CHECK(call, take_u32(&k, &n_fields) && n_fields == N_FIELDS, "%u fields, expected %zu", n_fields,
            (size_t)N_FIELDS);
    Snapshot s;
    memset(&s, 0, sizeof s);
    model_reset(&s.model);
    for (size_t i = 0; i < N_FIELDS; ++i) {
        const ModelField f = field(i);
        const char *wrong = read_field(&k, &f, &s);
        CHECK(call, !wrong, "field %zu ('%s'): %s", i, f.name, wrong);
    }
    CHECK(call, k.at == size - 4, "%zu bytes after the end of the state", size - 4 - k.at);
    const char *bad = implausible(&s);
    CHECK(call, !bad, "field '%s' holds a value this model cannot have", bad);
    *(Snapshot *)snapshot = s;
    return STATUS_OK;
}
