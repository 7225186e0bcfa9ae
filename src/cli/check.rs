//! `slipfront check RECORDING.rrd|LOG.mcap [--expect EXPECT.toml]`: the recording's schema,
//! values and expectations, judged.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::cli::isolated;
use crate::inspect;
use crate::inspect::check::{Expectations, check};
use crate::study::replay;

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The recording (.rrd) or MCAP log (.mcap).
    pub recording: PathBuf,
    /// Expectations (TOML): `[events] slip_events = [lo, hi]`, `ruptures = [lo, hi]`, and
    /// `[[at]] entity = "...", time = t, min = a, max = b` (the last row at or before t).
    #[arg(long, value_name = "EXPECT.toml")]
    pub expect: Option<PathBuf>,
}

/// Runs `slipfront check`.
pub fn command(args: CheckArgs) -> ExitCode {
    let expect = match &args.expect {
        Some(path) => match Expectations::load(path) {
            Ok(e) => e,
            Err(e) => return fail(EXIT_INVALID, e),
        },
        None => Expectations::default(),
    };
    let report = if is_mcap(&args.recording) {
        // An MCAP log is judged by the recording it replays into, plus its own damage.
        let log = match inspect::mcap::read(&args.recording) {
            Ok(log) => log,
            Err(e) => return fail(EXIT_INVALID, e),
        };
        let recording = match replay::replayed_recording(&log) {
            Ok(r) => r,
            Err(e) => return fail(EXIT_INVALID, e),
        };
        let mut report = check(&recording, &expect);
        report.summary.insert(0, format!("MCAP log: {} messages, {} recorded steps", log.messages, log.frames.len()));
        if let Some(problem) = &log.problem {
            report.problems.insert(0, format!("the log is damaged: {problem}"));
        }
        if !log.skipped.is_empty() {
            report.summary.push(format!("skipped channels of other producers: {:?}", log.skipped));
        }
        report
    } else {
        if let Some(failure) = isolated::decoder_failure(&args.recording) {
            let report = inspect::check::Report { problems: vec![failure], ..Default::default() };
            return match print(&report.render()) {
                Ok(()) => ExitCode::from(EXIT_FAILED),
                Err(exit) => exit,
            };
        }
        match inspect::rrd::read(&args.recording) {
            Ok(recording) => check(&recording, &expect),
            Err(e) => return fail(EXIT_INVALID, e),
        }
    };
    if let Err(exit) = print(&report.render()) {
        return exit;
    }
    if report.passed() { ExitCode::SUCCESS } else { ExitCode::from(EXIT_FAILED) }
}

/// Whether `path` is an MCAP log: named `.mcap`, or starting with the MCAP magic bytes.
fn is_mcap(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 8];
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
        || (std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut magic)).is_ok() && magic == *::mcap::MAGIC)
}
