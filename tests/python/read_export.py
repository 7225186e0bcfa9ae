"""Reads a `slipfront export` table back with pandas and polars (Feather and CSV) and compares
every value, bit for bit, with the recording as the official Rerun SDK reads it.

usage: python3 read_export.py RECORDING.rrd TABLE.feather TABLE.csv

Prints `rows R columns C` and, for the whole-recording query the docs warn about, the error it
raises (`whole-recording to_pandas: <error type>: <first words>`). Exit 3 if pandas, polars,
pyarrow or the Rerun SDK is missing (the caller skips), 1 on any mismatch.
"""

import re
import sys

try:
    import numpy as np
    import pandas as pd
    import polars as pl
    import pyarrow  # noqa: F401  (pandas' read_feather needs it)
except ImportError as missing:
    print(f"{missing.name} is not installed", file=sys.stderr)
    sys.exit(3)

from rerun_server import server

PANDAS_3 = int(pd.__version__.split(".")[0]) >= 3
COLUMN = re.compile(r"^(?P<quantity>.+?)(?:_(?P<unit>Pa|m|m_per_s|N_per_m))?(?:_(?P<place>seg|node)(?P<index>\d+))?$")
TOTALS = {"friction_force": "contact/friction_force", "base_u_x": "base/u_x", "block_x": "block/x", "block_v": "block/v"}


def bits(values) -> np.ndarray:
    """The IEEE 754 bits of float values (NaN for a missing one)."""
    return np.asarray(values, dtype=np.float64).view(np.uint64)


def fail(message: str) -> None:
    print(message, file=sys.stderr)
    sys.exit(1)


def entity_of(column: str, nodes: list, segments: list) -> tuple:
    """`traction_t_Pa_seg3` -> (`/contact/traction_t`, instance of segment 3)."""
    match = COLUMN.match(column)
    quantity, place, index = match["quantity"], match["place"], match["index"]
    if place is None:
        return "/" + TOTALS[quantity], 0
    if place == "node":
        return f"/body/{quantity}", nodes.index(int(index))
    return f"/contact/{quantity}", segments.index(int(index))


def main() -> None:
    recording, feather, csv = sys.argv[1:4]
    tables = {
        "pandas read_feather": pd.read_feather(feather),
        # pandas 3 parses CSV numbers exactly; pandas 2 only when asked to.
        "pandas read_csv": pd.read_csv(csv, **({} if PANDAS_3 else {"float_precision": "round_trip"})),
        "polars read_ipc": pl.read_ipc(feather).to_pandas(),
        "polars read_csv": pl.read_csv(csv).to_pandas(),
    }
    reference = tables["pandas read_feather"]
    columns = [c for c in reference.columns if c not in ("step", "sim_time_s")]
    segments = sorted({int(m["index"]) for c in columns if (m := COLUMN.match(c))["place"] == "seg"})
    nodes = sorted({int(m["index"]) for c in columns if (m := COLUMN.match(c))["place"] == "node"})
    entities = sorted({entity_of(c, nodes, segments)[0] for c in columns})
    with server({"run": [recording]}) as running:
        dataset = running.client().get_dataset("run")
        truth = dataset.filter_contents(entities).reader(index="step").to_pandas().set_index("step")
        try:
            dataset.reader(index="sim_time").to_pandas()
            print("whole-recording to_pandas: no error")
        except Exception as error:  # noqa: BLE001  (the docs name the error, so report it whole)
            print(f"whole-recording to_pandas: {type(error).__name__}: {str(error)[:120]}")
    steps = reference["step"].to_numpy()
    times = np.array([t.value / 1e9 for t in truth.loc[steps, "sim_time"]])
    for name, table in tables.items():
        if list(table.columns) != list(reference.columns) or len(table) != len(reference):
            fail(f"{name}: columns or rows differ from the Feather table's")
        if not np.array_equal(table["step"].to_numpy(), steps):
            fail(f"{name}: steps differ")
        if not np.array_equal(bits(table["sim_time_s"]), bits(times)):
            fail(f"{name}: sim_time_s differs from the recording's sim_time")
        for column in columns:
            entity, instance = entity_of(column, nodes, segments)
            cells = truth.loc[steps, f"{entity}:Scalars:scalars"]
            expected = [float(cell[instance]) for cell in cells]
            if not np.array_equal(bits(table[column]), bits(expected)):
                first = int(np.argmax(bits(table[column]) != bits(expected)))
                fail(f"{name}: {column} at step {steps[first]}: {table[column].iloc[first]!r} != {expected[first]!r}")
    print(f"rows {len(reference)} columns {len(reference.columns)}")


if __name__ == "__main__":
    main()
