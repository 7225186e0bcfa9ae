//! `slipfront export RECORDING.rrd|LOG.mcap`: the recorded time series as a table for pandas,
//! polars, R or a spreadsheet (CSV, or Arrow IPC / Feather v2).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::inspect::export::{self, Selection};
use crate::inspect::{self, Recording};
use crate::record::table::{Table, TableFormat};
use crate::study::replay;

/// Arguments of `slipfront export`.
#[derive(Debug, Args)]
#[command(after_long_help = "\
Columns: step, sim_time_s, then one per series, named by quantity, unit and segment or node:
  friction_force_N_per_m, base_u_x_m, traction_t_Pa_seg3, slip_rate_m_per_s_seg0,
  structure_seg9 (1/R*; R, R_star and structure are dimensionless), u_x_m_node5.
One row per recorded step (every step while a segment slips, every record.stick_every-th in
stick). Values are exact: Arrow holds the f64 bits, CSV the shortest digits that read back to
them (pandas: read_csv(..., float_precision=\"round_trip\")).

Examples:
  slipfront export recordings/paper_triangular.rrd --out paper.feather
  slipfront export recordings/paper_triangular.rrd --series contact/friction_force \\
      --series base/u_x --from 400 --to 450 --out pullout.csv
  slipfront export recordings/paper_triangular.rrd --list

Exit codes: 0 written, 1 the file is damaged (the table holds what came before the damage) or
the table could not be written, 2 unreadable input or invalid arguments.")]
pub struct ExportArgs {
    /// The recording (.rrd) or MCAP log (.mcap).
    pub recording: PathBuf,
    /// The table to write; `-` writes to standard output [default: beside the recording,
    /// <stem>.csv, or <stem>.feather with --format arrow].
    #[arg(long, short, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// csv, or arrow (Arrow IPC file, Feather v2) [default: from --out's extension (.csv;
    /// .feather, .arrow, .ipc), else csv].
    #[arg(long, value_enum)]
    pub format: Option<TableFormat>,
    /// Only these series: an entity (contact/traction_t: every recorded segment), one series
    /// (contact/traction_t[3], the fourth recorded segment) or a column name
    /// (traction_t_Pa_seg3). Repeatable, or comma-separated [default: every series].
    #[arg(long, value_name = "NAME", value_delimiter = ',')]
    pub series: Vec<String>,
    /// Only rows at or after this simulated time (s).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub from: Option<f64>,
    /// Only rows at or before this simulated time (s).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub to: Option<f64>,
    /// Thin the rows: keep a row only when it is at least SECONDS of simulated time after the
    /// last row kept (the recording's rows are dense in slip and sparse in stick).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub every: Option<f64>,
    /// List the columns (with the entity and series each comes from) instead of writing.
    #[arg(long)]
    pub list: bool,
}

/// Runs `slipfront export`.
pub fn command(args: ExportArgs) -> ExitCode {
    let selection = Selection { series: args.series.clone(), from: args.from, to: args.to, every: args.every };
    let (format, out) = match export::check_window(&selection).and_then(|()| destination(&args)) {
        Ok(d) => d,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let recording = match read(&args.recording) {
        Ok(r) => r,
        Err((code, e)) => return fail(code, e),
    };
    if args.list {
        return list(&recording);
    }
    let table = match export::table(&recording, &selection) {
        Ok(t) => t,
        Err(e) => return fail(EXIT_INVALID, format!("{}: {e}", args.recording.display())),
    };
    if let Err(e) = write(&table, format, &out) {
        return fail(EXIT_FAILED, format!("cannot write {}: {e}", out.display()));
    }
    let note = format!("{} rows × {} columns written to {}", table.steps.len(), table.columns.len() + 2, out.display());
    if out != Path::new("-")
        && let Err(exit) = print(&format!("{note}\n"))
    {
        return exit;
    }
    match &recording.problem {
        Some(problem) => fail(
            EXIT_FAILED,
            format!("{} is damaged ({problem}); the table holds what came before", args.recording.display()),
        ),
        None => ExitCode::SUCCESS,
    }
}

/// The format and path to write: `--format`, else `--out`'s extension, else CSV; `--out`, else
/// the recording's stem beside it. Refuses an extension it cannot tell and writing over the
/// input.
fn destination(args: &ExportArgs) -> Result<(TableFormat, PathBuf), String> {
    let format = match (args.format, &args.out) {
        (Some(format), _) => format,
        (None, Some(out)) if out == Path::new("-") => TableFormat::Csv,
        (None, Some(out)) => TableFormat::from_extension(out).ok_or_else(|| {
            format!(
                "--out = {}: name the table .csv, .feather, .arrow or .ipc, or say --format csv|arrow",
                out.display()
            )
        })?,
        (None, None) => TableFormat::Csv,
    };
    let out = args.out.clone().unwrap_or_else(|| args.recording.with_extension(format.extension()));
    let same = |a: &Path, b: &Path| a.canonicalize().ok().zip(b.canonicalize().ok()).is_some_and(|(a, b)| a == b);
    if same(&out, &args.recording) {
        return Err(format!("--out = {} is the input itself: name another file", out.display()));
    }
    Ok((format, out))
}

/// Reads a recording, or an MCAP log through the recording it replays into. The error's exit
/// code: 2 for a file that cannot be read, 1 for one whose decoding would end the process.
fn read(path: &Path) -> Result<Recording, (u8, String)> {
    if !path.is_file() {
        return Err((EXIT_INVALID, format!("{}: no such file", path.display())));
    }
    if crate::cli::check::is_mcap(path) {
        let log = inspect::mcap::read(path).map_err(|e| (EXIT_INVALID, e.to_string()))?;
        let mut recording = replay::replayed_recording(&log).map_err(|e| (EXIT_INVALID, e.to_string()))?;
        recording.problem = log.problem;
        return Ok(recording);
    }
    if let Some(failure) = crate::cli::isolated::decoder_failure(path) {
        return Err((EXIT_FAILED, format!("{failure}; nothing exported")));
    }
    inspect::rrd::read(path).map_err(|e| (EXIT_INVALID, e.to_string()))
}

/// Prints every column the recording can give, with the entity and series it comes from.
fn list(recording: &Recording) -> ExitCode {
    let info = match export::run_info(recording) {
        Ok(info) => info,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let mut text = String::from("column\tentity\tseries\n");
    for series in export::available(recording, &info) {
        text.push_str(&format!("{}\t{}\t{}\n", series.column, series.entity, series.series));
    }
    match print(&text) {
        Ok(()) => ExitCode::SUCCESS,
        Err(exit) => exit,
    }
}

/// Writes `table` to `out` (`-`: standard output), through a temporary file beside it so that
/// a failed write leaves no half table under the name.
fn write(table: &Table, format: TableFormat, out: &Path) -> Result<(), String> {
    if out == Path::new("-") {
        return format.write(table, std::io::stdout().lock());
    }
    let name = out.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let partial = out.with_file_name(format!(".{name}.partial"));
    let written = std::fs::File::create(&partial)
        .map_err(|e| e.to_string())
        .and_then(|file| format.write(table, file))
        .and_then(|()| std::fs::rename(&partial, out).map_err(|e| e.to_string()));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written
}
