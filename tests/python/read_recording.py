"""Reads scalar columns of a slipfront recording with the official Rerun SDK (an independent
judge of what slipfront writes) and prints them as CSV: series,step,sim_time_s,value.

usage: python3 read_recording.py RECORDING.rrd SERIES [SERIES ...]

A series is an entity (`contact/friction_force`) or one instance of a multi-instance entity
(`contact/traction_t[3]`, the fourth recorded segment).
Exit 3 if the SDK is missing (the caller skips), 1 on any other failure.
"""

import math
import sys

from rerun_server import server


def split(series: str) -> tuple[str, int]:
    """`contact/traction_t[3]` -> (`contact/traction_t`, 3); a total's instance is 0."""
    if series.endswith("]"):
        entity, index = series[:-1].split("[")
        return entity, int(index)
    return series, 0


def main() -> None:
    path, names = sys.argv[1], sys.argv[2:]
    entities = sorted({split(n)[0] for n in names})
    with server({"run": [path]}) as running:
        client = running.client()
        dataset = client.get_dataset("run")
        frame = dataset.filter_contents(["/" + e for e in entities]).reader(index="step").to_pandas()
    print("series,step,sim_time_s,value")
    for name in names:
        entity, instance = split(name)
        column = f"/{entity}:Scalars:scalars"
        if column not in frame.columns:
            print(f"column {column} missing", file=sys.stderr)
            sys.exit(1)
        for step, time, cell in zip(frame["step"], frame["sim_time"], frame[column]):
            if cell is None or (isinstance(cell, float) and math.isnan(cell)):
                continue
            seconds = time.total_seconds() if hasattr(time, "total_seconds") else time / 1e9
            print(f"{name},{int(step)},{seconds!r},{float(cell[instance])!r}")


if __name__ == "__main__":
    main()
