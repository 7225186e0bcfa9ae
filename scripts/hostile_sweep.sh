#!/usr/bin/env bash
# A sweep of hostile uses of the release binary: extreme and malformed --set values on every
# shipped case, colliding and unwritable output paths, damaged recordings and MCAP logs (bit
# flips, truncations) given to check, figures and replay, and bad command-line values. Every
# use runs under `timeout 60`; the sweep counts outcomes by exit code and flags what must never
# happen: a hang (124), a panic or an abort (101, 134, 139, or "panicked" in the output), and
# an exit 0 whose recording fails `slipfront check`.
#
# Usage: scripts/hostile_sweep.sh [--bin PATH] [--out DIR] [--seed N]
# It takes a few minutes on 2 cores; it is not part of CI. Exit 1 if anything was flagged.
set -uo pipefail

bin=target/release/slipfront out="" seed=1
while (($#)); do
    case "$1" in
        --bin) bin=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --seed) seed=$2; shift 2 ;;
        -h | --help) sed -n '2,10p' "$0"; exit 0 ;;
        *) echo "hostile_sweep: unknown argument $1 (see --help)" >&2; exit 2 ;;
    esac
done
cd "$(dirname "$0")/.."
[[ -x $bin ]] || { echo "hostile_sweep: no binary at $bin (cargo build --release)" >&2; exit 2; }
bin=$(realpath "$bin")
out=${out:-$(mktemp -d)}
mkdir -p "$out"
RANDOM=$seed
declare -A outcomes=()
flagged=0 total=0

# Runs one use: label, then the command. Classifies it.
use() {
    local label=$1
    shift
    total=$((total + 1))
    local log="$out/use-$total.log"
    timeout 60 "$@" >"$log" 2>&1
    local code=$?
    outcomes[$code]=$((${outcomes[$code]:-0} + 1))
    local why=""
    case $code in
        124) why="hang" ;;
        101 | 134 | 139) why="crash (exit $code)" ;;
    esac
    grep -q "panicked" "$log" && why="panic"
    if [[ -z $why && $code == 0 && -n ${check_after:-} && -f $check_after ]]; then
        "$bin" check "$check_after" >"$log.check" 2>&1 || why="exit 0 with a recording that fails check"
    fi
    if [[ -n $why ]]; then
        flagged=$((flagged + 1))
        echo "FLAGGED ($why): $label: $* (log: $log)"
    fi
}

# 1. Extreme and malformed values on every case.
values=(0 -1 1e-320 1e300 -1e300 nan inf -inf '"text"' '[1,2]' true 1e-12 1e12 0.5 2 '{}')
keys=(friction.mu_s friction.mu_k friction.alpha_t friction.r friction.kappa friction.m friction.xi friction.n
      friction.structure0 friction.f0 time.dt time.theta time.tolerance time.energy_tolerance
      events.slip_rate_threshold record.stick_every record.magnification record.segments)
for case in cases/*.toml; do
    stem=$(basename "$case" .toml)
    for i in $(seq 1 16); do
        key=${keys[RANDOM % ${#keys[@]}]}
        value=${values[RANDOM % ${#values[@]}]}
        dir="$out/run-$total"
        check_after="$dir/$stem.rrd" use "set $key=$value" \
            "$bin" run "$case" --quiet --out-dir "$dir" --set time.t_end=2 --set "$key=$value"
    done
done
check_after=""

# 2. Every integrator at extreme tolerances and steps on the small cases.
for case in cases/spring_block.toml cases/paper_triangular.toml cases/uniform_low.toml; do
    stem=$(basename "$case" .toml)
    for integrator in wilson tsit5 sdirk4 central auto bogus; do
        for extra in "time.dt=1e-9" "time.dt=100" "time.tolerance=1e-14" "time.tolerance=0.5" "time.theta=1.37"; do
            dir="$out/run-$total"
            check_after="$dir/$stem.rrd" use "$integrator $extra" "$bin" run "$case" --quiet --out-dir "$dir" \
                --set time.t_end=3 --set time.integrator=$integrator --set "$extra"
        done
    done
done
check_after=""

# 3. Output paths: collisions, inputs, missing and unwritable folders.
spring=cases/spring_block.toml
for pair in "--rrd X --mcap X" "--rrd X --events X" "--mcap X --events X" "--rrd CASE" "--events CASE" \
    "--mcap CASE" "--rrd /nonexistent/x.rrd" "--events /nonexistent/e.csv" "--mcap /proc/x.mcap" \
    "--rrd /dev/full" "--events /dev/full" "--out-dir /proc/slipfront"; do
    dir="$out/paths-$total"
    mkdir -p "$dir"
    cp "$spring" "$dir/c.toml"
    args=${pair//X/$dir/x}
    args=${args//CASE/$dir/c.toml}
    # shellcheck disable=SC2086
    use "paths $pair" "$bin" run "$dir/c.toml" --quiet --set time.t_end=5 --out-dir "$dir" $args
done

# 4. Damaged files: bit flips and cuts of a recording and a log, read back by every reader.
base="$out/base"
"$bin" run cases/paper_triangular.toml --quiet --set time.t_end=450 --out-dir "$base" --mcap "$base/log.mcap" \
    >/dev/null 2>&1
for original in "$base/paper_triangular.rrd" "$base/log.mcap"; do
    size=$(stat -c %s "$original")
    ext=${original##*.}
    for i in $(seq 1 60); do
        damaged="$out/damaged-$total.$ext"
        cp "$original" "$damaged"
        if ((i % 3 == 0)); then
            truncate -s $((RANDOM * 32768 % size)) "$damaged"
        else
            offset=$(((RANDOM * 32768 + RANDOM) % size))
            printf "\\x$(printf %02x $((RANDOM % 256)))" | dd of="$damaged" bs=1 seek=$offset conv=notrunc status=none
        fi
        use "check damaged $ext #$i" "$bin" check "$damaged"
        if [[ $ext == rrd ]]; then
            use "figures damaged #$i" "$bin" figures "$damaged" --out "$out/figures-$total"
        else
            use "replay damaged #$i" "$bin" replay "$damaged" --rrd "$out/replayed-$total.rrd"
        fi
    done
done

# 5. Bad command-line values.
for speed in 0 -1 1e-20 1e300 nan inf abc; do
    use "replay --speed $speed" "$bin" replay "$base/log.mcap" --rrd "$out/replayed-$total.rrd" "--speed=$speed"
done
for expect in 'min = nan' 'max = inf' 'time = -1' 'min = 2.0
max = 1.0' 'entity = 3' 'bogus = 1'; do
    file="$out/expect-$total.toml"
    printf '[[at]]\nentity = "contact/friction_force"\ntime = 1.0\n%s\n' "$expect" >"$file"
    use "expect $expect" "$bin" check "$base/paper_triangular.rrd" --expect "$file"
done
for case in /dev/null /dev/zero / "$out" cases/README.md nonexistent.toml; do
    use "case $case" "$bin" run "$case" --quiet --out-dir "$out/cases-$total"
done

echo "$total uses; by exit code:"
for code in $(printf '%s\n' "${!outcomes[@]}" | sort -n); do
    echo "  exit $code: ${outcomes[$code]}"
done
echo "flagged: $flagged (outputs in $out)"
((flagged == 0))
