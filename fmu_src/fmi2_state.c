/* FMI 2.0 FMU state: get, set, free, serialize, deserialize.
 *
 * A state is a Snapshot, a plain struct with no pointers. Co-Simulation
 * restarts CVODE wherever a state is taken or restored, so the snapshot
 * holds everything either interface needs to continue identically.
 *
 * Serialized form (little endian), self-describing and versioned:
 *   "PRODSTAT" | u32 version | u32 guid length | guid | u32 field count |
 *   fields: u8 name length, name, u8 type ('d' double, 'i' int32), value |
 *   u32 FNV-1a checksum of everything before it.
 * Deserializing checks every part and names what is wrong. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fmi2_instance.h"
#include "model_guid.h"

#define MAGIC "PRODSTAT"
#define FORMAT_VERSION 1u

typedef struct {
    double time, params[4], x[ROD_NX], z_at_restart[ROD_NZ];
    double window_start, tolerance, last_successful_time;
    int32_t type, state, contact, slip, initial_event, events_in_window;
} Snapshot;

/* The fields in serialized order: name, offset, type. */
typedef struct {
    const char *name;
    size_t offset;
    char type;
} Field;

#define D(name, member) { name, offsetof(Snapshot, member), 'd' }
#define I(name, member) { name, offsetof(Snapshot, member), 'i' }
static const Field FIELDS[] = {
    D("time", time), D("alpha", params[0]), D("mu", params[1]), D("delta", params[2]), D("epsilon", params[3]),
    D("x", x[0]), D("v", x[1]), D("y", x[2]), D("w", x[3]), D("theta", x[4]), D("phi", x[5]),
    D("z0", z_at_restart[0]), D("z1", z_at_restart[1]), D("z2", z_at_restart[2]), D("z3", z_at_restart[3]),
    D("window_start", window_start), D("tolerance", tolerance), D("last_successful_time", last_successful_time),
    I("interface", type), I("instance_state", state), I("contact", contact), I("mode", slip),
    I("initial_event", initial_event), I("events_in_window", events_in_window),
};
#define N_FIELDS (sizeof FIELDS / sizeof FIELDS[0])

static Snapshot take(const Instance *in)
{
    const Model *m = &in->model;
    Snapshot s = { .time = in->time, .window_start = in->window_start, .tolerance = in->tolerance,
                   .last_successful_time = in->last_successful_time, .type = (int32_t)in->type,
                   .state = (int32_t)in->state, .contact = m->mode.contact, .slip = m->mode.slip,
                   .initial_event = in->initial_event, .events_in_window = in->events_in_window };
    const double p[4] = { m->params.alpha, m->params.mu, m->params.delta, m->params.epsilon };
    memcpy(s.params, p, sizeof p);
    memcpy(s.x, m->x, sizeof s.x);
    memcpy(s.z_at_restart, in->z_at_restart, sizeof s.z_at_restart);
    return s;
}

static void restore(Instance *in, const Snapshot *s)
{
    Model *m = &in->model;
    in->time = s->time;
    m->params = (RodParams){ s->params[0], s->params[1], s->params[2], s->params[3] };
    memcpy(m->x, s->x, sizeof m->x);
    m->mode = (RodMode){ s->contact != 0, (int)s->slip };
    m->stale = true;
    memcpy(in->z_at_restart, s->z_at_restart, sizeof in->z_at_restart);
    in->window_start = s->window_start;
    in->tolerance = s->tolerance;
    in->last_successful_time = s->last_successful_time;
    in->initial_event = s->initial_event != 0;
    in->events_in_window = (int)s->events_in_window;
    in->state = (InstanceState)s->state;
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
    REQUIRE("fmi2SetFMUstate", s->type == (int32_t)in->type,
            "the state was taken from an instance of the other interface");
    restore(in, s);
    in->solver_live = false;
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
        const unsigned char len = (unsigned char)strlen(FIELDS[i].name), type = (unsigned char)FIELDS[i].type;
        put(&k, &len, 1);
        put(&k, FIELDS[i].name, len);
        put(&k, &type, 1);
        const char *at = (const char *)s + FIELDS[i].offset;
        if (type == 'd') {
            uint64_t bits;
            memcpy(&bits, at, 8);
            put_u64(&k, bits);
        } else {
            int32_t v;
            memcpy(&v, at, 4);
            put_u32(&k, (uint32_t)v);
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

/* Reads one field into s; NULL on success, else what is wrong. */
static const char *read_field(Cursor *k, const Field *f, Snapshot *s)
{
    unsigned char len, type;
    char name[256];
    if (!take_bytes(k, &len, 1) || !take_bytes(k, name, len) || !take_bytes(k, &type, 1)) return "truncated";
    name[len] = '\0';
    if (strcmp(name, f->name) != 0 || type != (unsigned char)f->type) return "unexpected field";
    uint32_t lo, hi = 0;
    if (!take_u32(k, &lo) || (type == 'd' && !take_u32(k, &hi))) return "truncated";
    char *at = (char *)s + f->offset;
    if (type == 'd') {
        const uint64_t bits = (uint64_t)hi << 32 | lo;
        memcpy(at, &bits, 8);
    } else {
        const int32_t v = (int32_t)lo;
        memcpy(at, &v, 4);
    }
    return NULL;
}

/* Values a state of this model can hold; NULL if all are. */
static const char *implausible(const Snapshot *s)
{
    for (unsigned int i = 0; i < 4; ++i)
        if (model_check_real(VR_ALPHA + i, s->params[i])) return model_real_info(VR_ALPHA + i)->name;
    for (unsigned int i = 0; i < ROD_NX; ++i)
        if (model_check_real(VR_X + i, s->x[i])) return model_real_info(VR_X + i)->name;
    if (!isfinite(s->time)) return "time";
    if (s->type != fmi2ModelExchange && s->type != fmi2CoSimulation) return "interface";
    if (s->slip < -1 || s->slip > 1 || (s->contact != 0 && s->contact != 1)) return "mode";
    if (s->state <= 0 || s->state > Error || (s->state & (s->state - 1))) return "instance_state";
    return NULL;
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
    for (size_t i = 0; i < N_FIELDS; ++i) {
        const char *wrong = read_field(&k, &FIELDS[i], &s);
        REQUIRE(call, !wrong, "field %zu ('%s'): %s", i, FIELDS[i].name, wrong);
    }
    const size_t body = k.at;
    REQUIRE(call, take_u32(&k, &checksum) && checksum == fnv1a(k.in, body), "checksum mismatch: the bytes are corrupted");
    REQUIRE(call, k.at == size, "%zu bytes after the end of the state", size - k.at);
    const char *bad = implausible(&s);
    REQUIRE(call, !bad, "field '%s' holds a value this model cannot have", bad);
    Snapshot *out = *state ? (Snapshot *)*state : in->cb.allocateMemory(1, sizeof(Snapshot));
    REQUIRE(call, out, "out of memory");
    *out = s;
    *state = out;
    return fmi2OK;
}
