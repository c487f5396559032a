# SPDX-License-Identifier: BSD-2-Clause
# Cross-build for 64-bit Windows with Debian's gcc-mingw-w64-x86-64 (GCC 12, the
# win32 thread model: the DLL then needs no libwinpthread). FMI 2.0 folder win64,
# FMI 3.0 x86_64-windows (cmake/PainlevePlatform.cmake names them from this).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(PAINLEVE_TRIPLE x86_64-w64-mingw32)
set(CMAKE_C_COMPILER ${PAINLEVE_TRIPLE}-gcc-win32)
set(CMAKE_RC_COMPILER ${PAINLEVE_TRIPLE}-windres)
set(CMAKE_FIND_ROOT_PATH /usr/${PAINLEVE_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# The test driver and try_run run the binaries under wine.
set(CMAKE_CROSSCOMPILING_EMULATOR /usr/lib/wine/wine64)
