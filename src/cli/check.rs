//! `slipfront check RECORDING.rrd|LOG.mcap [--expect EXPECT.toml]`: the recording's schema,
//! values and expectations, judged.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::cli::isolated;
use crate::inspect;
use crate::inspect::check::{Expectations, Report, check, check_partial, unknown_series};
use crate::study::replay;

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The recording (.rrd) or MCAP log (.mcap).
    pub recording: PathBuf,
    /// Expectations (TOML): `[events] slip_events = [lo, hi]`, `ruptures = [lo, hi]`, and
    /// `[[at]] entity = "...", time = t, min = a, max = b` (the last row at or before t).
    #[arg(long, value_name = "EXPECT.toml")]
    pub expect: Option<PathBuf>,
    /// Judge a file that may end early (a run killed, or stopped by a full disk, before it
    /// wrote its ending or footer): where the reading stopped is reported rather than failed,
    /// everything read is judged, and the summary says how far it reaches. What only a run's
    /// end writes (the ending record, the space-time map) is asked for only if the file has it.
    #[arg(long)]
    pub partial: bool,
}

/// Runs `slipfront check`.
pub fn command(args: CheckArgs) -> ExitCode {
    if let Err(e) = crate::files::open_regular(&args.recording, RECORDING) {
        return fail(EXIT_INVALID, e);
    }
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
        if let Some(e) = unknown_series(&recording, &expect) {
            return fail(EXIT_INVALID, format!("{}: {e}", args.expect.unwrap_or_default().display()));
        }
        let mut report = judge(&recording, &expect, args.partial);
        report.summary.insert(0, format!("MCAP log: {} messages, {} recorded steps", log.messages, log.frames.len()));
        match &log.problem {
            // Where a log that may end early stops is reported; what it holds is judged.
            Some(problem) if args.partial => {
                report.summary.insert(1, format!("the log ends early: {problem}"));
            }
            Some(problem) => report.problems.insert(0, format!("the log is damaged: {problem}")),
            None => {}
        }
        if !log.skipped.is_empty() {
            report.summary.push(format!("skipped channels of other producers: {:?}", log.skipped));
        }
        report
    } else {
        if let Some(failure) = isolated::decoder_failure(&args.recording) {
            let report = Report { problems: vec![failure], ..Default::default() };
            return match print(&report.render()) {
                Ok(()) => ExitCode::from(EXIT_FAILED),
                Err(exit) => exit,
            };
        }
        let recording = match inspect::rrd::read(&args.recording) {
            Ok(recording) => recording,
            Err(e) => return fail(EXIT_INVALID, e),
        };
        if let Some(e) = unknown_series(&recording, &expect) {
            return fail(EXIT_INVALID, format!("{}: {e}", args.expect.unwrap_or_default().display()));
        }
        judge(&recording, &expect, args.partial)
    };
    if let Err(exit) = print(&report.render()) {
        return exit;
    }
    if report.passed() { ExitCode::SUCCESS } else { ExitCode::from(EXIT_FAILED) }
}

/// What `check` and `figures` read, for the refusal of anything else.
pub(crate) const RECORDING: &str = "a recording is a .rrd file (or an MCAP log, .mcap) that slipfront wrote";

/// [`check`], or with `partial` [`check_partial`].
fn judge(recording: &inspect::Recording, expect: &Expectations, partial: bool) -> Report {
    if partial { check_partial(recording, expect) } else { check(recording, expect) }
}

/// Whether `path` is an MCAP log: named `.mcap`, or starting with the MCAP magic bytes.
pub(crate) fn is_mcap(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 8];
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
        || (std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut magic)).is_ok() && magic == *::mcap::MAGIC)
}
