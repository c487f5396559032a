# SPDX-License-Identifier: BSD-2-Clause
# The target platform of a build (native or cross, cmake/toolchains/): its FMI
# folder names, and what every binary built for it needs so that all platforms
# give the same numbers and load on a bare system (docs/platforms.md).

set(PAINLEVE_PLATFORM_DIR ${CMAKE_CURRENT_LIST_DIR})

# PAINLEVE_FMI2_PLATFORM (linux64, win64, darwin64; empty where FMI 2.0 names no
# folder, as for aarch64: docs/platforms.md) and PAINLEVE_FMI3_PLATFORM
# (x86_64-linux, x86_64-windows, aarch64-linux, ...): FMI 3.0's <arch>-<system>.
function(painleve_platform_folders)
  string(TOLOWER "${CMAKE_SYSTEM_PROCESSOR}" arch)
  if(arch MATCHES "^(amd64|x86_64|x64)$")
    set(arch x86_64)
  elseif(arch MATCHES "^(arm64|aarch64)$")
    set(arch aarch64)
  endif()
  if(CMAKE_SYSTEM_NAME STREQUAL "Windows")
    set(system windows)
    set(fmi2 win)
  elseif(CMAKE_SYSTEM_NAME STREQUAL "Darwin")
    set(system darwin)
    set(fmi2 darwin)
  else()
    set(system linux)
    set(fmi2 linux)
  endif()
  if(arch STREQUAL "x86_64" AND CMAKE_SIZEOF_VOID_P EQUAL 8)
    set(fmi2 ${fmi2}64)
  else()
    set(fmi2 "")
  endif()
  set(PAINLEVE_FMI2_PLATFORM "${fmi2}" PARENT_SCOPE)
  set(PAINLEVE_FMI3_PLATFORM "${arch}-${system}" PARENT_SCOPE)
endfunction()

# What TARGET (an FMU's shared library) needs on every platform.
# -ffp-contract=off: no fused multiply-add (GCC's default on aarch64), which
# moves CVODE's step decisions and so the results (by up to 4e-7 in random rod
# cases); every platform then rounds each operation the same way.
# Windows: the DLL is a RUNTIME output (each target sets its own folder),
# and libgcc is linked statically, so it imports system DLLs only
# (KERNEL32, msvcrt); the win32 thread model of the toolchain needs no
# libwinpthread. Only the FMI functions leave it: FMI2_Export/FMI3_Export are
# __declspec(dllexport) there, and a DLL with any such export exports nothing else.
function(painleve_platform_target TARGET)
  target_compile_options(${TARGET} PRIVATE -ffp-contract=off)
  # glibc: pow, exp and log from their oldest symbol versions, not GLIBC_2.29 (cmake/glibc_math.c).
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux")
    include(CheckSymbolExists)
    check_symbol_exists(__GLIBC__ features.h PAINLEVE_GLIBC)
    if(PAINLEVE_GLIBC)
      target_sources(${TARGET} PRIVATE ${PAINLEVE_PLATFORM_DIR}/glibc_math.c)
      target_link_options(${TARGET} PRIVATE -Wl,--wrap=pow,--wrap=exp,--wrap=log)
    endif()
  endif()
  # macOS (zig's clang, cmake/toolchains/*-macos.cmake): clang warns where GCC does not, about
  # fmpy's fmi3FunctionTypes.h (two declarations without prototypes) and about an enum
  # constant (a count) in double arithmetic, which converts as C says.
  # The library's install name is @rpath/NAME.dylib, not the build folder's path.
  if(APPLE)
    target_compile_options(${TARGET} PRIVATE -Wno-strict-prototypes -Wno-enum-float-conversion)
    set_target_properties(${TARGET} PROPERTIES INSTALL_NAME_DIR "@rpath" BUILD_WITH_INSTALL_NAME_DIR ON)
  endif()
  if(WIN32)
    target_link_options(${TARGET} PRIVATE -static-libgcc)
    # mingw-w64's isfinite (math.h) is a __builtin_choose_expr over __fpclassify,
    # __fpclassifyf and __fpclassifyl: GCC warns about the float branch it never
    # takes. The native build keeps -Wfloat-conversion on the same sources.
    target_compile_options(${TARGET} PRIVATE -Wno-float-conversion)
  endif()
endfunction()

# OUTPUT_DIR for TARGET's library, whichever kind of output the platform makes of it.
function(painleve_platform_output TARGET OUTPUT_DIR)
  set_target_properties(${TARGET} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${OUTPUT_DIR}
    RUNTIME_OUTPUT_DIRECTORY ${OUTPUT_DIR})
endfunction()
