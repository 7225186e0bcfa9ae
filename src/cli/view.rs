//! `slipfront view RECORDING.rrd --at SECONDS`: the recording opened in the Rerun viewer with
//! its time cursor at a chosen simulated time ([`crate::sink::open_at`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::inspect::rrd;
use crate::sink::open_at;
use crate::validate::shortest;

/// Arguments of `slipfront view`.
#[derive(Debug, Args)]
#[command(after_long_help = "\
Rerun 0.36 cannot move a file's time cursor from the command line or a URL (its #when= fragment
works in a dataset on a Rerun server only). This writes a blueprint file beside the recording,
<stem>.at-<SECONDS>s.rbl, that extends the recording's own layout with a time panel playing a
loop of zero length at SECONDS, which holds the cursor there, and opens both:

  rerun RECORDING.rrd RECORDING.at-425.3s.rbl              # a window
  rerun --serve-web RECORDING.rrd RECORDING.at-425.3s.rbl  # a browser

Pause (space) to scrub from there; the loop button in the time panel turns the loop off.")]
pub struct ViewArgs {
    /// The recording (.rrd).
    pub recording: PathBuf,
    /// The simulated time (s) to open the recording at.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub at: f64,
    /// Write the blueprint file here instead [default: <recording-stem>.at-<SECONDS>s.rbl beside it].
    #[arg(long, value_name = "PATH")]
    pub blueprint: Option<PathBuf>,
    /// Only write the blueprint file and print how to open it; start no viewer.
    #[arg(long)]
    pub no_open: bool,
}

/// Runs `slipfront view`.
pub fn command(args: ViewArgs) -> ExitCode {
    if !(args.at.is_finite() && args.at >= 0.0) {
        return fail(
            EXIT_INVALID,
            format!("--at = {} must be a simulated time in seconds, 0 or more", shortest(args.at)),
        );
    }
    if !args.recording.is_file() {
        return fail(EXIT_INVALID, format!("{}: no such file", args.recording.display()));
    }
    let store = match rrd::blueprint_store(&args.recording) {
        Ok(Some(store)) => store,
        Ok(None) => {
            return fail(
                EXIT_INVALID,
                format!("{} has no blueprint: not a slipfront recording", args.recording.display()),
            );
        }
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let blueprint = args.blueprint.clone().unwrap_or_else(|| beside(&args.recording, args.at));
    if let Err(e) = open_at::write(&blueprint, &store, args.at) {
        return fail(EXIT_FAILED, e);
    }
    let (recording, blueprint) = (args.recording.display(), blueprint.display());
    let how = format!(
        "{blueprint} opens {recording} at {} s:\n  rerun {recording} {blueprint}\n  rerun --serve-web {recording} {blueprint}   (in a browser)\n",
        shortest(args.at)
    );
    if args.no_open || !can_open() {
        return match print(&how) {
            Ok(()) => ExitCode::SUCCESS,
            Err(exit) => exit,
        };
    }
    match std::process::Command::new("rerun").arg(&args.recording).arg(blueprint.to_string()).spawn() {
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => fail(EXIT_FAILED, format!("cannot start `rerun`: {e}; {how}")),
    }
}

/// `<dir>/<stem>.at-<SECONDS>s.rbl` beside the recording.
fn beside(recording: &Path, at: f64) -> PathBuf {
    let stem = recording.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    recording.with_file_name(format!("{stem}.at-{}s.rbl", shortest(at)))
}

/// Whether a viewer window can be opened here: a display, and `rerun` on `PATH`.
fn can_open() -> bool {
    crate::sink::rerun::has_display() && crate::sink::rerun::find_on_path("rerun").is_some()
}
