//! The tables `slipfront export` writes: one row per recorded step, a `step` column, a
//! `sim_time_s` column and one column per series, as CSV or as Arrow IPC (Feather v2, which
//! pandas' `read_feather`, polars' `read_ipc` and R's `arrow::read_feather` open natively).
//!
//! Values are exact in both: Arrow stores the `f64` bits, and CSV writes each number in the
//! shortest digits that read back to the same `f64` ([`crate::validate::shortest`]). A series
//! without a row at a step (a file cut between two series) leaves an empty CSV cell, an Arrow
//! null.

use std::io::Write;
use std::sync::Arc;

use rerun::external::arrow;

use arrow::array::{ArrayRef, Float64Array, Int64Array};
use arrow::datatypes::{DataType, Field, Schema};
use arrow::ipc::writer::FileWriter;
use arrow::record_batch::RecordBatch;

use crate::validate::shortest;

/// The name of the step column (a sequence: 0 is the initial state).
pub const STEP_COLUMN: &str = "step";
/// The name of the simulated-time column, in seconds.
pub const TIME_COLUMN: &str = "sim_time_s";

/// A table of time series, one row per recorded step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    pub steps: Vec<i64>,
    /// Simulated time of each row (s).
    pub times: Vec<f64>,
    pub columns: Vec<Column>,
}

/// One series: its column name (with its unit) and a value per row, `None` where it has none.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Column {
    pub name: String,
    pub values: Vec<Option<f64>>,
}

/// The formats a table is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TableFormat {
    /// Comma-separated values, a header line first.
    Csv,
    /// Arrow IPC file (Feather v2), uncompressed.
    #[value(alias = "feather", alias = "ipc")]
    Arrow,
}

impl TableFormat {
    /// The format a file name asks for: `.csv`, or `.arrow`, `.feather`, `.ipc`.
    pub fn from_extension(path: &std::path::Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "csv" => Some(Self::Csv),
            "arrow" | "feather" | "ipc" => Some(Self::Arrow),
            _ => None,
        }
    }

    /// The file extension written by default.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Csv => "csv",
            Self::Arrow => "feather",
        }
    }

    /// Writes `table` to `out` in this format.
    pub fn write(self, table: &Table, out: impl Write) -> Result<(), String> {
        match self {
            Self::Csv => write_csv(table, out).map_err(|e| e.to_string()),
            Self::Arrow => write_arrow(table, out),
        }
    }
}

/// Writes `table` as CSV: a header, then a line per row; names holding a comma or a quote are
/// quoted.
pub fn write_csv(table: &Table, out: impl Write) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(out);
    let quote = |name: &str| {
        if name.contains([',', '"', '\n']) { format!("\"{}\"", name.replace('"', "\"\"")) } else { name.to_string() }
    };
    let mut header = vec![STEP_COLUMN.to_string(), TIME_COLUMN.to_string()];
    header.extend(table.columns.iter().map(|c| quote(&c.name)));
    writeln!(out, "{}", header.join(","))?;
    let mut line = String::new();
    for (row, (step, time)) in table.steps.iter().zip(&table.times).enumerate() {
        line.clear();
        line.push_str(&format!("{step},{}", shortest(*time)));
        for column in &table.columns {
            line.push(',');
            if let Some(value) = column.values[row] {
                line.push_str(&shortest(value));
            }
        }
        writeln!(out, "{line}")?;
    }
    out.flush()
}

/// Writes `table` as one Arrow IPC file (Feather v2) with one record batch: `step` as int64,
/// every other column as float64, nullable where a series has no row.
pub fn write_arrow(table: &Table, out: impl Write) -> Result<(), String> {
    let mut fields =
        vec![Field::new(STEP_COLUMN, DataType::Int64, false), Field::new(TIME_COLUMN, DataType::Float64, false)];
    let mut arrays: Vec<ArrayRef> =
        vec![Arc::new(Int64Array::from(table.steps.clone())), Arc::new(Float64Array::from(table.times.clone()))];
    for column in &table.columns {
        let nullable = column.values.iter().any(Option::is_none);
        fields.push(Field::new(&column.name, DataType::Float64, nullable));
        arrays.push(Arc::new(Float64Array::from(column.values.clone())));
    }
    let schema = Arc::new(Schema::new(fields));
    let batch = RecordBatch::try_new(schema.clone(), arrays).map_err(|e| format!("cannot build the table: {e}"))?;
    let mut writer = FileWriter::try_new(out, &schema).map_err(|e| format!("cannot write the table: {e}"))?;
    writer.write(&batch).map_err(|e| format!("cannot write the table: {e}"))?;
    writer.finish().map_err(|e| format!("cannot write the table: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use arrow::array::Array;

    fn table() -> Table {
        Table {
            steps: vec![0, 3],
            times: vec![0.0, 0.1 + 0.2],
            columns: vec![
                Column { name: "a_Pa".into(), values: vec![Some(1e-320), None] },
                Column { name: "b,c".into(), values: vec![Some(-0.5), Some(f64::MAX)] },
            ],
        }
    }

    #[test]
    fn csv_numbers_read_back_to_the_same_bits() {
        let mut bytes = Vec::new();
        write_csv(&table(), &mut bytes).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "step,sim_time_s,a_Pa,\"b,c\"");
        assert_eq!(lines[1], "0,0,1e-320,-0.5");
        let last: Vec<&str> = lines[2].split(',').collect();
        assert_eq!(last[0], "3");
        assert_eq!(last[1].parse::<f64>().unwrap().to_bits(), (0.1f64 + 0.2).to_bits());
        assert_eq!(last[2], "", "a missing value is an empty cell");
        assert_eq!(last[3].parse::<f64>().unwrap(), f64::MAX);
    }

    #[test]
    fn arrow_reads_back_with_the_same_bits_and_nulls() {
        let mut bytes = Vec::new();
        write_arrow(&table(), &mut bytes).unwrap();
        let reader = arrow::ipc::reader::FileReader::try_new(std::io::Cursor::new(bytes), None).unwrap();
        let batches: Vec<RecordBatch> = reader.map(Result::unwrap).collect();
        assert_eq!(batches.len(), 1);
        let batch = &batches[0];
        assert_eq!(batch.schema().field(2).name(), "a_Pa");
        let a = batch.column(2).as_any().downcast_ref::<Float64Array>().unwrap();
        assert_eq!(a.value(0).to_bits(), 1e-320f64.to_bits());
        assert!(a.is_null(1));
        let time = batch.column(1).as_any().downcast_ref::<Float64Array>().unwrap();
        assert_eq!(time.value(1).to_bits(), (0.1f64 + 0.2).to_bits());
    }
}
