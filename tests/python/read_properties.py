"""Prints the recording properties of slipfront recordings as the official Rerun SDK's dataset
server sees them: one line per recording and property column, `segment,column,value`.

usage: python3 read_properties.py RECORDING.rrd [RECORDING.rrd ...]
Exit 3 if the SDK is missing (the caller skips), 1 on any other failure.
"""

import sys

from rerun_server import server


def main() -> None:
    paths = sys.argv[1:]
    with server({"runs": paths}) as running:
        client = running.client()
        dataset = client.get_dataset("runs")
        table = dataset.segment_table().to_pandas()
    print("segment,column,value")
    for _, row in table.iterrows():
        for column in table.columns:
            if column.startswith("property:"):
                cell = row[column]
                value = cell[0] if hasattr(cell, "__len__") and not isinstance(cell, str) else cell
                print(f"{row['rerun_segment_id']},{column},{value}")


if __name__ == "__main__":
    main()
