#!/usr/bin/env python3
"""Slip frequency and slip size per depth bin over the members of a study of the fault case.

Reads the study's events.csv (slipfront study cases/studies/fault_ensemble.toml writes it under
<out-dir>/fault_ensemble/) and prints, for each depth bin of the fault of
cases/fault_at_depth.toml, over the finished members:

  - slip frequency: slip events per segment per 1000 s, the mean over members with its 95 %
    interval (Student's t over the members' values);
  - slip size: the mean slip of an event (m), each member's mean, then the mean over members
    with its 95 % interval (members without an event in the bin are left out of that bin's size);

then the paper's claim (its section 3.1 and Figure 5: slip frequency falls and slip size grows
with depth) between neighbouring bins and between the shallowest and the deepest: the change
from one bin to the deeper one within each member, its mean over the members and its 95 %
interval. Paired within members, the comparison is not blurred by how much the members differ
as a whole (a chaotic family: 43 to 247 events per member in the shipped study).

The fault of cases/meshes/fault.geo: 20 segments of 0.5 m down a 30 degree dip from 2 m below
the level of the lithostatic normal traction, so segment k's centre lies at depth
2 + (k + 0.5) x 0.5 x sin 30 m.

Usage: python3 scripts/fault_depth_bins.py <out-dir>/fault_ensemble/events.csv [--bins 4] [--t-end 1000]
"""

import argparse
import csv
import math
import statistics
import sys
from collections import defaultdict

SEGMENTS = 20
TOP_DEPTH = 2.0          # m below the level, at the fault's shallow end
SEGMENT_DEPTH = 0.5 * 0.5  # m of depth per segment: 0.5 m along a 30 degree dip

# Two-sided 95 % quantiles of Student's t for n - 1 degrees of freedom, n up to 40.
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
       2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
       2.052, 2.048, 2.045, 2.042, 2.040, 2.037, 2.035, 2.032, 2.030, 2.028, 2.026, 2.024, 2.023]


def interval(values):
    """Mean and half-width of the 95 % t-interval."""
    n = len(values)
    if n == 0:
        return float("nan"), float("nan")
    mean = statistics.fmean(values)
    if n < 2:
        return mean, float("nan")
    t = T95[n - 2] if n - 2 < len(T95) else 1.96
    return mean, t * statistics.stdev(values) / math.sqrt(n)


def depth(segment):
    return TOP_DEPTH + (segment + 0.5) * SEGMENT_DEPTH


def label(b, per_bin):
    """A bin's depths, `2.00 to 3.25`."""
    low, high = depth(b * per_bin) - SEGMENT_DEPTH / 2, depth((b + 1) * per_bin - 1) + SEGMENT_DEPTH / 2
    return f"{low:.2f} to {high:.2f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("events", help="the study's events.csv")
    parser.add_argument("--bins", type=int, default=4, help="depth bins of equal numbers of segments (default 4)")
    parser.add_argument("--t-end", type=float, default=1000.0, help="simulated time of every member (s)")
    args = parser.parse_args()
    if SEGMENTS % args.bins:
        sys.exit(f"--bins {args.bins} must divide the {SEGMENTS} segments")
    per_bin = SEGMENTS // args.bins
    members = set()
    counts = defaultdict(lambda: defaultdict(int))
    slips = defaultdict(lambda: defaultdict(list))
    with open(args.events, newline="") as f:
        for row in csv.DictReader(f):
            member = int(row["member"])
            members.add(member)
            b = int(row["segment"]) // per_bin
            counts[b][member] += 1
            slips[b][member].append(float(row["slip_m"]))
    if not members:
        sys.exit(f"{args.events} holds no events")
    # A member with no event at all does not appear in events.csv; every member of the fault
    # study slips, so the members seen are the members finished.
    print(f"{len(members)} members, {args.t_end:g} s each, {args.bins} depth bins of {per_bin} segments\n")
    print("| depth (m) | slip events per segment per 1000 s | mean slip of an event (m) |")
    print("|---|---|---|")
    rows = []
    for b in range(args.bins):
        frequency = [counts[b][m] / per_bin * 1000.0 / args.t_end for m in sorted(members)]
        size = [statistics.fmean(slips[b][m]) for m in sorted(members) if slips[b][m]]
        (f, df), (s, ds) = interval(frequency), interval(size)
        rows.append((f, df, s, ds))
        print(f"| {label(b, per_bin)} | {f:.2f} ± {df:.2f} | {s:.4f} ± {ds:.4f} ({len(size)} members) |")
    print()
    ordered = sorted(members)
    print("| from -> to (depth, m) | change of frequency per 1000 s | change of mean slip (m) | the claim |")
    print("|---|---|---|---|")
    pairs = [(b, b + 1) for b in range(args.bins - 1)] + ([(0, args.bins - 1)] if args.bins > 2 else [])
    for a, b in pairs:
        df = [(counts[b][m] - counts[a][m]) / per_bin * 1000.0 / args.t_end for m in ordered]
        ds = [statistics.fmean(slips[b][m]) - statistics.fmean(slips[a][m]) for m in ordered
              if slips[a][m] and slips[b][m]]
        (f, hf), (d, hd) = interval(df), interval(ds)
        falls = f + hf < 0
        grows = d - hd > 0
        claim = ("frequency falls, size grows" if falls and grows else
                 "frequency falls; size not shown to grow" if falls else
                 "size grows; frequency not shown to fall" if grows else "neither shown")
        span = f"{label(a, per_bin)} -> {label(b, per_bin)}"
        print(f"| {span} | {f:+.2f} ± {hf:.2f} | {d:+.4f} ± {hd:.4f} ({len(ds)} members) | {claim} |")

if __name__ == "__main__":
    main()
