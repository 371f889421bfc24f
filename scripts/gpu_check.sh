#!/usr/bin/env bash
# The checks to run on a lent GPU machine (docs/performance.md, "On a real GPU"), in one call.
#
#   bash scripts/gpu_check.sh prepare   # here: builds the binaries into .gl/ (ignored by git),
#                                       # with Debian's Vulkan loader, which such machines lack
#   bash scripts/gpu_check.sh run       # there: every check, logs and a summary under $OUT
#
# With the device tool: run `bash scripts/gpu_check.sh run` with carry [".gl"]. The adapter is
# chosen by WGPU_ADAPTER_NAME (default: the NVIDIA GPU nvidia-smi names, else wgpu's choice).
# Each check runs within a time limit, reference_gpu several times (REPEATS): a run that hangs is
# cut short with its threads' stacks (gdb, else each thread's kernel wait channel). The exit
# status is 1 when any check failed or hung.
set -uo pipefail

# The GPU test binaries checked on real hardware: the one that hung, run
# REPEATS times, and the others once.
REPEATED=reference_gpu
ONCE=(gpu_renderer gpu_raytrace gpu_bvh specialised_shading cube_seams)
TESTS=("$REPEATED" "${ONCE[@]}")
REPEATS=${REPEATS:-5}
# Checks that failed or hung (the exit status: 1 when any did).
FAILED=0

prepare() {
    set -e
    cargo build --release --locked
    rm -rf .gl/tests && mkdir -p .gl/tests
    local args=()
    for t in "${TESTS[@]}"; do args+=(--test "$t"); done
    cargo test --release --locked --no-run "${args[@]}" 2>&1 |
        sed -n 's/.*Executable tests\/\([a-z_]*\)\.rs (\(.*\))/\1 \2/p' |
        while read -r name path; do cp "$path" ".gl/tests/$name"; done
    cargo bench --locked --no-run --bench frame_cost 2>&1 |
        sed -n 's/.*Executable benches\/frame_cost\.rs (\(.*\))/\1/p' |
        while read -r path; do cp "$path" .gl/frame_cost; done
    cp target/release/lumlab .gl/lumlab
    strip .gl/lumlab .gl/frame_cost .gl/tests/*
    # Compressed: the device tool carries at most 64 MiB.
    (cd .gl && tar cJf bundle.tar.xz lumlab frame_cost tests && rm -rf lumlab frame_cost tests)
    (cd .gl && rm -f libvulkan1_*.deb && apt-get download libvulkan1)
    du -sh .gl
}

# Runs "$@" within $1 seconds into log $2; the summary gets its exit status.
timed() {
    local limit=$1 log=$2
    shift 2
    timeout -s INT --kill-after=10 "$limit" "$@" >"$log" 2>&1 &
    local pid=$!
    # Stacks of a run about to be cut short: the hang's cause (issue 17).
    (
        sleep $((limit - 5))
        local test_pid
        test_pid=$(pgrep -P "$pid" | head -1)
        if [ -n "$test_pid" ] && command -v gdb; then
            gdb -p "$test_pid" -batch -ex "thread apply all bt" >"$log.stacks" 2>&1
        elif [ -n "$test_pid" ]; then
            # Without gdb: each thread's name and where the kernel holds it.
            for task in /proc/"$test_pid"/task/*; do
                echo "$(cat "$task/comm"): $(cat "$task/wchan")"
            done >"$log.stacks"
        fi
    ) >/dev/null 2>&1 &
    local watcher=$!
    wait "$pid"
    local rc=$?
    pkill -P "$watcher" 2>/dev/null
    kill "$watcher" 2>/dev/null
    echo "$(basename "$log" .log): rc=$rc ($(grep -h 'test result' "$log" | tail -1))" >>"$OUT/summary.txt"
    [ "$rc" -eq 0 ] || FAILED=$((FAILED + 1))
}

run() {
    OUT=${OUT:-/tmp/gpu-check}
    mkdir -p "$OUT"
    tar xJf .gl/bundle.tar.xz -C .gl
    for deb in .gl/*.deb; do dpkg -x "$deb" /; done
    ldconfig
    export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
    if [ -z "${WGPU_ADAPTER_NAME:-}" ]; then
        local gpu
        gpu=$(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1 | awk '{print $NF}')
        [ -n "$gpu" ] && export WGPU_ADAPTER_NAME=$gpu
    fi
    .gl/lumlab render --adapter-info --size 64x48 --out "$OUT/smoke.png" >"$OUT/adapter.txt" 2>&1
    head -1 "$OUT/adapter.txt" >"$OUT/summary.txt"
    timed 120 "$OUT/stability.log" .gl/lumlab stability
    for k in $(seq "$REPEATS"); do
        timed 120 "$OUT/$REPEATED.$k.log" ".gl/tests/$REPEATED"
    done
    for t in "${ONCE[@]}"; do
        timed 240 "$OUT/$t.log" ".gl/tests/$t"
    done
    [ -x .gl/frame_cost ] && timed 240 "$OUT/frame_cost.log" .gl/frame_cost --bench interaction
    cat "$OUT/summary.txt"
    [ "$FAILED" -eq 0 ]
}

case "${1:-}" in
prepare) prepare ;;
run) run ;;
*)
    echo "usage: bash scripts/gpu_check.sh prepare|run" >&2
    exit 2
    ;;
esac
