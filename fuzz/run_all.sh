#!/usr/bin/env bash
# Runs every fuzz target in turn for SECONDS each (default 300) and prints, per target, the
# inputs tried, the time and whether it crashed. Needs nightly and cargo-fuzz:
#   rustup toolchain install nightly && cargo install cargo-fuzz
# Usage: fuzz/run_all.sh [SECONDS] [TARGET...]
# Crashes land in fuzz/artifacts/TARGET/; replay one with
#   cargo +nightly fuzz run TARGET fuzz/artifacts/TARGET/crash-...
# The corpus grows in fuzz/corpus/TARGET/ (seeded from scenes/ for the scene and mesh targets).
set -uo pipefail
cd "$(dirname "$0")"
seconds="${1:-300}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(scene_parse obj_read stl_read convex_hull narrow_phase world_step)
fi

# Seeds: real files make the parsers reach their checks instead of stopping at the first byte.
mkdir -p corpus/scene_parse corpus/obj_read corpus/stl_read
cp ../scenes/*.toml corpus/scene_parse/ 2>/dev/null || true
cp ../scenes/*.obj corpus/obj_read/ 2>/dev/null || true
find ../crates -name '*.stl' -exec cp {} corpus/stl_read/ \; 2>/dev/null || true

# No sanitizer: the engine has no unsafe code (the workspace denies it), so AddressSanitizer would
# only slow the runs; debug assertions stay on to catch overflow and broken invariants.
flags=(--sanitizer none --debug-assertions)
cargo +nightly fuzz build "${flags[@]}" || exit 1

status=0
for target in "${targets[@]}"; do
    log="$(mktemp)"
    cargo +nightly fuzz run "${flags[@]}" "$target" -- -max_total_time="$seconds" -print_final_stats=1 \
        >"$log" 2>&1
    code=$?
    runs="$(grep -m1 '^stat::number_of_executed_units' "$log" | awk '{print $2}')"
    if [ $code -eq 0 ]; then
        echo "$target: ${runs:-?} inputs in ${seconds} s, no crash"
    else
        status=1
        echo "$target: CRASHED (exit $code) after ${runs:-?} inputs; see fuzz/artifacts/$target/"
        grep -m5 -E "panicked|ERROR" "$log" | sed 's/^/    /'
    fi
    rm -f "$log"
done
exit $status
