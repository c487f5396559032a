/* SPDX-License-Identifier: BSD-2-Clause */
/* Linked into the Linux FMUs by cmake/PainlevePlatform.cmake (not an FMU source):
 * every call of pow, exp and log in the link (CVODE's pow, the explicit pair's exp and log;
 * -Wl,--wrap=pow,--wrap=exp,--wrap=log) goes to glibc's oldest symbol of the function instead
 * of the GLIBC_2.29 one, so that glibc 2.17 (aarch64) or 2.14 (x86_64, memcpy) is all the binary
 * needs (docs/platforms.md). From glibc 2.29 on, each old symbol is the same function with the
 * SVID error handling of before around it, which only acts where the result overflows or is
 * not finite: the numbers are those of the GLIBC_2.29 symbols. */
#include <math.h>

#if defined(__x86_64__)
#define OLDEST(name) #name "@GLIBC_2.2.5"
#elif defined(__aarch64__)
#define OLDEST(name) #name "@GLIBC_2.17"
#endif

double __wrap_pow(double x, double y);
double __wrap_exp(double x);
double __wrap_log(double x);

/* What each wrapper calls: glibc's oldest symbol where one is named, else the function the link
 * would have called. */
#ifdef OLDEST
__asm__(".symver oldest_pow, " OLDEST(pow));
__asm__(".symver oldest_exp, " OLDEST(exp));
__asm__(".symver oldest_log, " OLDEST(log));
#define TARGET(name) oldest_##name
#else
#define TARGET(name) __real_##name
#endif

double TARGET(pow)(double x, double y);
double TARGET(exp)(double x);
double TARGET(log)(double x);
double __wrap_pow(double x, double y) { return TARGET(pow)(x, y); }
double __wrap_exp(double x) { return TARGET(exp)(x); }
double __wrap_log(double x) { return TARGET(log)(x); }
