//! A recording stream whose messages are kept in memory, for the blueprint's capture and an
//! in-memory replay.
//!
//! Rerun's own memory sink (`RecordingStreamBuilder::memory`) keeps a strong handle to its
//! stream, so the stream is never dropped and leaves its two threads running: a process that
//! builds many recordings runs out of threads (the `mcap_read` fuzz target did, at about 2 000
//! replays a minute, each making three such streams). This sink holds only the messages, so
//! the stream ends when its last handle is dropped.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use rerun::log::LogMsg;
use rerun::sink::{LogSink, SinkFlushError};
use rerun::{RecordingStream, RecordingStreamBuilder, RecordingStreamResult};

/// The messages a [`stream`] was sent.
#[derive(Clone, Default)]
pub struct Collected(Arc<Mutex<Vec<LogMsg>>>);

impl Collected {
    /// Flushes `rec` (so that everything logged has arrived), drops it and takes the messages.
    pub fn take(self, rec: RecordingStream) -> Vec<LogMsg> {
        let _ = rec.flush_blocking();
        drop(rec);
        std::mem::take(&mut *self.0.lock().unwrap_or_else(PoisonError::into_inner))
    }
}

impl LogSink for Collected {
    fn send(&self, msg: LogMsg) {
        self.0.lock().unwrap_or_else(PoisonError::into_inner).push(msg);
    }

    fn flush_blocking(&self, _timeout: Duration) -> Result<(), SinkFlushError> {
        Ok(())
    }
}

/// A stream built by `builder` whose messages go to the returned [`Collected`].
pub fn stream(builder: RecordingStreamBuilder) -> RecordingStreamResult<(RecordingStream, Collected)> {
    let collected = Collected::default();
    let rec = builder.set_sinks(vec![Box::new(collected.clone()) as Box<dyn LogSink>])?;
    Ok((rec, collected))
}
