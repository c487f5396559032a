/* SPDX-License-Identifier: BSD-2-Clause */
/* What the fuzz targets (fuzz_fmi.c for FMI 2.0, fuzz_fmi3.c for FMI 3.0) read
 * from libFuzzer's bytes: one byte, or a double that is an edge value, a modest
 * decimal or any bit pattern; and the invariant that aborts (a finding). Each
 * target defines FUZZ_NAME before including this header. */
#ifndef FUZZ_BYTES_H
#define FUZZ_BYTES_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define INVARIANT(cond, ...)                                                  \
    do {                                                                      \
        if (!(cond)) {                                                        \
            fprintf(stderr, FUZZ_NAME ": invariant broken: " __VA_ARGS__);   \
            fprintf(stderr, "\n");                                            \
            abort();                                                          \
        }                                                                     \
    } while (0)

typedef struct {
    const uint8_t *p;
    size_t n;
} Bytes;

/* The next byte; 0 once the bytes run out. */
static inline uint8_t take(Bytes *b)
{
    if (!b->n) return 0;
    --b->n;
    return *b->p++;
}

/* Values that sit on edges: IEEE specials, the ranges' ends and just past them. */
static inline double special_double(unsigned k)
{
    static const double table[] = {
        0.0, -0.0, 1.0, -1.0, NAN, -NAN, INFINITY, -INFINITY,
        DBL_MIN, -DBL_MIN, 4.9406564584124654e-324, -4.9406564584124654e-324, 1e-310, DBL_MAX, -DBL_MAX, 1e300,
        1e-300, 1e-8, 9.9999999999999994e-09 * (1 - 1e-15), 1e-16, 1e-6, 1e-3, 0.1, 0.5,
        1.0000000000000002, 1e6, 1e6 * (1 + 1e-15), -1e6, -1e6 * (1 + 1e-15), 3.0, 1.4, 2.0,
        0.9463, 1.6654, 1e-12, 1e12,
    };
    return table[k % (sizeof table / sizeof table[0])];
}

/* A double: an edge value, a modest decimal, or 8 raw bytes (any bit pattern). */
static inline double take_double(Bytes *b)
{
    const uint8_t sel = take(b);
    if (sel < 64) return special_double(sel);
    if (sel < 192) return (double)(int8_t)take(b) / 16.0 * pow(10.0, (double)(sel % 9) - 4);
    uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits = bits << 8 | take(b);
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

#endif
