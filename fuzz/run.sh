#!/usr/bin/env bash
# Fuzzes slipfront's four readers of untrusted input with cargo fuzz (libFuzzer):
#   case_parse  case text and --set overrides     (slipfront::fuzzing::case_parse)
#   mcap_read   MCAP logs for check and replay    (slipfront::fuzzing::mcap_read; run it in fork mode,
#               -fork=1, for long campaigns: Rerun's blueprint builder leaves 2 threads per replay)
#   rrd_read    Rerun recordings for check         (slipfront::fuzzing::rrd_read)
#   gmsh_read   Gmsh mesh files (MSH 4.1, 2.2)     (slipfront::fuzzing::gmsh_read)
#
# Usage: fuzz/run.sh [SECONDS_PER_TARGET] [--parallel]   (default 600; --parallel runs the four
# targets at once, at low priority, each for SECONDS of wall clock, and prints each one's final
# stats: on 2 cores, four 30-minute runs take 30 minutes instead of 120)
#
# Needs `cargo install cargo-fuzz`. The stable toolchain builds libFuzzer's instrumentation with
# RUSTC_BOOTSTRAP=1; no sanitizer (-s none), since the code under test is safe Rust and
# a panic is what we look for. Corpora are seeded from the shipped cases, from short runs'
# recordings and from the committed meshes (cases/meshes). Crashes land in
# fuzz/artifacts/<target>/; once fixed, copy each into fuzz/regressions/<target>/ so that
# `cargo test` replays it (tests/fuzz_regressions.rs).
set -euo pipefail
cd "$(dirname "$0")"
seconds="${1:-600}"
parallel="${2:-}"
RUSTC_BOOTSTRAP=1 cargo fuzz build -s none -O --debug-assertions

mkdir -p corpus/case_parse corpus/mcap_read corpus/rrd_read corpus/gmsh_read seeds
cp ../cases/*.toml corpus/case_parse/
cp regressions/case_parse/* corpus/case_parse/
cp ../cases/meshes/*.msh regressions/gmsh_read/* corpus/gmsh_read/
# The seeds come from the main build (RUSTC_BOOTSTRAP is for the fuzz build only: set for cargo
# in the main folder, it would change every fingerprint there and rebuild everything).
(cd .. && env -u RUSTC_BOOTSTRAP cargo build --release --quiet --bin slipfront)
../target/release/slipfront run ../cases/spring_block.toml --quiet --set time.t_end=0.05 \
    --out-dir seeds --mcap seeds/spring_block.mcap
../target/release/slipfront run ../cases/paper_triangular.toml --quiet --set time.t_end=0.05 \
    --no-rrd --out-dir seeds --mcap seeds/paper_triangular.mcap
cp seeds/*.mcap regressions/mcap_read/* corpus/mcap_read/
cp seeds/spring_block.rrd regressions/rrd_read/* corpus/rrd_read/

fuzz_one() {
    local fork=""
    [ "$1" = mcap_read ] && fork="-fork=1"
    RUSTC_BOOTSTRAP=1 nice -n "${2:-0}" cargo fuzz run -s none -O --debug-assertions "$1" "corpus/$1" -- \
        $fork -max_total_time="$seconds" -max_len=262144 -rss_limit_mb=4096 -timeout=20 -print_final_stats=1 \
        > "fuzz-$1.log" 2>&1 || true
    echo "== $1: $seconds s"
    grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss|==[0-9]+== ERROR|SUMMARY|Done)" \
        "fuzz-$1.log" || true
    ls "artifacts/$1" 2>/dev/null | sed 's/^/artifact: /' || true
}
if [ "$parallel" = "--parallel" ]; then
    for target in case_parse mcap_read rrd_read gmsh_read; do fuzz_one "$target" 19 & done
    wait
else
    for target in case_parse mcap_read rrd_read gmsh_read; do fuzz_one "$target"; done
fi
