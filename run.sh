#!/usr/bin/env bash
# The project's two entry points on a fresh Debian machine:
#   bash run.sh main   set up, build PainleveRod.fmu, run the main job
#   bash run.sh test   set up, build, run every test
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$PWD
VENV=$ROOT/.venv
PY=$VENV/bin/python

log() { printf '== %s\n' "$*" >&2; }

# System packages the build and tests need (Debian names), installed only if missing.
APT_PACKAGES=(python3-venv libsundials-dev clang libclang-rt-14-dev valgrind)
apt_install() {
    local missing=()
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
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
importer_setup() {
    grep -qs "^\"fmi-sim $FMI_SIM_VERSION " "$TOOLS/.crates.toml" && return
    apt_install libclang-dev
    local cargo
    cargo=$(command -v cargo || echo "$HOME/.cargo/bin/cargo")
    if [ ! -x "$cargo" ]; then apt_install cargo-web; cargo=/usr/bin/cargo; fi
    log "cargo install fmi-sim $FMI_SIM_VERSION into $TOOLS (about 5 minutes, once)"
    "$cargo" install --quiet --locked --version "$FMI_SIM_VERSION" --root "$TOOLS" fmi-sim
}

# The harness is installed the way a Python user installs it (pyproject.toml: scikit-build-core
# runs CMake and bundles PainleveRod.fmu in the package), here editable and with the pinned
# build requirements of requirements.txt already in the venv.
python_setup() {
    [ -x "$PY" ] || { log "creating $VENV"; python3 -m venv "$VENV"; }
    log "pip install (pinned, requirements.txt)"
    "$PY" -m pip install -q --disable-pip-version-check -r requirements.txt
    log "pip install -e . (builds the FMU into the package)"
    "$PY" -m pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e .
}

build_fmu() {
    log "building PainleveRod.fmu"
    cmake -S . -B build -DPython3_EXECUTABLE="$PY" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build build -j 2 >/dev/null
    log "built $ROOT/build/PainleveRod.fmu"
}

setup() { apt_install "${APT_PACKAGES[@]}"; python_setup; build_fmu; }

case "${1:-}" in
    main) setup; rc=0; "$VENV/bin/painleve" validate build/PainleveRod.fmu --report out/validation.md || rc=$?; "$VENV/bin/painleve" figures --out out/figures; printf '\nvalidation report: %s\nfigures: %s (fig_GB.png, fig_eDelta0.png, fig_video.png; the numbers in figures.json, a summary in figures.md)\n' "$ROOT/out/validation.md" "$ROOT/out/figures/"; exit $rc ;;
    test) setup; importer_setup; "$PY" -m pytest -q -p no:cacheprovider tests ;;
    *) echo "usage: bash run.sh main|test" >&2; exit 2 ;;
esac
