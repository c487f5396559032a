# SPDX-License-Identifier: BSD-2-Clause
# Cross-build for 64-bit ARM Linux with Debian's gcc-aarch64-linux-gnu and the
# sysroot of libc6-dev-arm64-cross (/usr/aarch64-linux-gnu). FMI 3.0 folder
# aarch64-linux; FMI 2.0 has none (docs/platforms.md).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(PAINLEVE_TRIPLE aarch64-linux-gnu)
set(CMAKE_C_COMPILER ${PAINLEVE_TRIPLE}-gcc)
set(CMAKE_FIND_ROOT_PATH /usr/${PAINLEVE_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64;-L;/usr/${PAINLEVE_TRIPLE})
