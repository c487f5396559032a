/* SPDX-License-Identifier: BSD-2-Clause */
/* What the native driver measures beyond the run: wall time and peak memory. */
#ifndef MEASURE_H
#define MEASURE_H

#include <stddef.h>

/* CLOCK_MONOTONIC, in seconds. */
double seconds(void);

/* The median of v[0..count) (v is sorted in place). */
double median(double *v, size_t count);

/* VmHWM of /proc/self/status, KiB, or -1. */
long peak_rss_of_this_image(void);

#endif
