#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The multi-platform FMUs (docs/platforms.md): run by `bash run.sh platforms`,
# which installs the cross compilers and fetches the pinned SUNDIALS first.
#   cmake/platforms.sh PYTHON SUNDIALS_SOURCE_DIR
# For each platform (this machine's x86_64-linux, and with cmake/toolchains/
# x86_64-windows, aarch64-linux, x86_64-darwin and aarch64-darwin): static CVODE from the pinned SUNDIALS into
# .tools/platforms/NAME/sundials, the project's FMUs into build-platforms/NAME;
# then build/platforms/ gets every FMU of the native build (FMI 2.0 and 3.0,
# every model it has) with the other builds' binaries added.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
PY=$1
SUNDIALS_SRC=$2
log() { printf '== %s\n' "$*" >&2; }

# NAME TOOLCHAIN (empty: native). Both SUNDIALS and the FMUs without fused multiply-add; for
# macOS, SUNDIALS with hidden symbols (Mach-O's linker has no --exclude-libs).
build_platform() {
    local name=$1 toolchain=$2 prefix=$ROOT/.tools/platforms/$1/sundials work=$ROOT/build-platforms/$1
    local cross=() flags=-ffp-contract=off
    [ -n "$toolchain" ] && cross=(-DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/toolchains/$toolchain.cmake")
    [[ "$name" == *-darwin ]] && flags="$flags -fvisibility=hidden"
    local stamp="$prefix/.from-$(basename "$(dirname "$SUNDIALS_SRC")")"
    mkdir -p "$ROOT/build-platforms"
    if [ ! -f "$stamp" ]; then
        log "$name: static CVODE from $SUNDIALS_SRC into $prefix"
        rm -rf "$work-sundials" "$prefix"
        cmake -S "$SUNDIALS_SRC" -B "$work-sundials" "${cross[@]}" -DCMAKE_BUILD_TYPE=Release \
            -DCMAKE_C_FLAGS="$flags" -DCMAKE_INSTALL_PREFIX="$prefix" \
            -DBUILD_SHARED_LIBS=OFF -DBUILD_STATIC_LIBS=ON -DCMAKE_POSITION_INDEPENDENT_CODE=ON \
            -DBUILD_CVODE=ON -DBUILD_ARKODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF \
            -DBUILD_KINSOL=OFF -DBUILD_FORTRAN_MODULE_INTERFACE=OFF -DEXAMPLES_ENABLE_C=OFF \
            -DEXAMPLES_ENABLE_CXX=OFF -DEXAMPLES_INSTALL=OFF >"$work-sundials.log" 2>&1 &&
            cmake --build "$work-sundials" -j 2 >>"$work-sundials.log" 2>&1 &&
            cmake --install "$work-sundials" >>"$work-sundials.log" 2>&1 ||
            { tail -n 40 "$work-sundials.log" >&2; return 1; }
        touch "$stamp"
        rm -rf "$work-sundials" "$work-sundials.log"
    fi
    # What the FMUs' documentation/licenses/ says of this SUNDIALS (cmake/PainleveLicenses.cmake).
    cp "$SUNDIALS_SRC/LICENSE" "$prefix/LICENSE"
    printf 'the sources %s/%s holds\n' "$(basename "$(dirname "$SUNDIALS_SRC")")" "$(basename "$SUNDIALS_SRC")" \
        >"$prefix/ORIGIN"
    log "$name: the FMUs into $work"
    cmake -S . -B "$work" "${cross[@]}" -DPython3_EXECUTABLE="$PY" -DCMAKE_BUILD_TYPE=Release \
        -DSUNDIALS_ROOT="$prefix" -DPAINLEVE_CVODE_SOURCE_DIR="$SUNDIALS_SRC" >"$work.log" 2>&1 &&
        cmake --build "$work" -j 2 >>"$work.log" 2>&1 || { tail -n 40 "$work.log" >&2; return 1; }
}

# zig (PyPI ziglang, in PYTHON's environment) as the compiler, ar and ranlib the macOS
# toolchain files name; the minimum macOS is the target's version (docs/platforms.md).
MACOS_MIN=11.0
zig_wrappers() {
    local dir=$ROOT/.tools/zig arch tool
    mkdir -p "$dir"
    for arch in x86_64 aarch64; do
        printf '#!/bin/sh\nexec "%s" -m ziglang cc -target %s-macos.%s "$@"\n' "$PY" "$arch" "$MACOS_MIN" \
            >"$dir/cc-$arch-macos"
    done
    for tool in ar ranlib; do printf '#!/bin/sh\nexec "%s" -m ziglang %s "$@"\n' "$PY" "$tool" >"$dir/$tool"; done
    chmod +x "$dir"/*
}

zig_wrappers
build_platform x86_64-linux ""
build_platform x86_64-windows x86_64-w64-mingw32
build_platform aarch64-linux aarch64-linux-gnu
build_platform x86_64-darwin x86_64-macos
build_platform aarch64-darwin aarch64-macos
# FMI 2.0's darwin64: one universal binary of both macOS builds' (build-platforms/darwin).
"$PY" cmake/universal_darwin.py llvm-lipo-14 build-platforms/darwin build-platforms/x86_64-darwin \
    build-platforms/aarch64-darwin
"$PY" cmake/merge_platforms.py build/platforms build-platforms/x86_64-linux \
    build-platforms/x86_64-windows build-platforms/aarch64-linux build-platforms/darwin \
    build-platforms/aarch64-darwin
log "built $ROOT/build/platforms/*.fmu and $ROOT/build/platforms/fmi3/*.fmu"
