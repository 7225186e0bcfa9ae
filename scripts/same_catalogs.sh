#!/usr/bin/env bash
# A pure restructuring changes no result: the event and rupture catalogs of every case and
# integrator are byte-identical between revision REV and the current work tree (or REV2).
# Run `scripts/same_catalogs.sh --help` for the usage.
set -euo pipefail

usage() {
    cat <<'EOF'
Usage: scripts/same_catalogs.sh REV [--against REV2] [--jobs N] [--keep DIR] [--timeout SECS]

Proves that the slip-event and rupture catalogs (<case>.events.csv, <case>.ruptures.csv) are
byte-identical between the slipfront binary of revision REV and that of the current work tree
(uncommitted changes included), for every cases/*.toml with every integrator that applies:

  wilson      the case as is, --set time.integrator=wilson (fixed step)
  wilson-ad   Wilson adaptive, --set time.integrator=wilson --set time.tolerance=1e-6
  tsit5       --set time.integrator=tsit5
  sdirk4      --set time.integrator=sdirk4
  central     --set time.integrator=central

A combination that both binaries refuse as invalid input (exit 2, same message: e.g. the point
scene takes Wilson only) is printed "n/a". The scaling_* meshes run shortened (--set
time.t_end=...) and their slowest integrator/mesh pairs are printed "skipped (slow)", so that
one binary's matrix takes 1.5-3 minutes on 2 cores (measured: 80-104 s, and 136-170 s
while another build shared the machine); paper_triangular runs its full 1000 s with every
fixed-step or Runge-Kutta integrator, adaptive Wilson up to 440 s (its first 4 events).
A run that fails must fail the same way in both (exit code and last line of stderr).

REV is built in a temporary git worktree under target/same-catalogs/ (removed at exit) with
CARGO_TARGET_DIR set to the repository's target/, so the dependencies are reused and only the
slipfront crate recompiles; its binary is copied aside, then the work tree is built the same
way. Before each build the slipfront crate's fingerprints and the uplifted target/release/slipfront
are deleted, and cargo's JSON messages must report that crate rebuilt (not fresh) and name the
executable it wrote: so each binary is provably the one built from its own sources.

Options:
  --against REV2   compare REV with revision REV2 (built in a second worktree) instead of
                   the work tree, e.g. `same_catalogs.sh e8215ae --against e8215ae`
  --jobs N         runs in parallel for each binary (default 2)
  --keep DIR       keep the outputs and logs in DIR (a/ for REV, b/ for the other side)
  --timeout SECS   wall-time limit of each run (default 300)
  -h, --help       this text

Exit status: 0 all identical, 1 some run differs (or timed out), 2 usage or build error.
EOF
}

die() {
    echo "same_catalogs: $*" >&2
    exit 2
}

# ---------------------------------------------------------------------------------------------
# Arguments.
rev_a="" rev_b="" jobs=2 keep="" run_timeout=300
while (($#)); do
    case "$1" in
        -h | --help) usage; exit 0 ;;
        --against) (($# >= 2)) || die "--against needs a revision"; rev_b="$2"; shift 2 ;;
        --jobs) (($# >= 2)) || die "--jobs needs a number"; jobs="$2"; shift 2 ;;
        --keep) (($# >= 2)) || die "--keep needs a folder"; keep="$2"; shift 2 ;;
        --timeout) (($# >= 2)) || die "--timeout needs seconds"; run_timeout="$2"; shift 2 ;;
        -*) die "unknown option $1 (see --help)" ;;
        *) [[ -z "$rev_a" ]] || die "one revision only, or --against REV2 (see --help)"; rev_a="$1"; shift ;;
    esac
done
[[ -n "$rev_a" ]] || { usage >&2; exit 2; }
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs must be a positive integer"
[[ "$run_timeout" =~ ^[1-9][0-9]*$ ]] || die "--timeout must be a positive integer"

root=$(git -C "$(dirname "${BASH_SOURCE[0]}")" rev-parse --show-toplevel) || die "not in a git repository"
target="$root/target"
commit_a=$(git -C "$root" rev-parse --verify --quiet "$rev_a^{commit}") || die "unknown revision $rev_a"
if [[ -n "$rev_b" ]]; then
    commit_b=$(git -C "$root" rev-parse --verify --quiet "$rev_b^{commit}") || die "unknown revision $rev_b"
fi
if [[ -n "$keep" ]]; then
    mkdir -p "$keep" && keep=$(cd "$keep" && pwd -P)
    [[ -z "$(ls -A "$keep")" ]] || die "--keep $keep is not empty"
fi

# ---------------------------------------------------------------------------------------------
# Scratch folder and cleanup: worktrees are removed at exit, whatever happens.
mkdir -p "$target/same-catalogs"
scratch=$(mktemp -d "$target/same-catalogs/run.XXXXXX")
worktrees=()
purge_at_exit=0
cleanup() {
    local status=$? wt
    trap - EXIT INT TERM
    jobs -pr | xargs -r kill 2>/dev/null || true
    # If the last build in target/ was of a worktree, the work tree's next `cargo build` could
    # judge its crate fresh by those mtimes and keep the worktree's: make it recompile.
    if ((purge_at_exit)); then
        forget_slipfront_build
    fi
    for wt in "${worktrees[@]}"; do
        git -C "$root" worktree remove --force "$wt" >/dev/null 2>&1 || rm -rf "$wt"
    done
    git -C "$root" worktree prune >/dev/null 2>&1 || true
    rm -rf "$scratch"
    rmdir "$target/same-catalogs" 2>/dev/null || true
    exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
out=${keep:-$scratch/out}
mkdir -p "$out"

# ---------------------------------------------------------------------------------------------
# Builds.

# Deletes the uplifted target/release/slipfront and the fingerprints of slipfront's release lib
# and bin units (not its tests'). Every checkout of the crate gets the same unit hashes, so
# without this cargo judges the work tree's crate fresh by the mtimes of REV's build and
# keeps (or re-uplifts) REV's.
forget_slipfront_build() {
    local fp
    rm -f "$target/release/slipfront"
    for fp in "$target"/release/.fingerprint/slipfront-*; do
        if [[ -e "$fp/lib-slipfront" || -e "$fp/bin-slipfront" ]]; then
            rm -rf "$fp"
        fi
    done
}

# Builds the slipfront binary of the sources in $1 into the shared target/ and copies it to $2.
# The crate's build is forgotten first, so cargo must recompile the crate and write the binary
# again; its JSON messages must say so.
build_binary() {
    local src=$1 dest=$2 log=$3 artifacts exe
    purge_at_exit=1
    forget_slipfront_build
    echo "  cargo build --release in $src (log: $log)" >&2
    if ! (cd "$src" && CARGO_TARGET_DIR="$target" cargo build --release --bin slipfront \
        --message-format=json-render-diagnostics >"$log.json" 2>"$log"); then
        tail -n 20 "$log" >&2
        die "the build in $src failed"
    fi
    artifacts=$(grep '"reason":"compiler-artifact"' "$log.json" | grep '"name":"slipfront"' || true)
    [[ -n "$artifacts" ]] || die "cargo reported no slipfront artifact for $src"
    if grep -q '"fresh":true' <<<"$artifacts"; then
        die "cargo reused a fresh slipfront crate for $src: its binary cannot be trusted"
    fi
    exe=$(grep -o '"executable":"[^"]*"' <<<"$artifacts" | tail -n 1 | cut -d'"' -f4)
    [[ -n "$exe" && -x "$exe" ]] || die "cargo named no slipfront executable for $src"
    cp "$exe" "$dest"
    [[ "$src" != "$root" ]] || purge_at_exit=0
}

# Which of the checkouts $2 and $3 the binary $1 names as the folder it was compiled in (the
# DWARF compilation directory: the release profile keeps line tables). Every worktree here has a
# fresh path, so a binary that names its own is the one compiled from it. Dies if it names the
# other one; says "unchecked" without strings(1) or debug info.
binary_origin() {
    local bin=$1 own=$2 other=$3 names
    command -v strings >/dev/null || { echo "unchecked (no strings(1))"; return; }
    names=$(strings -n 6 "$bin" | grep -Fx -e "$own" -e "$other" | sort -u || true)
    if [[ "$own" != "$other" ]] && grep -Fxq -- "$other" <<<"$names"; then
        die "the binary built from $own was compiled in $other"
    fi
    if grep -Fxq -- "$own" <<<"$names"; then
        echo "compiled in $own"
    else
        echo "unchecked (it names no compilation folder)"
    fi
}

# Checks out revision $1 in a new worktree $2 (removed at exit).
add_worktree() {
    git -C "$root" worktree add --detach "$2" "$1" >/dev/null 2>&1 || die "cannot check out $1 in $2"
    worktrees+=("$2")
}

src_a="$scratch/wt-a"
add_worktree "$commit_a" "$src_a"
if [[ -n "$rev_b" ]]; then
    src_b="$scratch/wt-b"
    add_worktree "$commit_b" "$src_b"
    label_b="$rev_b (${commit_b:0:10})"
else
    src_b="$root"
    label_b="work tree ($(git -C "$root" rev-parse --short HEAD) + $(git -C "$root" status --porcelain -- src | wc -l) changed paths in src/)"
fi
label_a="$rev_a (${commit_a:0:10})"
# The case files of each side, copied now: the work tree may change while the matrix runs.
cp -r "$src_a/cases" "$scratch/cases-a"
cp -r "$src_b/cases" "$scratch/cases-b"

echo "A = $label_a" >&2
build_binary "$src_a" "$scratch/slipfront-a" "$out/build-a.log"
echo "B = $label_b" >&2
build_binary "$src_b" "$scratch/slipfront-b" "$out/build-b.log"
sum_a=$(sha256sum <"$scratch/slipfront-a" | cut -c1-16)
sum_b=$(sha256sum <"$scratch/slipfront-b" | cut -c1-16)
echo "binaries: A sha256 $sum_a, B sha256 $sum_b ($([[ $sum_a == "$sum_b" ]] && echo "bit-identical" || echo "different"))" >&2
origin_a=$(binary_origin "$scratch/slipfront-a" "$src_a" "$src_b")
origin_b=$(binary_origin "$scratch/slipfront-b" "$src_b" "$src_a")
echo "  A: fresh compile (cargo), $origin_a" >&2
echo "  B: fresh compile (cargo), $origin_b" >&2

# ---------------------------------------------------------------------------------------------
# The matrix.

# Seconds elapsed since $1 (an $EPOCHREALTIME), with one decimal.
seconds_since() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f\n", b - a }'; }
integrators=(wilson wilson-ad tsit5 sdirk4 central)

# The --set arguments of integrator $1.
integrator_sets() {
    case "$1" in
        wilson) echo "--set time.integrator=wilson" ;;
        wilson-ad) echo "--set time.integrator=wilson --set time.tolerance=1e-6" ;;
        tsit5) echo "--set time.integrator=tsit5" ;;
        sdirk4) echo "--set time.integrator=sdirk4" ;;
        central) echo "--set time.integrator=central" ;;
    esac
}

# How case $1 runs with integrator $2: extra --set arguments (none: the case's full t_end), or
# "skip". Chosen from single runs of e8215ae on this 2-core machine (seconds in brackets) so
# that one binary's whole matrix takes under 3 minutes with 2 jobs. The 10 x 1 cases run their full
# 1000 s (1-4 s each) but for adaptive Wilson, slow through slip at 1e-6 (paper 281 s), which
# stops just past its first events (paper and triangular_inverted: 4 events by 440 s [4 s];
# uniform_low: 6 by 360 s [3 s]; uniform_high: 10 by 950 s [2 s]). scaling_100x10 (first slip
# at 421.6 s): central differences the full 1000 s (493 events) [12 s]; the others until 425 s
# (20 events) [wilson 44 s, tsit5 35 s, sdirk4 14 s]; adaptive Wilson 10 s [6 s]. The finer
# meshes run only a few seconds of loading (no event: the catalogs are headers, the runs prove
# the same code paths complete) and skip what their setup alone makes slow: adaptive Wilson on
# 300 x 30 takes 21 s for 0.2 s, and on 1000 x 100 SDIRK4 takes 106 s and adaptive Wilson 169 s
# for 0.01 s.
case_plan() {
    case "$1:$2" in
        scaling_1000x100:central) echo "--set time.t_end=1" ;;          # [3 s]
        scaling_1000x100:tsit5) echo "--set time.t_end=0.1" ;;          # [7 s]
        scaling_1000x100:wilson) echo "--set time.t_end=0.05" ;;        # [16-20 s]
        scaling_1000x100:*) echo "skip" ;;
        scaling_300x30:central) echo "--set time.t_end=20" ;;           # [3 s]
        scaling_300x30:tsit5) echo "--set time.t_end=5" ;;              # [4 s]
        scaling_300x30:wilson) echo "--set time.t_end=2" ;;             # [4 s]
        scaling_300x30:sdirk4) echo "--set time.t_end=0.5" ;;           # [6 s]
        scaling_300x30:*) echo "skip" ;;
        scaling_100x10:central) echo "" ;;
        scaling_100x10:wilson-ad) echo "--set time.t_end=10" ;;
        scaling_100x10:*) echo "--set time.t_end=425" ;;
        paper_triangular:wilson-ad | triangular_inverted:wilson-ad) echo "--set time.t_end=440" ;;
        uniform_low:wilson-ad) echo "--set time.t_end=360" ;;
        uniform_high:wilson-ad) echo "--set time.t_end=950" ;;
        *) echo "" ;;
    esac
}

# Runs case $2 with integrator $3 by binary side $1 (a or b) in its own folder, where `cases`
# links to that side's case files and the catalogs go to `out/`: the paths the binary sees, and
# so its messages, are the same on both sides. Leaves command, rc, stderr and seconds there.
run_one() {
    local side=$1 case=$2 integrator=$3 dir start rc
    dir="$out/$side/$case.$integrator"
    mkdir -p "$dir"
    ln -s "$scratch/cases-$side" "$dir/cases"
    # shellcheck disable=SC2046 # the --set arguments are words by design
    set -- run "cases/$case.toml" --quiet --no-rrd --out-dir out \
        $(integrator_sets "$integrator") $(case_plan "$case" "$integrator")
    echo "slipfront $*" >"$dir/command"
    start=$EPOCHREALTIME
    rc=0
    (cd "$dir" && exec timeout -k 10 "$run_timeout" "$scratch/slipfront-$side" "$@" >stdout 2>stderr </dev/null) || rc=$?
    echo "$rc" >"$dir/rc"
    seconds_since "$start" >"$dir/seconds"
}

cases=()
for f in "$scratch"/cases-b/*.toml; do
    cases+=("$(basename "$f" .toml)")
done
# The slowest runs start first, so that the last ones to finish are short.
run_order=()
for case in scaling_100x10 scaling_1000x100 scaling_300x30 "${cases[@]}"; do
    if [[ -f "$scratch/cases-b/$case.toml" && " ${run_order[*]} " != *" $case "* ]]; then
        run_order+=("$case")
    fi
done

# Runs the whole matrix for side $1, $jobs at a time; sets matrix_seconds to its wall time.
run_matrix() {
    local side=$1 case integrator start
    start=$EPOCHREALTIME
    for case in "${run_order[@]}"; do
        for integrator in "${integrators[@]}"; do
            [[ "$(case_plan "$case" "$integrator")" != skip ]] || continue
            while (($(jobs -rp | wc -l) >= jobs)); do
                wait -n || true
            done
            run_one "$side" "$case" "$integrator" &
        done
    done
    wait
    matrix_seconds=$(seconds_since "$start")
}

echo "matrix of A ($jobs parallel runs)..." >&2
run_matrix a
time_a=$matrix_seconds
echo "  ${time_a} s" >&2
echo "matrix of B ($jobs parallel runs)..." >&2
run_matrix b
time_b=$matrix_seconds
echo "  ${time_b} s" >&2

# ---------------------------------------------------------------------------------------------
# Comparison.

# "identical", "differ", "absent" (in both) or "missing in a/b" for catalog file $3 of runs $1, $2.
compare_file() {
    local fa="$1/$3" fb="$2/$3"
    if [[ ! -e "$fa" && ! -e "$fb" ]]; then
        echo "absent"
    elif [[ ! -e "$fa" ]]; then
        echo "missing in A"
    elif [[ ! -e "$fb" ]]; then
        echo "missing in B"
    elif cmp -s "$fa" "$fb"; then
        echo "identical"
    else
        echo "DIFFER"
    fi
}

last_line() { grep -v '^[[:space:]]*$' "$1" 2>/dev/null | tail -n 1 || true; }

runs=0 differ=0 na=0 skipped=0
printf '%-20s %-10s %-10s %-12s %-12s %7s %7s  %s\n' case integrator verdict events ruptures "A s" "B s" note
for case in "${cases[@]}"; do
    for integrator in "${integrators[@]}"; do
        if [[ "$(case_plan "$case" "$integrator")" == skip ]]; then
            printf '%-20s %-10s %s\n' "$case" "$integrator" "skipped (slow)"
            skipped=$((skipped + 1))
            continue
        fi
        da="$out/a/$case.$integrator" db="$out/b/$case.$integrator"
        rc_a=$(cat "$da/rc") rc_b=$(cat "$db/rc")
        err_a=$(last_line "$da/stderr") err_b=$(last_line "$db/stderr")
        ev=$(compare_file "$da/out" "$db/out" "$case.events.csv")
        ru=$(compare_file "$da/out" "$db/out" "$case.ruptures.csv")
        note=""
        cmp -s "$scratch/cases-a/$case.toml" "$scratch/cases-b/$case.toml" 2>/dev/null || note="case file differs; "
        if [[ $rc_a == 2 && $rc_b == 2 && "$err_a" == "$err_b" ]]; then
            printf '%-20s %-10s %s\n' "$case" "$integrator" "n/a (both refuse: ${err_a#slipfront: })"
            na=$((na + 1))
            continue
        fi
        runs=$((runs + 1))
        if [[ $rc_a != "$rc_b" ]] || [[ $rc_a != 0 && "$err_a" != "$err_b" ]]; then
            verdict="DIFFER"
            note+="exit A $rc_a: ${err_a:-(no stderr)} / exit B $rc_b: ${err_b:-(no stderr)}"
        elif [[ $rc_a == 124 ]]; then
            verdict="TIMEOUT"
            note+="both timed out after ${run_timeout} s"
        elif [[ $ev == identical && ($ru == identical || $ru == absent) ]]; then
            verdict="identical"
            [[ $rc_a == 0 ]] || note+="both failed identically (exit $rc_a: $err_a)"
        else
            verdict="DIFFER"
        fi
        [[ $verdict == identical ]] || differ=$((differ + 1))
        printf '%-20s %-10s %-10s %-12s %-12s %7.1f %7.1f  %s\n' "$case" "$integrator" "$verdict" "$ev" "$ru" \
            "$(cat "$da/seconds")" "$(cat "$db/seconds")" "$note"
    done
done
echo "A = $label_a, sha256 $sum_a, $origin_a: matrix ${time_a} s"
echo "B = $label_b, sha256 $sum_b, $origin_b: matrix ${time_b} s (${jobs} parallel runs each)"
extra="$na n/a, $skipped skipped"
[[ -z "$keep" ]] || extra+="; outputs kept in $keep"
if ((differ == 0)); then
    echo "$runs runs: all identical ($extra)"
else
    echo "$runs runs: $differ differ ($extra)"
    exit 1
fi
