"""Reads a slipfront study folder as one dataset with the official Rerun SDK: prints one line
per dataset segment with its member parameters (`segment,ID,LEFT,STRUCTURE0`) from the segment
table, then reads `contact/friction_force` of every member in one query and prints each
member's last value (`final,ID,VALUE`).

usage: python3 read_study.py STUDY_DIR
Exit 3 if the SDK is missing (the caller skips), 1 on any other failure.
"""

import sys

from rerun_server import server


def main() -> None:
    folder = sys.argv[1]
    with server({"study": folder}) as running:
        client = running.client()
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
