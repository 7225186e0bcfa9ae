"""Reads a slipfront study as one dataset with the official Rerun SDK: prints one line per
dataset segment with its member parameters (`segment,ID,LEFT,STRUCTURE0`) from the segment
table, then reads `contact/friction_force` of every member in one query and prints each
member's last value (`final,ID,VALUE`), segments in order.

usage: python3 read_study.py STUDY_DIR        serves the folder itself, on a free local port
       python3 read_study.py rerun+http://HOST:PORT
                                              queries a server already serving it as `study`
                                              (`rerun server -d study=STUDY_DIR`), as a colleague
                                              would; waits up to 60 s for it to answer
Exit 3 if the SDK is missing (the caller skips), 1 on any other failure.
"""

import sys
import time

from rerun_server import rr, server


def query(client) -> None:
    dataset = client.get_dataset("study")
    table = dataset.segment_table().to_pandas().sort_values("rerun_segment_id")
    left = "property:case:scene_normal_traction_left"
    structure = "property:case:friction_structure0"
    for _, row in table.iterrows():
        print(f"segment,{row['rerun_segment_id']},{float(row[left][0])!r},{float(row[structure][0])!r}")
    frame = dataset.filter_contents(["/contact/friction_force"]).reader(index="step").to_pandas()
    column = "/contact/friction_force:Scalars:scalars"
    for segment, rows in sorted(frame.groupby("rerun_segment_id"), key=lambda group: group[0]):
        values = [cell[0] for cell in rows.sort_values("step")[column] if cell is not None]
        print(f"final,{segment},{values[-1]!r}")


def connect(url: str):
    """A client of the server at `url`, once it answers with its datasets."""
    deadline = time.monotonic() + 60
    while True:
        try:
            client = rr.catalog.CatalogClient(url)
            client.datasets()
            return client
        except Exception:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


def main() -> None:
    target = sys.argv[1]
    if target.startswith("rerun+http"):
        query(connect(target))
        return
    with server({"study": target}) as running:
        query(running.client())


if __name__ == "__main__":
    main()
