#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The project's two entry points on a fresh Debian machine:
#   bash run.sh main   set up, build PainleveRod.fmu, run the main job
#   bash run.sh platforms  set up, build the FMUs for Linux, Windows, ARM and macOS into
#                          build/platforms/, and the wheel for every platform into build/platforms/dist/
#   bash run.sh test   set up, build, run every test
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$PWD
VENV=$ROOT/.venv
PY=$VENV/bin/python

log() { printf '== %s\n' "$*" >&2; }

# System packages (Debian names), installed only if missing: what the build and the main job
# need, and what only the tests add (clang and its sanitizer runtime, valgrind: the C
# robustness tests).
APT_PACKAGES=(python3-venv libsundials-dev)
APT_TEST_PACKAGES=(clang libclang-rt-14-dev valgrind)
apt_install() {
    local missing=()
    for p in "$@"; do
        # NAME=VERSION (pinned) is there only in that version.
        local want="ok installed "; [[ "$p" == *=* ]] && want="ok installed ${p#*=}\$"
        dpkg-query -W -f='${Status} ${Version}\n' "${p%%=*}" 2>/dev/null | grep -q "$want" || missing+=("$p")
    done
    # A python3 that already has venv and ensurepip (e.g. pyenv's) needs no python3-venv.
    if python3 -c "import venv, ensurepip" 2>/dev/null; then
        missing=("${missing[@]/python3-venv/}")
    fi
    missing=($(printf '%s\n' "${missing[@]}" | grep -v '^$' || true))
    if ((${#missing[@]})); then
        log "apt-get install ${missing[*]}"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq && apt-get install -y -qq "${missing[@]}" >/dev/null
    fi
}

# The tests' second FMI importer: fmi-sim from crates.io, built once into .tools/
# with the machine's cargo (rustup's), else Debian's cargo-web; bindgen needs libclang.
FMI_SIM_VERSION=0.7.0
TOOLS=$ROOT/.tools
find_cargo() {
    local cargo
    cargo=$(command -v cargo || echo "$HOME/.cargo/bin/cargo")
    if [ ! -x "$cargo" ]; then apt_install cargo-web; cargo=/usr/bin/cargo; fi
    echo "$cargo"
}
importer_setup() {
    grep -qs "^\"fmi-sim $FMI_SIM_VERSION " "$TOOLS/.crates.toml" && return
    apt_install libclang-dev
    local cargo
    cargo=$(find_cargo)
    log "cargo install fmi-sim $FMI_SIM_VERSION into $TOOLS (about 5 minutes, once)"
    "$cargo" install --quiet --locked --version "$FMI_SIM_VERSION" --root "$TOOLS" fmi-sim
}

# SUNDIALS 7 for tests/fmu/test_sundials7.py (Debian 12 has 6): the sources that
# the crates.io crate sundials-sys vendors (cmake/sundials.pin: SUNDIALS 7.1.1), fetched
# by cargo and built once, static, CVODE alone, into .tools/ (about 10 s).
SUNDIALS7=$TOOLS/sundials-7.1
# The pinned SUNDIALS sources: sundials-sys's vendor/ folder, fetched by cargo (which
# checks the crate against crates.io's checksum) and checked here against the hash of
# the tree (every file's sha256, in byte order of the names). cmake/sundials.pin pins both
# (SUNDIALS_SYS_VERSION, SUNDIALS_TREE_SHA256), for this script and the CMake build alike,
# which checks the tree again and downloads the same crate itself where no tree is given.
# Prints the folder.
. "$ROOT/cmake/sundials.pin"
sundials_source() {
    local cargo work src hash
    cargo=$(find_cargo)
    work=$(mktemp -d)
    mkdir -p "$work/fetch/src"
    printf '[package]\nname = "fetch-sundials"\nversion = "0.0.0"\nedition = "2021"\n[dependencies]\nsundials-sys = "=%s"\n' \
        "$SUNDIALS_SYS_VERSION" >"$work/fetch/Cargo.toml"
    : >"$work/fetch/src/lib.rs"
    # Only this platform's dependencies are downloaded; cargo says where it unpacked the crate.
    local platform; platform="$(uname -m)-unknown-linux-gnu"
    "$cargo" fetch --quiet --manifest-path "$work/fetch/Cargo.toml" --target "$platform"
    src=$("$cargo" metadata --quiet --format-version 1 --filter-platform "$platform" \
        --manifest-path "$work/fetch/Cargo.toml" | python3 -c \
        'import json, os, sys; print(next(os.path.dirname(p["manifest_path"]) for p in json.load(sys.stdin)["packages"] if p["name"] == "sundials-sys"))')/vendor
    rm -rf "$work"
    hash=$(cd "$src" && find . -type f -print0 | LC_ALL=C sort -z | xargs -0 sha256sum | sha256sum | cut -d' ' -f1)
    [ "$hash" = "$SUNDIALS_TREE_SHA256" ] || { log "$src: tree hash $hash, pinned $SUNDIALS_TREE_SHA256"; return 1; }
    grep -q 'PACKAGE_VERSION_MAJOR "7"' "$src/CMakeLists.txt" || { log "$src is not SUNDIALS 7"; return 1; }
    echo "$src"
}
sundials7_setup() {
    local stamp="$SUNDIALS7/.from-sundials-sys-$SUNDIALS_SYS_VERSION"
    [ -f "$stamp" ] && [ -f "$SUNDIALS7/LICENSE" ] && return
    local work src
    if [ -f "$stamp" ]; then sundials_license "$CVODE_SRC" "$SUNDIALS7"; return; fi
    log "SUNDIALS 7 from crates.io sundials-sys $SUNDIALS_SYS_VERSION into $SUNDIALS7 (once)"
    src=$(sundials_source)
    work=$(mktemp -d)
    cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$SUNDIALS7" \
        -DBUILD_SHARED_LIBS=OFF -DBUILD_STATIC_LIBS=ON -DCMAKE_POSITION_INDEPENDENT_CODE=ON \
        -DBUILD_CVODE=ON -DBUILD_ARKODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
        -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_ENABLE_CXX=OFF -DEXAMPLES_INSTALL=OFF >"$work/build.log" 2>&1 &&
        cmake --build "$work/build" -j 2 >>"$work/build.log" 2>&1 && rm -rf "$SUNDIALS7" &&
        cmake --install "$work/build" >>"$work/build.log" 2>&1 || { tail -n 40 "$work/build.log" >&2; return 1; }
    sundials_license "$src" "$SUNDIALS7"
    touch "$stamp"
    rm -rf "$work"
}
# What the FMUs' documentation/licenses/ says of a SUNDIALS built from SRC into PREFIX
# (cmake/PainleveLicenses.cmake): its LICENSE, and where the sources came from.
sundials_license() {
    cp "$1/LICENSE" "$2/LICENSE"
    printf 'the sources sundials-sys-%s/vendor holds\n' "$SUNDIALS_SYS_VERSION" >"$2/ORIGIN"
}

# The multi-platform FMUs (docs/platforms.md): cross compilers, wine and qemu from Debian 12
# (pinned where Debian 12 has the version; the test runs every binary), llvm-14's lipo for the
# universal macOS binary, zig (pinned, cmake/toolchains/requirements.txt) for macOS; then
# cmake/platforms.sh, and the py3-none-any wheel that carries build/platforms/'s FMUs into
# build/platforms/dist/ (its CMake build links the same SUNDIALS as build-platforms/x86_64-linux,
# so the wheel's licenses are its FMUs').
APT_PLATFORM_PACKAGES=(gcc-mingw-w64-x86-64=12.2.0-14+25.2 gcc-aarch64-linux-gnu=4:12.2.0-3
                       libc6-dev-arm64-cross=2.36-8cross1 wine64=8.0~repack-4 qemu-user llvm-14=1:14.0.6-12)
platforms() {
    apt_install "${APT_PLATFORM_PACKAGES[@]}"
    log "pip install (pinned, cmake/toolchains/requirements.txt)"
    "$PY" -m pip install -q --disable-pip-version-check -r cmake/toolchains/requirements.txt
    bash cmake/platforms.sh "$PY" "$CVODE_SRC"
    log "the py3-none-any wheel with build/platforms/'s FMUs into build/platforms/dist"
    rm -rf build/platforms/dist
    "$PY" -m pip wheel -q --disable-pip-version-check --no-deps --no-build-isolation -w build/platforms/dist \
        -C wheel.platlib=false -C build-dir=build/pip/any \
        -C cmake.define.PAINLEVE_WHEEL_FMUS="$ROOT/build/platforms" \
        -C cmake.define.SUNDIALS_ROOT="$ROOT/.tools/platforms/x86_64-linux/sundials" \
        -C cmake.define.PAINLEVE_CVODE_SOURCE_DIR="$CVODE_SRC" . >/dev/null
    log "built $(ls "$ROOT"/build/platforms/dist/*.whl)"
}

# More test-only importers (tests/helpers/other_importers.py): libcosim and ecos from PyPI
# (tests/importers/requirements.txt; ecos's library needs Debian's libtbb12), FMI4j and
# JavaFMI from Maven Central (tests/importers/jvm/pom.xml, compiled with the machine's
# JDK and Maven, else Debian's).
more_importers_setup() {
    apt_install libtbb12
    log "pip install (pinned, tests/importers/requirements.txt)"
    "$PY" -m pip install -q --disable-pip-version-check -r tests/importers/requirements.txt
    command -v javac >/dev/null && command -v mvn >/dev/null || apt_install openjdk-17-jdk-headless maven
    local jvm=tests/importers/jvm built=tests/importers/jvm/target/classes/painleve/importers/CoSimulate.class
    [ -f "$built" ] && [ -z "$(find "$jvm/pom.xml" "$jvm/src" -newer "$built")" ] && return
    log "mvn: FMI4j and JavaFMI (pinned, $jvm/pom.xml; about 15 s)"
    mvn -q -B -Dstyle.color=never -f "$jvm/pom.xml" compile dependency:copy-dependencies
}

# The harness is installed the way a Python user installs it (pyproject.toml: scikit-build-core
# runs CMake and bundles PainleveRod.fmu in the package), here editable and with the pinned
# build requirements of requirements.txt already in the venv. Its FMUs carry the CVODE subset
# of the pinned SUNDIALS in sources/ (cmake/PainleveCvodeSources.cmake), as the plain build's do.
python_setup() {
    [ -x "$PY" ] || { log "creating $VENV"; python3 -m venv "$VENV"; }
    log "pip install (pinned, requirements.txt)"
    "$PY" -m pip install -q --disable-pip-version-check -r requirements.txt
    log "pip install -e . (builds the FMU into the package)"
    SKBUILD_CMAKE_DEFINE="PAINLEVE_CVODE_SOURCE_DIR=$CVODE_SRC" \
        "$PY" -m pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e .
}

# The test tools of the Python side (pytest), for `bash run.sh test` only.
test_python_setup() {
    log "pip install (pinned, tests/requirements.txt)"
    "$PY" -m pip install -q --disable-pip-version-check -r tests/requirements.txt
}

build_fmu() {
    log "building the FMUs (PainleveRod FMI 2.0 and 3.0, PainleveRodSI, ShakerTable)"
    cmake -S . -B build -DPython3_EXECUTABLE="$PY" -DCMAKE_BUILD_TYPE=Release \
        -DPAINLEVE_CVODE_SOURCE_DIR="$CVODE_SRC" >/dev/null
    cmake --build build -j 2 >/dev/null
    log "built $ROOT/build/*.fmu"
}

# The pinned SUNDIALS sources (sundials_source) go into every FMU's sources/, so that each
# builds Co-Simulation with no SUNDIALS installed; the binaries of build/ link Debian's.
setup() { apt_install "${APT_PACKAGES[@]}"; CVODE_SRC=$(sundials_source); python_setup; build_fmu; }

case "${1:-}" in
    main) setup; rc=0
          "$VENV/bin/painleve" validate build/PainleveRod.fmu --report out/validation.md || rc=$?
          "$VENV/bin/painleve" validate build/fmi3/PainleveRod.fmu --report out/validation-fmi3.md || rc=$?
          "$VENV/bin/painleve" figures --out out/figures || rc=$?
          "$VENV/bin/painleve" couple --out out/couple.png || rc=$?
          printf '\nvalidation reports: %s (FMI 2.0), %s (FMI 3.0)\nfigures: %s (fig_GB.png, fig_eDelta0.png, fig_video.png, fig_eLaw.png; the numbers in figures.json, a summary in figures.md)\ncoupled study (PainleveRodSI on ShakerTable, SSP): %s\n' \
              "$ROOT/out/validation.md" "$ROOT/out/validation-fmi3.md" "$ROOT/out/figures/" "$ROOT/out/couple.png"
          exit $rc ;;
    platforms) setup; platforms ;;
    test) setup; apt_install "${APT_TEST_PACKAGES[@]}"; test_python_setup; importer_setup; sundials7_setup; platforms; more_importers_setup; "$PY" -m pytest -q -p no:cacheprovider --durations=15 tests ;;
    *) echo "usage: bash run.sh main|platforms|test" >&2; exit 2 ;;
esac
