"""Prints the names a slipfront recording gives its time series (the `SeriesLines` names the
viewer shows in its legends), as the official Rerun SDK reads them: `entity,index,name`.

usage: python3 read_series_names.py RECORDING.rrd ENTITY [ENTITY ...]
Exit 3 if the SDK is missing (the caller skips), 1 on any other failure.
"""

import sys

from rerun_server import server


def main() -> None:
    path, entities = sys.argv[1], sys.argv[2:]
    with server({"run": [path]}) as running:
        dataset = running.client().get_dataset("run")
        frame = dataset.filter_contents(["/" + e for e in entities]).reader(index="step").to_pandas()
    print("entity,index,name")
    for entity in entities:
        column = f"/{entity}:SeriesLines:names"
        if column not in frame.columns:
            print(f"column {column} missing", file=sys.stderr)
            sys.exit(1)
        # The names are static: logged once, so one row holds them.
        cells = [c for c in frame[column] if c is not None and len(c) > 0]
        if not cells:
            print(f"no names in {column}", file=sys.stderr)
            sys.exit(1)
        for index, name in enumerate(cells[0]):
            print(f"{entity},{index},{name}")


if __name__ == "__main__":
    main()
