# SPDX-License-Identifier: BSD-2-Clause
# The licenses every FMU of the build carries in documentation/licenses/
# (cmake/fmu_licenses.py): the project's, the SUNDIALS the binaries link, the
# SUNDIALS subset in sources/ (cmake/PainleveCvodeSources.cmake), the FMI headers'.
set(PAINLEVE_SUNDIALS_LICENSE "" CACHE FILEPATH
    "license text of the SUNDIALS the binaries link (empty: SUNDIALS_ROOT/LICENSE, or Debian's copyright file)")

# Where the linked SUNDIALS came from, and its license text: SUNDIALS_ROOT's LICENSE and
# ORIGIN (cmake/platforms.sh and run.sh write them beside the static build), else the
# LICENSE a SUNDIALS 7 install has in include/sundials/, or the Debian package's
# copyright file for the system's SUNDIALS.
function(painleve_sundials_license OUT_FILE OUT_ORIGIN)
  set(file "${PAINLEVE_SUNDIALS_LICENSE}")
  set(origin "${SUNDIALS_ROOT}")
  if(NOT file AND SUNDIALS_ROOT AND EXISTS ${SUNDIALS_ROOT}/LICENSE)
    set(file ${SUNDIALS_ROOT}/LICENSE)
    if(EXISTS ${SUNDIALS_ROOT}/ORIGIN)
      file(READ ${SUNDIALS_ROOT}/ORIGIN origin)
      string(STRIP "${origin}" origin)
    endif()
  elseif(NOT file AND SUNDIALS_ROOT AND EXISTS ${SUNDIALS_ROOT}/include/sundials/LICENSE)
    # SUNDIALS 7's own install puts its LICENSE beside its headers.
    set(file ${SUNDIALS_ROOT}/include/sundials/LICENSE)
  elseif(NOT file AND NOT SUNDIALS_ROOT AND EXISTS /usr/share/doc/libsundials-dev/copyright)
    set(file /usr/share/doc/libsundials-dev/copyright)
    execute_process(COMMAND dpkg-query -W -f=\${Version} libsundials-dev OUTPUT_VARIABLE package
                    ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
    set(origin "Debian's libsundials-dev ${package} (its copyright file, /usr/share/doc/libsundials-dev/copyright)")
  endif()
  if(NOT file)
    message(FATAL_ERROR "The license of the SUNDIALS in ${SUNDIALS_INCLUDE_DIR} is unknown: "
                        "pass -DPAINLEVE_SUNDIALS_LICENSE=its LICENSE file")
  endif()
  set(${OUT_FILE} ${file} PARENT_SCOPE)
  set(${OUT_ORIGIN} "${origin}" PARENT_SCOPE)
endfunction()

# LICENSES_DIR (the folder each FMU copies into documentation/licenses/) and
# LICENSES_STAMP (its license.txt, a build output to depend on).
function(painleve_licenses)
  set(out ${CMAKE_BINARY_DIR}/licenses)
  set(args "")
  set(depends ${CMAKE_CURRENT_SOURCE_DIR}/LICENSE ${CMAKE_CURRENT_SOURCE_DIR}/cmake/fmu_licenses.py)
  if(HAVE_SUNDIALS)
    painleve_sundials_license(file origin)
    list(APPEND args --sundials binaries ${SUNDIALS_VERSION} "${origin}" ${file})
    list(APPEND depends ${file})
  endif()
  if(CVODE_BUNDLE_DIR)
    list(APPEND args --sundials sources ${CVODE_BUNDLE_VERSION} "${CVODE_BUNDLE_ORIGIN}"
         ${CVODE_BUNDLE_DIR}/sundials_src/LICENSE)
  endif()
  add_custom_command(OUTPUT ${out}/license.txt
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/cmake/fmu_licenses.py ${out}
            ${CMAKE_CURRENT_SOURCE_DIR}/LICENSE ${FMI_HEADERS} ${args}
    DEPENDS ${depends}
    COMMENT "documentation/licenses/ of the FMUs" VERBATIM)
  set(LICENSES_DIR ${out} PARENT_SCOPE)
  set(LICENSES_STAMP ${out}/license.txt PARENT_SCOPE)
endfunction()
