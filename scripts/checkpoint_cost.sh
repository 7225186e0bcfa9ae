#!/usr/bin/env bash
# What checkpoints cost: N interleaved pairs of runs of CASE, without and with
# --checkpoint-every at its default interval (a tenth of time.t_end), their median wall times and
# the median ratio; and the checkpoints' count, size and write time from the run's summary.
#
# Usage: scripts/checkpoint_cost.sh N CASE [--set KEY=VALUE ...]
#   scripts/checkpoint_cost.sh 7 cases/paper_triangular.toml
#   scripts/checkpoint_cost.sh 3 cases/paper_triangular.toml --set scene.nx=1000 --set scene.ny=100 --set time.t_end=100
set -euo pipefail
cd "$(dirname "$0")/.."
n="$1"; case_file="$2"; shift 2
bin=target/release/slipfront
cargo build --release --quiet --bin slipfront
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
seconds() { python3 -c 'import time; print(time.monotonic())'; }
for i in $(seq "$n"); do
    start=$(seconds); "$bin" run "$case_file" --quiet --out-dir "$out/plain" "$@"; end=$(seconds)
    echo "plain $start $end" >> "$out/times"
    start=$(seconds); "$bin" run "$case_file" --out-dir "$out/checkpointed" --checkpoint-every "$@" \
        > "$out/summary" 2>/dev/null; end=$(seconds)
    echo "checkpointed $start $end" >> "$out/times"
done
python3 - "$out/times" "$out/summary" "$out/checkpointed" <<'PY'
import re, statistics, sys, pathlib
rows = [line.split() for line in open(sys.argv[1])]
plain = [float(e) - float(s) for k, s, e in rows if k == "plain"]
checked = [float(e) - float(s) for k, s, e in rows if k == "checkpointed"]
ratios = [c / p for p, c in zip(plain, checked)]
summary = open(sys.argv[2]).read()
found = re.search(r"(\d+) checkpoints? \(([\d.]+) MB, ([\d.]+) s\)", summary)
size = pathlib.Path(sys.argv[3], next(pathlib.Path(sys.argv[3]).glob("*.ckpt")).name).stat().st_size
print(f"runs: {len(plain)} pairs, interleaved")
print(f"median wall: {statistics.median(plain):.3f} s without, {statistics.median(checked):.3f} s with checkpoints")
print(f"median ratio (with / without): {statistics.median(ratios):.4f}  (all: {', '.join(f'{r:.3f}' for r in ratios)})")
if found:
    count, mb, spent = int(found[1]), float(found[2]), float(found[3])
    print(f"checkpoints per run: {count}; one checkpoint: {size / 1e6:.3f} MB, written in {1e3 * spent / count:.1f} ms")
PY
