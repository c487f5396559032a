/* SPDX-License-Identifier: BSD-2-Clause */
/* Linked into the Linux FMUs by cmake/PainlevePlatform.cmake (not an FMU source):
 * every call of pow in the link (CVODE's, -Wl,--wrap=pow) goes to glibc's
 * oldest pow symbol instead of pow@GLIBC_2.29, so that glibc 2.17 (aarch64)
 * or 2.14 (x86_64, memcpy) is all the binary needs (docs/platforms.md). From
 * glibc 2.29 on, the old symbol is the same pow with the SVID error handling of
 * before around it, which only acts where pow overflows or is not finite: the
 * numbers are those of pow@GLIBC_2.29. */
#include <math.h>

#if defined(__x86_64__)
#define OLDEST_POW "pow@GLIBC_2.2.5"
#elif defined(__aarch64__)
#define OLDEST_POW "pow@GLIBC_2.17"
#endif

double __wrap_pow(double x, double y);

#ifdef OLDEST_POW
__asm__(".symver oldest_pow, " OLDEST_POW);
double oldest_pow(double x, double y);
double __wrap_pow(double x, double y)
{
    return oldest_pow(x, y);
}
#else
double __real_pow(double x, double y);
double __wrap_pow(double x, double y)
{
    return __real_pow(x, y);
}
#endif
