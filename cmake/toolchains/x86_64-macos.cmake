# SPDX-License-Identifier: BSD-2-Clause
# Cross-build for macOS on x86_64 with zig's clang and Mach-O linker (PyPI ziglang,
# pinned in cmake/toolchains/requirements.txt), through the wrappers cmake/platforms.sh
# writes into .tools/zig/. FMI 3.0 folder x86_64-darwin; the FMI 2.0 folder darwin64
# holds one universal binary of both architectures (cmake/universal_darwin.py).
set(CMAKE_SYSTEM_NAME Darwin)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
get_filename_component(PAINLEVE_ZIG ${CMAKE_CURRENT_LIST_DIR}/../../.tools/zig ABSOLUTE)
set(CMAKE_C_COMPILER ${PAINLEVE_ZIG}/cc-x86_64-macos)
set(CMAKE_AR ${PAINLEVE_ZIG}/ar CACHE FILEPATH "zig's ar")
set(CMAKE_RANLIB ${PAINLEVE_ZIG}/ranlib CACHE FILEPATH "zig's ranlib")
# No Xcode SDK: zig brings the macOS headers and libSystem's stubs; the wrapper sets the
# minimum macOS version (-target x86_64-macos.VERSION).
set(CMAKE_OSX_SYSROOT "" CACHE PATH "")
set(CMAKE_OSX_DEPLOYMENT_TARGET "" CACHE STRING "")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
