/* SPDX-License-Identifier: BSD-2-Clause */
/* The native driver's one way to fail: a message naming what to fix, written
 * to err (n bytes), and 0 returned (every function that can fail takes err, n). */
#ifndef NATIVE_FAIL_H
#define NATIVE_FAIL_H

#include <stdio.h>

#define FAIL(...)                       \
    do {                                \
        snprintf(err, n, __VA_ARGS__); \
        return 0;                       \
    } while (0)

#endif
