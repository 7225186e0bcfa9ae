//! Sinks observe a run through one small interface: they say what they need in each frame,
//! receive the layout once, every frame, and a final call that must leave their output valid
//! whether the run completed, failed or was interrupted.

pub mod blueprint;
pub mod cadence;
pub mod catalog;
pub mod geometry;
pub mod mcap;
pub mod properties;
pub mod rerun;
pub mod series;
pub mod slip_front;
pub mod spacetime;
pub mod viewer;

use std::fmt;

use crate::catalog::events::Catalog;
use crate::frame::{Ending, Frame, Layout, Needs};

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
    /// Called once at the end, however the run ended, with the last frame recorded (the last
    /// good step; a decimating sink records it if it skipped it) and the catalog of every slip
    /// event up to it.
    fn finish(&mut self, ending: Ending, last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError>;
}
