//! The recording's `.rrd` file, written by slipfront's own log sink instead of Rerun's
//! `FileSink`.
//!
//! Rerun 0.36's `FileSink` writes on a thread of its own, which ends at its first write error
//! and reports the error only to its logger. A flush sent to it just before it ends is never
//! answered: the recording stream's forwarding thread then waits for ever (it flushes its
//! sink with no time limit), our flush times out, and the stream's shutdown waits on that
//! same thread. On a full disk the run hung, or stopped with "File-writer thread shut down
//! prematurely" instead of the operating system's error. This sink encodes each message on
//! the thread that sends it (the recording stream's forwarding thread), keeps the first error
//! and answers every later flush with it at once, so the run stops within one flush cadence
//! naming the OS error, and shutdown never waits on a writer.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

use rerun::external::re_build_info::CrateVersion;
use rerun::external::re_log_encoding::{Encoder, EncodingOptions};
use rerun::log::LogMsg;
use rerun::sink::{LogSink, SinkFlushError};

/// Writes a recording to a file; see the module docs.
pub struct RecordingFile {
    path: PathBuf,
    state: Mutex<Writing>,
    failure: FileFailure,
}

/// The first write error of a [`RecordingFile`], shared with whoever must stop on it.
pub type FileFailure = Arc<OnceLock<String>>;

/// The encoder while it writes, and the first error once one happened (after which nothing
/// more is written: the file ends at its last whole write).
struct Writing {
    encoder: Option<Encoder<BufWriter<File>>>,
    error: Option<String>,
}

impl RecordingFile {
    /// Creates (or truncates) the file at `path` and writes the stream's header.
    pub fn create(path: &Path) -> Result<Self, String> {
        let error = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
        let file = File::create(path).map_err(|e| error(&e))?;
        let encoder =
            Encoder::new_eager(CrateVersion::LOCAL, EncodingOptions::PROTOBUF_COMPRESSED, BufWriter::new(file))
                .map_err(|e| error(&e))?;
        let state = Mutex::new(Writing { encoder: Some(encoder), error: None });
        Ok(Self { path: path.to_path_buf(), state, failure: FileFailure::default() })
    }

    /// Where the first write error will be, once there is one.
    pub fn failure(&self) -> FileFailure {
        Arc::clone(&self.failure)
    }

    /// Runs `write` on the encoder unless an error already stopped it; its error stops it.
    fn with_encoder(&self, write: impl FnOnce(&mut Encoder<BufWriter<File>>) -> Result<(), String>) -> Option<String> {
        let mut state = self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(error) = &state.error {
            return Some(error.clone());
        }
        let encoder = state.encoder.as_mut()?;
        let Err(e) = write(encoder) else { return None };
        let error = format!("cannot write {}: {e}", self.path.display());
        // Neither the footer nor the buffered bytes: the file keeps what reached it.
        if let Some(encoder) = state.encoder.take()
            && let Ok(buffered) = encoder.into_inner()
        {
            drop(buffered.into_parts());
        }
        state.error = Some(error.clone());
        let _ = self.failure.set(error.clone());
        Some(error)
    }
}

impl LogSink for RecordingFile {
    fn send(&self, msg: LogMsg) {
        self.with_encoder(|encoder| encoder.append(&msg).map(|_| ()).map_err(|e| e.to_string()));
    }

    /// Hands what is buffered to the file; the first write error, this one's or an earlier
    /// send's, is the answer from then on.
    fn flush_blocking(&self, _timeout: Duration) -> Result<(), SinkFlushError> {
        match self.with_encoder(|encoder| encoder.flush_blocking().map_err(|e| e.to_string())) {
            Some(error) => Err(SinkFlushError::failed(error)),
            None => Ok(()),
        }
    }
}
