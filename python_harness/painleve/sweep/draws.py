# SPDX-License-Identifier: BSD-2-Clause
"""A random sweep's uniform draws, `np.random.default_rng([seed, id]).random(n)` for many ids at
once: numpy's SeedSequence (its entropy pool of four 32-bit words, hashmix and mix) and PCG64
(a 128-bit LCG, XSL-RR output; random() is the top 53 bits) written over arrays of ids. A
generator made per case costs about 15 us, as much as the rest of a sweep's Python for its row;
the same numbers over arrays cost well under 1 us a case. The values are numpy's
bit for bit (tests/sweep/test_draws.py compares them); ids or seeds outside [0, 2^32) go through
default_rng itself."""
import numpy as np

U32, U64 = np.uint32, np.uint64
INIT_A, MULT_A, INIT_B, MULT_B = 0x43B0D7E5, 0x931E8875, 0x8B51F9DD, 0x58F38DED
MIX_MULT_L, MIX_MULT_R, XSHIFT = 0xCA01F9DD, 0x4973F715, 16
POOL = 4
PCG_MULT = (2549297995355413924, 4865540595714422341)      # the LCG's multiplier (high, low 64 bits)
MASK32 = 0xFFFFFFFF


def _hashmix(value, hash_const):
    """(hashmix(value), the next hash constant), as SeedSequence's (uint32, wrapping)."""
    value = value ^ U32(hash_const)
    hash_const = (hash_const * MULT_A) & MASK32
    value = value * U32(hash_const)
    return value ^ (value >> U32(XSHIFT)), hash_const


def _mix(x, y):
    result = U32(MIX_MULT_L) * x - U32(MIX_MULT_R) * y
    return result ^ (result >> U32(XSHIFT))


def _pool(entropy):
    """SeedSequence's mixed pool of entropy words [n words][ids] (uint32 arrays): [4][ids]."""
    hash_const, mixer = INIT_A, []
    for i in range(POOL):
        value, hash_const = _hashmix(entropy[i] if i < len(entropy) else np.zeros_like(entropy[0]), hash_const)
        mixer.append(value)
    for src in range(POOL):
        for dst in range(POOL):
            if src != dst:
                value, hash_const = _hashmix(mixer[src], hash_const)
                mixer[dst] = _mix(mixer[dst], value)
    for src in range(POOL, len(entropy)):
        for dst in range(POOL):
            value, hash_const = _hashmix(entropy[src], hash_const)
            mixer[dst] = _mix(mixer[dst], value)
    return mixer


def _state_words(mixer, n_words):
    """SeedSequence.generate_state(n_words // 2, uint64) as uint64 arrays (two 32-bit words each)."""
    hash_const, words = INIT_B, []
    for i in range(n_words):
        value = mixer[i % POOL] ^ U32(hash_const)
        hash_const = (hash_const * MULT_B) & MASK32
        value = value * U32(hash_const)
        words.append(value ^ (value >> U32(XSHIFT)))
    return [words[k].astype(U64) | (words[k + 1].astype(U64) << U64(32)) for k in range(0, n_words, 2)]


def _mul_64(a, b):
    """The full product of uint64 arrays a, b: (high, low) 64 bits."""
    a_lo, a_hi, b_lo, b_hi = a & U64(MASK32), a >> U64(32), b & U64(MASK32), b >> U64(32)
    lo_lo, hi_lo, lo_hi, hi_hi = a_lo * b_lo, a_hi * b_lo, a_lo * b_hi, a_hi * b_hi
    cross = (lo_lo >> U64(32)) + (hi_lo & U64(MASK32)) + lo_hi
    return hi_hi + (hi_lo >> U64(32)) + (cross >> U64(32)), (cross << U64(32)) | (lo_lo & U64(MASK32))


def _add_128(a, b):
    hi, lo = a[0] + b[0], a[1] + b[1]
    return hi + (lo < a[1]).astype(U64), lo


def _step(state, inc):
    """state * PCG_MULT + inc (mod 2^128); 128-bit numbers as (high, low) uint64 arrays."""
    hi, lo = state
    m_hi, m_lo = U64(PCG_MULT[0]), U64(PCG_MULT[1])
    p_hi, p_lo = _mul_64(lo, np.full_like(lo, m_lo))
    return _add_128((p_hi + hi * m_lo + lo * m_hi, p_lo), inc)


def uniform(seed, ids, n):
    """[len(ids), n] float64: row k is np.random.default_rng([seed, ids[k]]).random(n)."""
    ids = np.asarray(ids, dtype=np.int64)
    if not (0 <= seed <= MASK32) or (ids.size and (ids.min() < 0 or ids.max() > MASK32)):
        return np.array([np.random.default_rng([seed, int(i)]).random(n) for i in ids]).reshape(-1, n)
    entropy = [np.full(ids.shape, seed, dtype=U32), ids.astype(U32)]
    seed_hi, seed_lo, inc_hi, inc_lo = _state_words(_pool(entropy), 8)
    # PCG64's seeding (pcg_setseq_128_srandom_r): inc = initseq << 1 | 1; state = 0, step, += initstate, step.
    inc = ((inc_hi << U64(1)) | (inc_lo >> U64(63)), (inc_lo << U64(1)) | U64(1))
    zero = np.zeros_like(seed_lo)
    state = _step(_add_128(_step((zero, zero), inc), (seed_hi, seed_lo)), inc)
    out = np.empty((ids.size, n))
    for k in range(n):      # each draw: a step, then XSL-RR of the new state, its top 53 bits
        state = _step(state, inc)
        xored, rot = state[0] ^ state[1], state[0] >> U64(58)
        word = (xored >> rot) | (xored << ((U64(64) - rot) & U64(63)))
        out[:, k] = (word >> U64(11)) * (1.0 / 9007199254740992.0)
    return out
