"""Reads a slipfront study folder as one dataset with the official Rerun SDK: prints one line
per dataset segment with its member parameters (`segment,ID,LEFT,STRUCTURE0`) from the segment
table, then reads `contact/friction_force` of every member in one query and prints each
member's last value (`final,ID,VALUE`).

usage: python3 read_study.py STUDY_DIR
Exit 3 if the SDK is missing (the caller skips), 1 on any other failure.
"""

import socket
import sys

try:
    import rerun as rr
except ImportError:
    print("rerun-sdk is not installed", file=sys.stderr)
    sys.exit(3)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def main() -> None:
    folder = sys.argv[1]
    with rr.server.Server(host="127.0.0.1", port=free_port(), datasets={"study": folder}) as server:
        client = server.client()
        dataset = client.get_dataset("study")
        table = dataset.segment_table().to_pandas()
        left = "property:case:scene_normal_traction_left"
        structure = "property:case:friction_structure0"
        for _, row in table.iterrows():
            print(f"segment,{row['rerun_segment_id']},{float(row[left][0])!r},{float(row[structure][0])!r}")
        frame = dataset.filter_contents(["/contact/friction_force"]).reader(index="step").to_pandas()
        column = "/contact/friction_force:Scalars:scalars"
        for segment, rows in frame.groupby("rerun_segment_id"):
            values = [cell[0] for cell in rows.sort_values("step")[column] if cell is not None]
            print(f"final,{segment},{values[-1]!r}")


if __name__ == "__main__":
    main()
