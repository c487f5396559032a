/* SPDX-License-Identifier: BSD-2-Clause */
/* HAVE_CVODE: whether Co-Simulation has CVODE. The CMake build defines it when
 * it links SUNDIALS. A source FMU that carries the CVODE sources (sources/
 * sundials_src/, cmake/PainleveCvodeSources.cmake) also has cvode_bundled.h,
 * which defines it, for a tool that compiles sources/ with no definitions of
 * ours (FMI 2.0's <SourceFiles> have none; fmpy's build_platform_binary). */
#ifndef CVODE_BUILD_H
#define CVODE_BUILD_H

#if !defined(HAVE_CVODE) && defined(__has_include)
#if __has_include("cvode_bundled.h")
#include "cvode_bundled.h"
#endif
#endif

#endif
