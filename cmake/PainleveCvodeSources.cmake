# SPDX-License-Identifier: BSD-2-Clause
# The CVODE subset a source FMU carries, so that an importer's own
# compiler (fmpy's build_platform_binary, OpenModelica's importFMU with sources)
# builds a Co-Simulation binary with no SUNDIALS installed: from the pinned
# SUNDIALS sources (cmake/sundials.pin: sundials-sys 0.6.2's vendor/, hash-checked;
# docs/platforms.md), which every build path uses. run.sh passes the tree cargo fetched
# as -DPAINLEVE_CVODE_SOURCE_DIR; without it the build downloads the pinned crate
# itself (or takes -DPAINLEVE_SUNDIALS_CRATE, the file fetched by hand), checks it
# against the pin and unpacks it into the build tree.
#
# In the FMU's sources/: SUNDIALS' public headers in their folders (cvode/,
# sundials/, nvector/, ...: found by -I sources, the one include folder a tool
# adds), a sundials_config.h and sundials_export.h for any C99 compiler (no
# POSIX timers, no GCC attributes, nothing exported), the implementation files
# flat in sundials_src/ (quoted includes find each other there), and
# cvode_bundled.h, which defines HAVE_CVODE where cvode_build.h finds it.
set(PAINLEVE_CVODE_SOURCE_DIR "" CACHE PATH
    "the pinned SUNDIALS sources (sundials-sys's vendor/) for the source FMUs (empty: the build downloads them)")
set(PAINLEVE_SUNDIALS_CRATE "" CACHE FILEPATH
    "the pinned sundials-sys .crate file, for a build with no network (empty: downloaded)")

# The pin: SUNDIALS_SYS_VERSION, SUNDIALS_CRATE_SHA256 and SUNDIALS_TREE_SHA256 (cmake/sundials.pin).
file(STRINGS ${CMAKE_CURRENT_LIST_DIR}/sundials.pin _painleve_pins REGEX "^[A-Z0-9_]+=")
foreach(_painleve_pin IN LISTS _painleve_pins)
  string(REGEX MATCH "^([A-Z0-9_]+)=(.*)$" _ "${_painleve_pin}")
  set(${CMAKE_MATCH_1} "${CMAKE_MATCH_2}")
endforeach()
if(NOT SUNDIALS_SYS_VERSION OR NOT SUNDIALS_CRATE_SHA256 OR NOT SUNDIALS_TREE_SHA256)
  message(FATAL_ERROR "${CMAKE_CURRENT_LIST_DIR}/sundials.pin does not pin the SUNDIALS sources")
endif()
set(PAINLEVE_SUNDIALS_CRATE_URL
    "https://static.crates.io/crates/sundials-sys/sundials-sys-${SUNDIALS_SYS_VERSION}.crate" CACHE STRING
    "where the build downloads the pinned sundials-sys crate from (the registry's download of that version)")

# The hash of the tree in DIR, as run.sh computes it: sha256sum's line ("HASH  ./PATH") for
# every file, in byte order of the paths, hashed together. In OUT_VAR.
function(painleve_tree_sha256 DIR OUT_VAR)
  file(GLOB_RECURSE files LIST_DIRECTORIES false RELATIVE ${DIR} ${DIR}/*)
  list(SORT files)
  set(lines "")
  foreach(file IN LISTS files)
    if(NOT IS_SYMLINK ${DIR}/${file})
      file(SHA256 ${DIR}/${file} hash)
      string(APPEND lines "${hash}  ./${file}\n")
    endif()
  endforeach()
  string(SHA256 tree "${lines}")
  set(${OUT_VAR} ${tree} PARENT_SCOPE)
endfunction()

# The pinned SUNDIALS tree in OUT_DIR: PAINLEVE_CVODE_SOURCE_DIR, else the crate
# (PAINLEVE_SUNDIALS_CRATE, else downloaded into the build tree) unpacked in the build tree;
# either checked against the pin. Where the crate cannot be had, OUT_DIR is empty and
# OUT_WHY says why.
function(painleve_pinned_sundials OUT_DIR OUT_WHY)
  set(${OUT_DIR} "" PARENT_SCOPE)
  set(${OUT_WHY} "" PARENT_SCOPE)
  set(src "${PAINLEVE_CVODE_SOURCE_DIR}")
  if(NOT src)
    set(where ${CMAKE_BINARY_DIR}/sundials-sources)
    set(crate "${PAINLEVE_SUNDIALS_CRATE}")
    if(crate)
      if(NOT EXISTS "${crate}")
        message(FATAL_ERROR "PAINLEVE_SUNDIALS_CRATE=${crate} does not exist")
      endif()
    else()
      set(crate ${where}/sundials-sys-${SUNDIALS_SYS_VERSION}.crate)
      set(hash "")
      if(EXISTS ${crate})
        file(SHA256 ${crate} hash)
      endif()
      if(NOT hash STREQUAL SUNDIALS_CRATE_SHA256)
        message(STATUS "Downloading the pinned SUNDIALS sources: sundials-sys ${SUNDIALS_SYS_VERSION}")
        file(DOWNLOAD ${PAINLEVE_SUNDIALS_CRATE_URL} ${crate}.part STATUS status TLS_VERIFY ON
             INACTIVITY_TIMEOUT 60 TIMEOUT 600)
        list(GET status 0 code)
        if(NOT code EQUAL 0)
          list(GET status 1 message)
          file(REMOVE ${crate}.part)
          set(${OUT_WHY} "${PAINLEVE_SUNDIALS_CRATE_URL} could not be downloaded (${message})" PARENT_SCOPE)
          return()
        endif()
        file(RENAME ${crate}.part ${crate})
      endif()
    endif()
    file(SHA256 ${crate} hash)
    if(NOT hash STREQUAL SUNDIALS_CRATE_SHA256)
      message(FATAL_ERROR "${crate}: sha256 ${hash}, pinned ${SUNDIALS_CRATE_SHA256} (cmake/sundials.pin)")
    endif()
    set(src ${where}/sundials-sys-${SUNDIALS_SYS_VERSION}/vendor)
    if(NOT EXISTS ${where}/unpacked-${hash})
      file(REMOVE_RECURSE ${where}/sundials-sys-${SUNDIALS_SYS_VERSION})
      file(GLOB stamps ${where}/unpacked-*)
      if(stamps)
        file(REMOVE ${stamps})
      endif()
      file(MAKE_DIRECTORY ${where})
      execute_process(COMMAND ${CMAKE_COMMAND} -E tar xzf ${crate} WORKING_DIRECTORY ${where}
                      RESULT_VARIABLE status ERROR_VARIABLE error)
      if(NOT status EQUAL 0)
        message(FATAL_ERROR "${crate} could not be unpacked: ${error}")
      endif()
      file(WRITE ${where}/unpacked-${hash} "")
    endif()
  endif()
  if(NOT EXISTS ${src}/src/cvode/cvode.c OR NOT EXISTS ${src}/include/sundials/sundials_config.in)
    message(FATAL_ERROR "${src} is no SUNDIALS source tree")
  endif()
  painleve_tree_sha256(${src} tree)
  if(NOT tree STREQUAL SUNDIALS_TREE_SHA256)
    message(FATAL_ERROR "${src}: tree hash ${tree}, pinned ${SUNDIALS_TREE_SHA256} (cmake/sundials.pin): "
                        "not the pinned SUNDIALS sources")
  endif()
  set(${OUT_DIR} ${src} PARENT_SCOPE)
endfunction()

# CVODE_BUNDLE_DIR (the folder to copy into sources/), CVODE_BUNDLE_SOURCES (its .c
# files, relative to sources/), CVODE_BUNDLE_VERSION and CVODE_BUNDLE_ORIGIN (the
# SUNDIALS release, and where it came from: the pinned crate's vendor/) from the pinned
# sources (painleve_pinned_sundials). Where those cannot be had, all are empty and one
# warning says why: the FMUs then carry no sources/ at all (CMakeLists.txt), since sources
# without CVODE would not build the Co-Simulation their binaries declare.
function(painleve_cvode_bundle)
  set(CVODE_BUNDLE_DIR "" PARENT_SCOPE)
  set(CVODE_BUNDLE_SOURCES "" PARENT_SCOPE)
  set(CVODE_BUNDLE_VERSION "" PARENT_SCOPE)
  set(CVODE_BUNDLE_ORIGIN "" PARENT_SCOPE)
  painleve_pinned_sundials(src why)
  if(NOT src)
    message(WARNING "The FMUs carry no sources/: ${why}. Without the pinned SUNDIALS sources "
                    "(cmake/sundials.pin) their sources could not build the Co-Simulation their binaries "
                    "have, so they are binary-only. Pass -DPAINLEVE_SUNDIALS_CRATE=sundials-sys-"
                    "${SUNDIALS_SYS_VERSION}.crate (fetched by hand) or -DPAINLEVE_CVODE_SOURCE_DIR=its vendor/ "
                    "folder for source FMUs.")
    return()
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
  set(CVODE_BUNDLE_DIR ${out} PARENT_SCOPE)
  set(CVODE_BUNDLE_SOURCES ${names} PARENT_SCOPE)
  set(CVODE_BUNDLE_VERSION ${version} PARENT_SCOPE)
  set(CVODE_BUNDLE_ORIGIN "the sources sundials-sys-${SUNDIALS_SYS_VERSION}/vendor holds" PARENT_SCOPE)
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

# TEXT (an FMI 2.0 model description) with every <SourceFiles> element taken out, in OUT_VAR:
# the description of an FMU that carries no sources/. Each pass takes out one element.
function(painleve_without_source_files TEXT OUT_VAR)
  set(text "${TEXT}")
  string(FIND "${text}" "<SourceFiles>" first)
  while(NOT first EQUAL -1)
    string(FIND "${text}" "</SourceFiles>" last)
    if(last LESS first)
      message(FATAL_ERROR "a <SourceFiles> element without its end")
    endif()
    math(EXPR last "${last} + 14")
    string(SUBSTRING "${text}" 0 ${first} before)
    string(SUBSTRING "${text}" ${last} -1 after)
    string(REGEX REPLACE "[ \t]*$" "" before "${before}")
    string(REGEX REPLACE "^[ \t]*\n" "" after "${after}")
    set(text "${before}${after}")
    string(FIND "${text}" "<SourceFiles>" first)
  endwhile()
  set(${OUT_VAR} "${text}" PARENT_SCOPE)
endfunction()
