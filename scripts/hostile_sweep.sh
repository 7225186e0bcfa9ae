#!/usr/bin/env bash
# A sweep of hostile uses of the release binary: extreme and malformed --set values on every
# shipped case, colliding and unwritable output paths, damaged recordings and MCAP logs (bit
# flips, truncations) given to check, figures and replay, bad command-line values, resumes
# beside damaged, foreign, cut or missing files or killed at random moments, studies with
# tampered, orphaned and stale records, two studies in one folder and failing members, and
# devices, named pipes and oversized files given to every reader. Every use runs under
# `timeout 60`; the sweep counts outcomes by exit code and flags what must never happen: a hang
# (124), a panic or an abort (101, 134, 139, or "panicked" in the output), an exit 0 whose
# recording fails `slipfront check`, a resume refused, failed or killed that changed a file, a
# study that exits 0 with tables other than a clean run's or with failed members, a second
# study let into a busy folder, figures drawn from a recording that check fails, and a device,
# pipe or oversized file read.
#
# Usage: scripts/hostile_sweep.sh [--bin PATH] [--out DIR] [--seed N]
# It takes about ten minutes on 2 cores; it is not part of CI. Exit 1 if anything was flagged.
set -uo pipefail

bin=target/release/slipfront out="" seed=1
while (($#)); do
    case "$1" in
        --bin) bin=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --seed) seed=$2; shift 2 ;;
        -h | --help) sed -n '2,16p' "$0"; exit 0 ;;
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

# Flags one use: why, then what it was.
flag() {
    flagged=$((flagged + 1))
    echo "FLAGGED ($1): $2"
}

# Runs one use: label, then the command. Classifies it; leaves its exit code in $last.
use() {
    local label=$1
    shift
    total=$((total + 1))
    local log="$out/use-$total.log"
    timeout 60 "$@" >"$log" 2>&1
    local code=$?
    last=$code
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
        flag "$why" "$label: $* (log: $log)"
    fi
}

# As `use`, with the address space capped at 8 GB: a reader that reads a device ends there.
capped() {
    local label=$1
    shift
    use "$label" bash -c 'ulimit -v 8000000; exec "$@"' - "$@"
}

# The sha256 of every file in a folder, hidden ones with `all`.
fingerprint() {
    (
        cd "$1" || exit
        shopt -s nullglob
        if [[ ${2:-} == all ]]; then sha256sum -- * .[!.]*; else sha256sum -- *; fi
    ) 2>/dev/null
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
            checked=$last
            use "figures damaged #$i" "$bin" figures "$damaged" --out "$out/figures-$total"
            if [[ $last == 0 && $checked != 0 ]]; then
                flag "figures drawn from a recording that check fails" "figures damaged #$i ($damaged)"
            fi
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

# 6. Resumes beside damaged, foreign, cut or missing files, with bad options, and killed at
# random moments: a resume refused, failed or killed must leave every file as it was.
ckbase="$out/ckpt-base" other="$out/ckpt-other"
"$bin" run cases/paper_triangular.toml --quiet --out-dir "$ckbase" --set time.t_end=600 --set time.integrator=wilson \
    --checkpoint-every 300 --keep-checkpoints --mcap "$ckbase/paper_triangular.mcap" >/dev/null 2>&1
"$bin" run cases/paper_triangular.toml --quiet --out-dir "$other" --set time.t_end=400 \
    --mcap "$other/paper_triangular.mcap" >/dev/null 2>&1
# Damages the checkpointed run's copy in folder $1 by kind $2.
damage() {
    local f="$1/paper_triangular" file size
    case $2 in
        foreign-rrd | foreign-mcap) cp "$other/paper_triangular.${2#foreign-}" "$f.${2#foreign-}" ;;
        cut-rrd | cut-mcap)
            file="$f.${2#cut-}"
            truncate -s $((RANDOM * 32768 % $(stat -c %s "$file"))) "$file"
            ;;
        flip-rrd | flip-mcap)
            file="$f.${2#flip-}"
            size=$(stat -c %s "$file")
            printf "\\x$(printf %02x $((RANDOM % 256)))" |
                dd of="$file" bs=1 seek=$(((RANDOM * 32768 + RANDOM) % size)) conv=notrunc status=none
            ;;
        missing-rrd) rm "$f.rrd" ;;
        kept-folder) rm "$f.600s.ckpt" && mkdir "$f.600s.ckpt" ;;
    esac
}
# Resumes the copy in folder $1 with the remaining arguments; flags a changed folder unless it
# exited 0, and an exit 0 whose recording fails check.
resume_use() {
    local dir=$1 label=$2
    shift 2
    local before
    before=$(fingerprint "$dir" all)
    check_after="$dir/paper_triangular.rrd" use "$label" "$bin" resume "$dir/paper_triangular.300s.ckpt" --quiet "$@"
    if [[ $last != 0 && $(fingerprint "$dir" all) != "$before" ]]; then
        flag "a resume that exited $last changed its folder" "$label ($dir)"
    fi
}
kinds=(foreign-rrd foreign-mcap cut-rrd cut-mcap flip-rrd flip-rrd flip-rrd flip-mcap missing-rrd none)
for i in $(seq 1 40); do
    kind=${kinds[RANDOM % ${#kinds[@]}]}
    dir="$out/resume-$total"
    cp -r "$ckbase" "$dir"
    damage "$dir" "$kind"
    resume_use "$dir" "resume $kind #$i"
done
for option in "--checkpoint-every 0" "--checkpoint-every -1" "--checkpoint-every nan" "--set friction.mu_s=0.5" \
    "--set time.t_end=5" "--keep-checkpoints"; do
    dir="$out/resume-$total"
    cp -r "$ckbase" "$dir"
    [[ $option == --keep-checkpoints ]] && damage "$dir" kept-folder
    # shellcheck disable=SC2086
    resume_use "$dir" "resume $option" $option
done
for i in $(seq 1 12); do
    dir="$out/killed-$total"
    cp -r "$ckbase" "$dir"
    before=$(fingerprint "$dir")
    total=$((total + 1))
    "$bin" resume "$dir/paper_triangular.300s.ckpt" --quiet --set time.t_end=3000 --checkpoint-every 100 \
        >/dev/null 2>&1 &
    pid=$!
    sleep "$((RANDOM % 3)).$((RANDOM % 10))"
    kill -KILL $pid 2>/dev/null
    wait $pid 2>/dev/null
    code=$?
    outcomes[$code]=$((${outcomes[$code]:-0} + 1))
    if [[ $code == 137 && $(fingerprint "$dir") != "$before" ]]; then
        flag "a resume killed by SIGKILL changed its outputs" "resume killed #$i ($dir)"
    fi
done

# 7. Studies: records tampered with, outputs deleted or changed, the study file edited; two
# studies into one folder; members that fail.
points="$out/points/points.toml" edited="$out/points-edited/points.toml"
mkdir -p "$out/points" "$out/points-edited"
# Three spring blocks of 2 to 6 slip events each, a tenth of a second apiece.
printf 'case = "%s/cases/spring_block.toml"\n[set]\n"time.t_end" = 1000.0\n[sweep]\n"scene.stiffness" = [%s]\n' \
    "$PWD" "500.0, 1000.0, 1500.0" >"$points"
sed 's/1500.0\]/2000.0]/' "$points" >"$edited"
"$bin" study "$points" --quiet --out-dir "$out/study-clean" >/dev/null 2>&1
"$bin" study "$edited" --quiet --out-dir "$out/study-clean-edited" >/dev/null 2>&1
tables() { cat "$1/events.csv" "$1/summary.md"; }
for i in $(seq 1 24); do
    dir="$out/study-$total"
    cp -r "$out/study-clean" "$dir"
    m="$dir/points/member-000$((RANDOM % 3))"
    study=$points clean="$out/study-clean/points"
    case $((RANDOM % 7)) in
        0) printf x | dd of="$m.done.toml" bs=1 seek=$((RANDOM % $(stat -c %s "$m.done.toml"))) conv=notrunc status=none ;;
        1) sed -i 's/^index = [0-9]*/index = 99/' "$m.done.toml" ;;
        2) rm "$m.rrd" ;;
        3) echo "0,1,2,3,4,5,6" >>"$m.events.csv" ;;
        4) rm "$m.done.toml" && ln -s /dev/zero "$m.done.toml" ;;
        5) sed -i 's/ending = "completed"/ending = "stopped by hand"/' "$m.done.toml" ;;
        6) study=$edited clean="$out/study-clean-edited/points" ;;
    esac
    capped "study --resume #$i" "$bin" study "$study" --resume --quiet --out-dir "$dir"
    if [[ $last == 0 && "$(tables "$dir/points")" != "$(tables "$clean")" ]]; then
        flag "a resumed study's tables differ from a clean run's" "study --resume #$i ($dir)"
    fi
done
paper4="$out/paper4/paper4.toml"
mkdir -p "$out/paper4"
printf 'case = "%s/cases/paper_triangular.toml"\n[set]\n"time.t_end" = 450.0\n"time.integrator" = "wilson"\n' \
    "$PWD" >"$paper4"
printf '[sweep]\n"scene.normal_traction.left" = [300.0, 320.0, 340.0, 350.0]\n' >>"$paper4"
for second in "" "--shard 1/2" "--resume"; do
    dir="$out/two-$total"
    "$bin" study "$paper4" --quiet --jobs 1 --out-dir "$dir" >/dev/null 2>&1 &
    pid=$!
    for _ in $(seq 1 600); do
        [[ -e $dir/paper4/member-0000.events.csv ]] && break
        sleep 0.05
    done
    # shellcheck disable=SC2086
    use "a second study $second" "$bin" study "$paper4" --quiet --out-dir "$dir" $second
    [[ $last == 0 ]] && flag "a second study was let into a busy folder" "study $second ($dir)"
    wait $pid || flag "the first study failed beside a second" "study $second ($dir)"
    for rrd in "$dir"/paper4/member-*.rrd; do
        "$bin" check "$rrd" >/dev/null 2>&1 || flag "a member's recording fails check" "$rrd"
    done
done
failing="$out/failing/failing.toml"
mkdir -p "$out/failing"
printf 'case = "%s/cases/paper_triangular.toml"\n[set]\n"time.t_end" = 300.0\n"time.integrator" = "wilson"\n' \
    "$PWD" >"$failing"
printf '[sweep]\n"time.dt" = [0.01, 100.0, 50.0]\n' >>"$failing"
for extra in "" "--resume"; do
    # shellcheck disable=SC2086
    use "a study with failing members $extra" "$bin" study "$failing" --quiet --out-dir "$out/failing" $extra
    [[ $last == 0 ]] && flag "a study with failed members exited 0" "study failing $extra"
done

# 8. Devices, named pipes and oversized files through every reader; expectations that judge
# nothing.
mkfifo "$out/pipe"
truncate -s 5G "$out/huge.ckpt"
truncate -s 5M "$out/huge.toml"
printf 'case = "/dev/zero"\n' >"$out/zero-case.toml"
printf 'case = "%s"\n' "$out/pipe" >"$out/pipe-case.toml"
"$bin" run cases/spring_block.toml --quiet --set time.t_end=5 --out-dir "$out/base-spring" >/dev/null 2>&1
spring_rrd="$out/base-spring/spring_block.rrd"
for input in /dev/zero "$out/pipe" "$out/huge.ckpt" "$out/huge.toml" "$out/zero-case.toml" "$out/pipe-case.toml"; do
    for command in "resume INPUT" "check RRD --expect INPUT" "check INPUT" "figures INPUT --out $out/f" \
        "replay INPUT" "study INPUT --out-dir $out/s" "run INPUT --out-dir $out/r"; do
        args=${command//INPUT/$input}
        args=${args//RRD/$spring_rrd}
        # shellcheck disable=SC2086
        capped "read $args" "$bin" $args
        [[ $last == 0 ]] && flag "a device, pipe or oversized file was read" "$args"
    done
done
for expect in 'entity = "contact/nothing"
min = 0.0' 'entity = "contact/friction_force"'; do
    file="$out/expect-$total.toml"
    printf '[[at]]\ntime = 1.0\n%s\n' "$expect" >"$file"
    use "expect $expect" "$bin" check "$spring_rrd" --expect "$file"
    [[ $last == 0 ]] && flag "an expectation that judges nothing passed" "expect $expect"
done

echo "$total uses; by exit code:"
for code in $(printf '%s\n' "${!outcomes[@]}" | sort -n); do
    echo "  exit $code: ${outcomes[$code]}"
done
echo "flagged: $flagged (outputs in $out)"
((flagged == 0))
