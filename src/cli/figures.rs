//! `slipfront figures RECORDING.rrd [--out DIR]`: the paper's Figures 8 and 9 as PNG files.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::inspect;
use crate::study::figures;

#[derive(Debug, Args)]
pub struct FiguresArgs {
    /// The recording (.rrd).
    pub recording: PathBuf,
    /// Folder for the PNG files (created if missing).
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub out: PathBuf,
}

/// Runs `slipfront figures`.
pub fn command(args: FiguresArgs) -> ExitCode {
    if let Some(failure) = crate::cli::isolated::decoder_failure(&args.recording) {
        return fail(EXIT_FAILED, format!("{failure}; no figures drawn"));
    }
    let recording = match inspect::rrd::read(&args.recording) {
        Ok(r) => r,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    match figures::write_figures(&recording, &args.out) {
        Ok(paths) => {
            let listing: String = paths.iter().map(|path| format!("{}\n", path.display())).collect();
            if let Err(exit) = print(&listing) {
                return exit;
            }
            // Figures drawn from a damaged file show what came before the damage: say so.
            match &recording.problem {
                Some(problem) => fail(
                    EXIT_FAILED,
                    format!("{} is damaged ({problem}); the figures show what came before", args.recording.display()),
                ),
                None => ExitCode::SUCCESS,
            }
        }
        // Nothing to draw: the damage, if any, is why.
        Err(e) => match &recording.problem {
            Some(problem) => {
                fail(EXIT_FAILED, format!("{} is damaged ({problem}): {e}; no figures drawn", args.recording.display()))
            }
            None => fail(EXIT_FAILED, e),
        },
    }
}
