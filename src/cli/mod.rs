//! The command line: `slipfront run | resume | check | figures | export | replay | study | view`, one file per command.

pub mod check;
pub mod checkpoints;
pub mod common;
pub mod export;
pub mod figures;
pub mod isolated;
pub mod outputs;
pub mod replay;
pub mod resume;
pub mod run;
pub mod signals;
pub mod study;
pub mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub use check::CheckArgs;
pub use common::{EXIT_FAILED, EXIT_INTERRUPTED, EXIT_INVALID, ViewerArgs};
pub use export::ExportArgs;
pub use figures::FiguresArgs;
pub use replay::ReplayArgs;
pub use resume::ResumeArgs;
pub use run::RunArgs;
pub use study::StudyArgs;
pub use view::ViewArgs;

/// Frictional stick-slip with the super/subloading surface friction model: a dynamic finite
/// element solver whose contact follows Yasuike & Toyoda's model, with an event catalog of
/// every slip.
#[derive(Debug, Parser)]
#[command(name = "slipfront", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a case file and write its Rerun recording and event catalog to the output folder.
    ///
    /// Exit codes: 0 success, 1 the run failed (the outputs hold everything up to the last good
    /// step), 2 invalid input, 130 interrupted by Ctrl-C (SIGINT), 143 by SIGTERM, 129 by
    /// SIGHUP, 138 and 140 by SIGUSR1 and SIGUSR2 (outputs finished up to the last step in
    /// every case).
    Run(RunArgs),
    /// Continue a run from its checkpoint (written by `slipfront run --checkpoint-every`), to
    /// its end or, with --set time.t_end=T, beyond it.
    ///
    /// The recording, MCAP log and catalogs are left as those of one uninterrupted run (same
    /// recording id; the parts written after the checkpoint are written again), written beside
    /// them and put in place once finished: a resume that is refused, fails to write or is
    /// killed leaves every output as it was. Exit codes as for `run`; 2 also for a checkpoint
    /// that is not one, is damaged, cut short, of another version, or does not fit its case, and
    /// for a recording or log beside it that is missing, another run's, or cut or damaged before
    /// the checkpoint.
    Resume(ResumeArgs),
    /// Check a recording: the schema's entities, sim_time monotonic and covering the run, no NaN
    /// or Inf, equal row counts, the stored blueprint, and optional expectations.
    ///
    /// Exit codes: 0 pass, 1 mismatch, 2 unreadable.
    Check(CheckArgs),
    /// Draw PNG plots like the paper's Figures 8 (displacement at the probe nodes) and 9
    /// (traction and 1/R* at the probe segments) from a recording.
    Figures(FiguresArgs),
    /// Write a recording's or MCAP log's time series as a table (CSV, or Arrow IPC / Feather v2
    /// for pandas, polars and R): one row per recorded step, units in the column names.
    ///
    /// Choose series with --series, a time window with --from/--to, and thin rows with
    /// --every. Exit codes: 0 written, 1 damaged input (the table holds what came before the
    /// damage), 2 unreadable input or invalid arguments.
    Export(ExportArgs),
    /// Re-emit a slipfront MCAP log to Rerun with the live schema and blueprint.
    ///
    /// Writes <FILE-stem>.replay.rrd beside the log unless --rrd, --spawn or --connect says
    /// otherwise. Exit codes: 0 replayed, 1 the log is damaged (what could be recovered was
    /// replayed), 2 unreadable or invalid arguments.
    Replay(ReplayArgs),
    /// Run every member of an ensemble or parameter sweep of a case (a study file), on the
    /// cores or as one shard of a batch job, into <out-dir>/<study-stem>/: each member's
    /// recording and catalogs, events.csv (every member's events, its parameters as columns),
    /// summary.md and summary.png.
    ///
    /// Exit codes: 0 every selected member finished, 1 a member failed (listed in summary.md)
    /// or could not be written, 2 an invalid study file or argument, or another study writing
    /// the folder (nothing runs), 130/143 interrupted (finished members are kept; --resume runs
    /// the rest).
    Study(StudyArgs),
    /// Open a recording in the Rerun viewer with its time cursor at a chosen simulated time
    /// (--at SECONDS), through a blueprint file written beside it.
    ///
    /// Exit codes: 0 opened (or, with --no-open or no display, the blueprint written and the
    /// commands that open it printed), 1 the blueprint could not be written, 2 invalid input.
    View(ViewArgs),
    /// Decode a recording and exit 0 (the child process of `check` and `figures`).
    #[command(name = "__decode-rrd", hide = true)]
    DecodeRrd { recording: std::path::PathBuf },
}

/// Runs the command line and returns the process exit code.
pub fn main_with(cli: Cli) -> ExitCode {
    match cli.command {
        Command::Run(args) => run::command(args),
        Command::Resume(args) => resume::command(args),
        Command::Check(args) => check::command(args),
        Command::Figures(args) => figures::command(args),
        Command::Export(args) => export::command(args),
        Command::Replay(args) => replay::command(args),
        Command::Study(args) => study::command(args),
        Command::View(args) => view::command(args),
        Command::DecodeRrd { recording } => isolated::decode_in_child(&recording),
    }
}
