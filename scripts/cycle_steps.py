#!/usr/bin/env python3
"""The step-size history of cycle steps on cases/cycle_slow_loading.toml, from its MCAP log.

    cargo build --release
    python3 -m pip install mcap matplotlib
    python3 scripts/cycle_steps.py [T_END] [OUT.png]

Runs the case to T_END (default 8e8 s, its first two cycles; the MCAP log of every step is
about 0.8 KB a step, 650 MB for these) into a scratch folder, reads the simulated time of
every step (`record.stick_every = 1` and `record.slip_every = 1`: the log keeps every step, not
every 50th in stick nor the case's every 100th in a slip) from the log's `/contact/totals`
messages, and draws the step size against time
(docs/figures/cycle_slow_loading_steps.png). Prints the smallest and largest step, and the
share of the steps (each one Wilson step of the same 44 unknowns, so nearly the share of the
wall time) and of the simulated time taken by steps under 1 s, 1 s to 1e4 s, and above.
"""

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from mcap.reader import make_reader

ROOT = Path(__file__).resolve().parent.parent
T_END = float(sys.argv[1]) if len(sys.argv) > 1 else 8e8
OUT = Path(sys.argv[2]) if len(sys.argv) > 2 else ROOT / "docs" / "figures" / "cycle_slow_loading_steps.png"
YEAR = 3.15576e7


def step_times(t_end):
    scratch = Path(tempfile.mkdtemp())
    try:
        log = scratch / "steps.mcap"
        subprocess.run(
            [ROOT / "target" / "release" / "slipfront", "run", ROOT / "cases" / "cycle_slow_loading.toml",
             "--no-rrd", "--quiet", "--out-dir", scratch, "--mcap", log, "--set", f"time.t_end={t_end:g}",
             "--set", "record.stick_every=1", "--set", "record.slip_every=1"],
            check=True,
        )
        with open(log, "rb") as f:
            return [m.log_time * 1e-9 for _, channel, m in make_reader(f).iter_messages()
                    if channel.topic == "/contact/totals"]
    finally:
        shutil.rmtree(scratch)


def main():
    times = step_times(T_END)
    steps = [b - a for a, b in zip(times, times[1:])]
    ends = times[1:]
    print(f"{len(steps)} steps to {times[-1]:.6g} s; smallest {min(steps):.3g} s, largest {max(steps):.3g} s")
    for name, low, high in [("under 1 s", 0.0, 1.0), ("1 s to 1e4 s", 1.0, 1e4), ("above 1e4 s", 1e4, float("inf"))]:
        chosen = [h for h in steps if low <= h < high]
        print(f"  {name}: {len(chosen) / len(steps):.1%} of the steps, {sum(chosen) / sum(steps):.2%} of the time")
    fig, ax = plt.subplots(figsize=(9, 4))
    ax.semilogy([t / YEAR for t in ends], steps, ".", markersize=1)
    ax.set_xlabel("simulated time (years)")
    ax.set_ylabel("step (s)")
    ax.set_title(f"cases/cycle_slow_loading.toml: cycle steps from {min(steps):.2g} s to {max(steps):.2g} s")
    ax.grid(True, which="major", alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT, dpi=110)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
