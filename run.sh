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
apt_setup() {
    local missing=()
    for p in "${APT_PACKAGES[@]}"; do
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

python_setup() {
    [ -x "$PY" ] || { log "creating $VENV"; python3 -m venv "$VENV"; }
    log "pip install (pinned, requirements.txt)"
    "$PY" -m pip install -q --disable-pip-version-check -r requirements.txt
    "$PY" -m pip install -q --disable-pip-version-check --no-deps -e python_harness
}

build_fmu() {
    log "building PainleveRod.fmu"
    cmake -S . -B build -DPython3_EXECUTABLE="$PY" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build build -j 2 >/dev/null
    log "built $ROOT/build/PainleveRod.fmu"
}

setup() { apt_setup; python_setup; build_fmu; }

case "${1:-}" in
    main) setup; rc=0; "$VENV/bin/painleve" validate build/PainleveRod.fmu --report out/validation.md || rc=$?; "$VENV/bin/painleve" figures --out out/figures; printf '\nvalidation report: %s\nfigures: %s (fig_GB.png, fig_eDelta0.png, fig_video.png; the numbers in figures.json, a summary in figures.md)\n' "$ROOT/out/validation.md" "$ROOT/out/figures/"; exit $rc ;;
    test) setup; "$PY" -m pytest -q -p no:cacheprovider tests ;;
    *) echo "usage: bash run.sh main|test" >&2; exit 2 ;;
esac
