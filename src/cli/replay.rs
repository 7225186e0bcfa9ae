//! `slipfront replay LOG.mcap [--rrd OUT] [--spawn | --connect URL] [--speed FACTOR]`: an
//! MCAP log re-emitted to Rerun with the live schema and blueprint.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, ViewerArgs, compact_recording, fail, print};
use crate::cli::outputs::{self, Named};
use crate::cli::signals::Stop;
use crate::inspect;
use crate::sink::rerun::{Viewer, open_stream};
use crate::study::replay;
use crate::validate::shortest;

#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The MCAP log (written by `slipfront run --mcap`).
    pub log: PathBuf,
    /// Write the replay to this recording.
    #[arg(long, value_name = "PATH")]
    pub rrd: Option<PathBuf>,
    #[command(flatten)]
    pub viewer: ViewerArgs,
    /// Pace the replay: simulated seconds per wall-clock second (default: as fast as possible).
    #[arg(long, value_name = "FACTOR")]
    pub speed: Option<f64>,
}

/// The paces `--speed` may ask for: slower than a millionth of real time would wait days per
/// simulated second; faster than 1e12 is no pace at all (leave `--speed` out).
const SPEEDS: (f64, f64) = (1e-6, 1e12);

/// Runs `slipfront replay`.
pub fn command(args: ReplayArgs) -> ExitCode {
    if let Some(speed) = args.speed
        && !(SPEEDS.0..=SPEEDS.1).contains(&speed)
    {
        return fail(
            EXIT_INVALID,
            format!(
                "--speed {}: must lie in [{:e}, {:e}] (simulated seconds per wall-clock second)",
                shortest(speed),
                SPEEDS.0,
                SPEEDS.1
            ),
        );
    }
    let log = match inspect::mcap::read(&args.log) {
        Ok(log) => log,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    for (topic, count) in &log.skipped {
        eprintln!("slipfront: skipping {count} messages on {topic}: not a slipfront channel");
    }
    let viewer = args.viewer.viewer();
    let rrd = args.rrd.clone().or_else(|| {
        (viewer == Viewer::None).then(|| {
            let stem = args.log.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "log".into());
            args.log.with_file_name(format!("{stem}.replay.rrd"))
        })
    });
    let claimed = rrd
        .as_deref()
        .map(|path| outputs::claim(&[Named { role: "MCAP log", path: &args.log }], &[Named { role: "--rrd", path }]));
    let _locks = match claimed.transpose() {
        Ok(locks) => locks,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    // The live run's recording id, so that the replayed recording is the same run to Rerun.
    let plan = &log.header.plan;
    let stream = match open_stream(rrd.as_deref(), &viewer, &plan.case, plan.recording_id.as_deref()) {
        Ok(Some(stream)) => stream,
        Ok(None) => return fail(EXIT_INVALID, "nothing to replay into"),
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let stop = Stop::catch();
    let replayed = match replay::replay(&log, stream, args.speed, Some(&stop.flag)) {
        Ok(replayed) => replayed,
        Err(e) => return fail(EXIT_FAILED, e),
    };
    if let Some(rrd) = &rrd {
        compact_recording(rrd);
    }
    let into = rrd.map_or_else(|| "the viewer".to_string(), |p| p.display().to_string());
    if stop.requested() {
        let (code, name) = stop.exit();
        let of = log.frames.len();
        return fail(code, format!("interrupted by {name} after {replayed} of {of} recorded steps; {into} finished"));
    }
    let last = log.frames.last().map_or(0.0, |f| f.time);
    match &log.problem {
        Some(problem) => fail(
            EXIT_FAILED,
            format!(
                "{}: {problem}; replayed {} recorded steps up to t = {last} s into {into}",
                args.log.display(),
                log.frames.len()
            ),
        ),
        None => {
            let line =
                format!("slipfront: replayed {} recorded steps up to t = {last} s into {into}\n", log.frames.len());
            print(&line).err().unwrap_or(ExitCode::SUCCESS)
        }
    }
}
