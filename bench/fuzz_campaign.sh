#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# A long fuzzing campaign off CI: each fuzz target of tests/c for a time budget,
# in libFuzzer's fork mode (one job at a time: -fork=1; a crash, timeout or OOM
# is kept and the campaign goes on), over a scratch copy of tests/c/corpus, then
# a table: inputs tried, coverage (cov: edges, ft: features), corpus size and
# findings per target. Findings stay in the output directory, to replay with
# `BUILD/TARGET FILE` and, once fixed, to add to tests/c/corpus as regress-*.
#
#   bench/fuzz_campaign.sh [TARGET...] SECONDS
#
# With no TARGET: every fuzz target (fuzz_fmi*, fuzz_bounded*). C_BUILD names a
# build of tests/c to use (default: build/c-robustness, configured and built here
# with clang, -j 2); OUT the output directory (default: a new /tmp/fuzz-campaign-*).
# FUZZ_INPUT_TIMEOUT (20 s) is the time one input may take before it counts as a hang.
set -euo pipefail

if [ $# -lt 1 ] || ! [[ "${!#}" =~ ^[0-9]+$ ]]; then
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
SECONDS_EACH=${!#}
TARGETS=("${@:1:$#-1}")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
C_BUILD=${C_BUILD:-$ROOT/build/c-robustness}
OUT=${OUT:-$(mktemp -d /tmp/fuzz-campaign-XXXXXX)}
TIMEOUT=${FUZZ_INPUT_TIMEOUT:-20}
PYTHON=${PYTHON:-$ROOT/.venv/bin/python}
[ -x "$PYTHON" ] || PYTHON=python3

if [ ! -f "$C_BUILD/CMakeCache.txt" ]; then
    cmake -S "$ROOT/tests/c" -B "$C_BUILD" -DCMAKE_C_COMPILER=clang -DPython3_EXECUTABLE="$PYTHON" >/dev/null
fi
cmake --build "$C_BUILD" -j 2 >/dev/null
if [ ${#TARGETS[@]} -eq 0 ]; then
    mapfile -t TARGETS < <(cd "$C_BUILD" && ls fuzz_fmi* fuzz_bounded* 2>/dev/null | sort)
fi

echo "campaign: ${TARGETS[*]}, $SECONDS_EACH s each, output in $OUT"
summary=()
for target in "${TARGETS[@]}"; do
    dir=$OUT/$target
    mkdir -p "$dir/corpus" "$dir/findings"
    cp "$ROOT"/tests/c/corpus/* "$dir/corpus/"
    # the outer timeout only guards against libFuzzer itself not stopping; interrupted, the script stops it
    timeout --kill-after=30 $((SECONDS_EACH + 300)) "$C_BUILD/$target" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 \
        -ignore_ooms=1 -max_total_time="$SECONDS_EACH" -timeout="$TIMEOUT" -rss_limit_mb=2048 -use_value_profile=1 \
        -artifact_prefix="$dir/findings/" -print_final_stats=1 "$dir/corpus" >"$dir/log" 2>&1 &
    fuzzer=$!
    trap 'kill -TERM $fuzzer 2>/dev/null; exit 130' INT TERM
    wait $fuzzer || true
    trap - INT TERM
    # fork mode's status lines: "#RUNS: cov: N ft: N corp: N exec/s: N oom/timeout/crash: a/b/c time: Ns ..."
    last=$(grep -E '^#[0-9]+: cov:' "$dir/log" | tail -1 || true)
    runs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$last")
    cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
    ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
    corp=$(sed -nE 's/.* corp: ([0-9]+).*/\1/p' <<<"$last")
    found=$(ls "$dir/findings" | wc -l)
    kinds=$(ls "$dir/findings" | sed -E 's/-.*//' | sort | uniq -c | awk '{printf "%s %s ", $1, $2}')
    summary+=("$(printf '%-28s %12s %6s %7s %6s %5s  %s' "$target" "${runs:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" \
        "$found" "$kinds")")
    echo "$target: ${runs:-?} inputs, cov ${cov:-?}, ft ${ft:-?}, $found findings"
done

printf '\n%-28s %12s %6s %7s %6s %5s  %s\n' target inputs cov ft corpus found kinds
printf '%s\n' "${summary[@]}"
echo "logs, corpora and findings: $OUT (replay a finding: $C_BUILD/TARGET FILE)"
