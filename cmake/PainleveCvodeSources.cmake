# SPDX-License-Identifier: BSD-2-Clause
# The CVODE subset a source FMU carries, so that an importer's own
# compiler (fmpy's build_platform_binary, OpenModelica's importFMU with sources)
# builds a Co-Simulation binary with no SUNDIALS installed: from the pinned
# SUNDIALS tree that `run.sh platforms` passes as -DPAINLEVE_CVODE_SOURCE_DIR
# (sundials-sys 0.6.2's vendor/, hash-checked; docs/platforms.md).
#
# In the FMU's sources/: SUNDIALS' public headers in their folders (cvode/,
# sundials/, nvector/, ...: found by -I sources, the one include folder a tool
# adds), a sundials_config.h and sundials_export.h for any C99 compiler (no
# POSIX timers, no GCC attributes, nothing exported), the implementation files
# flat in sundials_src/ (quoted includes find each other there), and
# cvode_bundled.h, which defines HAVE_CVODE where cvode_build.h finds it.
set(PAINLEVE_CVODE_SOURCE_DIR "" CACHE PATH "pinned SUNDIALS 7 sources to put in the source FMUs (empty: none)")

# CVODE_BUNDLE_DIR (the folder to copy into sources/), CVODE_BUNDLE_SOURCES (its .c
# files, relative to sources/), CVODE_BUNDLE_VERSION and CVODE_BUNDLE_ORIGIN (the
# SUNDIALS release, and the folder it came from named by its parent: sundials-sys-0.6.2/vendor);
# all empty without PAINLEVE_CVODE_SOURCE_DIR.
function(painleve_cvode_bundle)
  set(CVODE_BUNDLE_DIR "" PARENT_SCOPE)
  set(CVODE_BUNDLE_SOURCES "" PARENT_SCOPE)
  set(CVODE_BUNDLE_VERSION "" PARENT_SCOPE)
  set(CVODE_BUNDLE_ORIGIN "" PARENT_SCOPE)
  set(src ${PAINLEVE_CVODE_SOURCE_DIR})
  if(NOT src)
    return()
  endif()
  if(NOT EXISTS ${src}/src/cvode/cvode.c OR NOT EXISTS ${src}/include/sundials/sundials_config.in)
    message(FATAL_ERROR "PAINLEVE_CVODE_SOURCE_DIR=${src} is no SUNDIALS source tree")
  endif()
  file(STRINGS ${src}/CMakeLists.txt version REGEX "set\\(PACKAGE_VERSION_(MAJOR|MINOR|PATCH) ")
  string(REGEX REPLACE "[^;]*\"([0-9]+)\"[^;]*" "\\1" version "${version}")
  string(REPLACE ";" "." version "${version}")
  set(out ${CMAKE_BINARY_DIR}/cvode_bundle)
  file(REMOVE_RECURSE ${out})
  foreach(dir cvode nvector sundials sunlinsol sunmatrix sunnonlinsol sunmemory sunadaptcontroller)
    file(COPY ${src}/include/${dir} DESTINATION ${out} FILES_MATCHING PATTERN "*.h")
  endforeach()
  # CVODE with the serial vector, dense matrix and solver and Newton's method, and the core
  # (the objects of libsundials_cvode's and libsundials_core's that the FMUs' link uses).
  set(units cvode/cvode.c cvode/cvode_io.c cvode/cvode_ls.c cvode/cvode_nls.c cvode/cvode_proj.c
      nvector/serial/nvector_serial.c sunmatrix/dense/sunmatrix_dense.c sunmatrix/band/sunmatrix_band.c
      sunlinsol/dense/sunlinsol_dense.c
      sunnonlinsol/newton/sunnonlinsol_newton.c)
  foreach(core adaptcontroller band context dense direct errors futils hashmap iterative linearsolver logger
          math matrix memory nonlinearsolver nvector nvector_senswrapper version)
    list(APPEND units sundials/sundials_${core}.c)
  endforeach()
  file(GLOB private ${src}/src/sundials/*.h ${src}/src/cvode/*.h)
  set(names "")
  foreach(unit IN LISTS units)
    get_filename_component(name ${unit} NAME)
    list(APPEND names sundials_src/${name})
  endforeach()
  list(TRANSFORM units PREPEND ${src}/src/)
  file(COPY ${units} ${private} DESTINATION ${out}/sundials_src)
  file(COPY ${src}/LICENSE DESTINATION ${out}/sundials_src)
  file(WRITE ${out}/sundials/sundials_export.h
    "/* Written by cmake/PainleveCvodeSources.cmake: SUNDIALS compiled into the FMU, nothing exported. */\n"
    "#ifndef SUNDIALS_EXPORT_H\n#define SUNDIALS_EXPORT_H\n#define SUNDIALS_EXPORT\n#define SUNDIALS_NO_EXPORT\n"
    "#define SUNDIALS_DEPRECATED\n#define SUNDIALS_DEPRECATED_EXPORT\n#define SUNDIALS_DEPRECATED_NO_EXPORT\n#endif\n")
  string(REPLACE "." ";" parts "${version}")
  list(GET parts 0 major)
  list(GET parts 1 minor)
  list(GET parts 2 patch)
  file(WRITE ${out}/sundials/sundials_config.h
    "/* Written by cmake/PainleveCvodeSources.cmake for any C99 compiler: SUNDIALS ${version}, double\n"
    " * precision, 64-bit indices, CVODE alone, no MPI, no timers, no compiler extensions. */\n"
    "#ifndef _SUNDIALS_CONFIG_H\n#define _SUNDIALS_CONFIG_H\n#include \"sundials/sundials_export.h\"\n"
    "#define SUNDIALS_NOEXCEPT\n#define SUNDIALS_DEPRECATED_MSG(msg)\n"
    "#define SUNDIALS_DEPRECATED_EXPORT_MSG(msg) SUNDIALS_EXPORT\n"
    "#define SUNDIALS_DEPRECATED_NO_EXPORT_MSG(msg) SUNDIALS_NO_EXPORT\n"
    "#define SUNDIALS_VERSION \"${version}\"\n#define SUNDIALS_VERSION_MAJOR ${major}\n"
    "#define SUNDIALS_VERSION_MINOR ${minor}\n#define SUNDIALS_VERSION_PATCH ${patch}\n"
    "#define SUNDIALS_VERSION_LABEL \"\"\n#define SUNDIALS_GIT_VERSION \"\"\n"
    "#define SUNDIALS_DOUBLE_PRECISION 1\n#define SUNDIALS_INT64_T 1\n#define SUNDIALS_INDEX_TYPE int64_t\n"
    "#define SUNDIALS_LOGGING_LEVEL 2\n#define SUNDIALS_MPI_ENABLED 0\n#define SUNDIALS_CVODE 1\n"
    "#define SUNDIALS_NVECTOR_SERIAL 1\n#define SUNDIALS_SUNMATRIX_DENSE 1\n#define SUNDIALS_SUNLINSOL_DENSE 1\n"
    "#define SUNDIALS_SUNNONLINSOL_NEWTON 1\n#define SUN_C_COMPILER \"\"\n#define SUN_C_COMPILER_VERSION \"\"\n"
    "#define SUN_C_COMPILER_FLAGS \"\"\n#define SUN_CXX_COMPILER \"\"\n#define SUN_CXX_COMPILER_VERSION \"\"\n"
    "#define SUN_CXX_COMPILER_FLAGS \"\"\n#define SUN_FORTRAN_COMPILER \"\"\n#define SUN_FORTRAN_COMPILER_VERSION \"\"\n"
    "#define SUN_FORTRAN_COMPILER_FLAGS \"\"\n#define SUN_BUILD_TYPE \"\"\n#define SUN_JOB_ID \"\"\n"
    "#define SUN_JOB_START_TIME \"\"\n#define SUN_TPL_LIST \"\"\n#define SUN_TPL_LIST_SIZE \"\"\n"
    "#define SUNDIALS_SPACK_VERSION \"\"\n#endif\n")
  file(WRITE ${out}/cvode_bundled.h
    "/* Written by cmake/PainleveCvodeSources.cmake: this source FMU carries CVODE (sundials_src/). */\n"
    "#ifndef HAVE_CVODE\n#define HAVE_CVODE 1\n#endif\n")
  get_filename_component(parent ${src} DIRECTORY)
  get_filename_component(parent ${parent} NAME)
  get_filename_component(folder ${src} NAME)
  set(CVODE_BUNDLE_DIR ${out} PARENT_SCOPE)
  set(CVODE_BUNDLE_SOURCES ${names} PARENT_SCOPE)
  set(CVODE_BUNDLE_VERSION ${version} PARENT_SCOPE)
  set(CVODE_BUNDLE_ORIGIN "the sources ${parent}/${folder} holds" PARENT_SCOPE)
endfunction()

# TEXT (an FMI 2.0 model description) with CVODE_BUNDLE_SOURCES added to each of
# its <SourceFiles>, in OUT_VAR.
function(painleve_cvode_bundle_description TEXT OUT_VAR)
  set(files "")
  foreach(name IN LISTS CVODE_BUNDLE_SOURCES)
    string(APPEND files "  <File name=\"${name}\"/>\n")
  endforeach()
  string(REGEX REPLACE "([ \t]*)</SourceFiles>" "${files}\\1</SourceFiles>" text "${TEXT}")
  set(${OUT_VAR} "${text}" PARENT_SCOPE)
endfunction()
