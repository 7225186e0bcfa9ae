//! `slipfront replay`: a slipfront MCAP log back into Rerun, through the very sink a live run
//! uses, so the replayed recording holds what the live one held (schema, blueprint, values).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::frame::Ending;
use crate::inspect::mcap::Log;
use crate::inspect::{ReadError, Recording, rrd};
use crate::sink::collected;
use crate::sink::rerun::{RerunSink, Stream};
use crate::sink::{Sink, SinkError};

/// Re-emits `log` into `stream`. With `speed`, simulated time runs at `speed` × wall time.
/// With `stop` set (by a signal), the replay ends after the current frame, its recording
/// finished as an interrupted run's. Returns how many frames were replayed.
pub fn replay(log: &Log, stream: Stream, speed: Option<f64>, stop: Option<&AtomicBool>) -> Result<usize, SinkError> {
    let mut sink = RerunSink::new(stream, log.header.plan.clone());
    sink.begin(&log.header.layout)?;
    let start = Instant::now();
    let stopped = || stop.is_some_and(|flag| flag.load(Ordering::SeqCst));
    let mut replayed = 0;
    for frame in &log.frames {
        if let Some(speed) = speed {
            // A wait too long for a Duration (a tiny speed, a damaged time) waits the longest.
            let due = Duration::try_from_secs_f64(frame.time / speed).unwrap_or(Duration::MAX);
            while let Some(wait) = due.checked_sub(start.elapsed()).filter(|w| !w.is_zero() && !stopped()) {
                std::thread::sleep(wait.min(PACE_SLICE));
            }
        }
        if stopped() {
            return sink.finish(Ending::Interrupted, log.frames[..replayed].last(), &log.catalog).map(|()| replayed);
        }
        sink.record(frame)?;
        replayed += 1;
    }
    // A log cut off before its ending record replays as an interrupted run.
    let ending = match log.ending.as_ref().map(|e| e.ending.as_str()) {
        Some("completed") => Ending::Completed,
        Some("failed") => Ending::Failed,
        _ => Ending::Interrupted,
    };
    sink.finish(ending, log.frames.last(), &log.catalog).map(|()| replayed)
}

/// The longest sleep between looks at the stop flag while pacing.
const PACE_SLICE: Duration = Duration::from_millis(50);

/// The recording a log replays into, read back for `check`.
pub fn replayed_recording(log: &Log) -> Result<Recording, ReadError> {
    let builder = rerun::RecordingStreamBuilder::new(crate::record::schema::APP_ID).enabled(true);
    let (stream, collected) =
        collected::stream(builder).map_err(|e| ReadError(format!("cannot replay the log in memory: {e}")))?;
    replay(log, Stream { rec: stream.clone(), file: None, file_failure: None }, None, None)
        .map_err(|e| ReadError(format!("cannot replay the log: {e}")))?;
    Ok(rrd::from_messages(collected.take(stream).into_iter().map(Ok)))
}
