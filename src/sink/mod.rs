//! Sinks observe a run through one small interface: they say what they need in each frame,
//! receive the layout once, every frame, and a final call that must leave their output valid
//! whether the run completed, failed or was interrupted.

pub mod blueprint;
pub mod cadence;
pub mod catalog;
pub mod collected;
pub mod geometry;
pub mod heap;
pub mod mcap;
pub mod memory;
pub mod open_at;
pub mod properties;
pub mod recording_file;
pub mod rerun;
pub mod series;
pub mod slip_front;
pub mod spacetime;
pub mod viewer;

use std::fmt;

/// Whether this is a measuring build whose recording stops at slipfront's own buffers: Rerun's
/// stream is off and each hand-over drops the rows instead of sending them (the Cargo feature
/// `measure-without-rerun`; [docs/performance.md](../../docs/performance.md)).
pub const WITHOUT_RERUN: bool = cfg!(feature = "measure-without-rerun");
use std::path::PathBuf;

use crate::catalog::events::Catalog;
use crate::frame::{Ending, Frame, Layout, Needs};
pub use crate::sink::memory::SinkMemory;

/// A sink could not write.
#[derive(Debug, Clone, PartialEq)]
pub struct SinkError(pub String);

impl fmt::Display for SinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

impl std::error::Error for SinkError {}

/// An observer of a run.
pub trait Sink {
    /// What this sink reads from frames beyond the always-present segment traction, slip and
    /// slip rate; asked after [`Sink::begin`], so it may depend on the layout.
    fn needs(&self) -> Needs {
        Needs::default()
    }
    /// Called once, before the initial frame.
    fn begin(&mut self, layout: &Layout) -> Result<(), SinkError>;
    /// Called for the initial frame and after every step.
    fn record(&mut self, frame: &Frame) -> Result<(), SinkError>;
    /// Whether [`Sink::record`] writes `frame`, asked of a frame that holds what every frame
    /// holds (step, time, the segments) but not yet the parts of [`Sink::needs`]: the run loop
    /// computes those only for frames some sink writes. A decimating sink answers from its
    /// decimator, without remembering anything; `true` by default.
    fn writes(&self, _frame: &Frame) -> bool {
        true
    }
    /// Hands everything buffered to the disk and returns what the sink must remember to
    /// continue after a checkpoint taken now ([`SinkMemory`]).
    fn checkpoint(&mut self) -> Result<SinkMemory, SinkError> {
        Ok(SinkMemory::Nothing)
    }
    /// Continues from a checkpoint: called after [`Sink::begin`], in place of the initial
    /// frame, with what every sink's [`Sink::checkpoint`] returned (each takes its own kind).
    fn resume(&mut self, _saved: &[SinkMemory]) -> Result<(), SinkError> {
        Ok(())
    }
    /// Called once at the end, however the run ended, with the last frame recorded (the last
    /// good step; a decimating sink records it if it skipped it) and the catalog of every slip
    /// event up to it.
    fn finish(&mut self, ending: Ending, last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError>;
}

/// Where a resumed run's file sink finds the file it continues (`previous`), and where it
/// writes the continued one (`writing`, beside the file it will replace): the part of
/// `previous` up to the checkpoint first, then the continued run. `slipfront resume` renames it
/// over the file it replaces only once the run has finished it, so a resume that is refused,
/// fails or is killed leaves the earlier run's files as they were.
#[derive(Debug, Clone, PartialEq)]
pub struct Continuation {
    pub previous: PathBuf,
    pub writing: PathBuf,
}

/// Forces what was written to `path` (through any handle) onto the disk.
pub fn sync(path: &std::path::Path) -> Result<(), SinkError> {
    std::fs::File::open(path)
        .and_then(|file| file.sync_data())
        .map_err(|e| SinkError(format!("cannot sync {}: {e}", path.display())))
}
