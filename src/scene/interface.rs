//! What the run loop sees of a scene ([`Scene`]), and how a failure inside one is reported
//! ([`RunError`]): the step, the time, and the segment involved.

use std::fmt;

use crate::dynamics::{Statistics, StepError};
use crate::frame::{Frame, Layout, Needs};
use crate::friction::{ContactState, FrictionError};

/// A failure while running: the step it happened in, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct RunError {
    pub step: u64,
    pub time: f64,
    /// Segment of the contact point involved, if any.
    pub segment: Option<usize>,
    pub message: String,
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "step {} (t = {} s)", self.step, self.time)?;
        if let Some(s) = self.segment {
            write!(f, ", segment {s}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for RunError {}

/// A model that can be advanced and observed.
pub trait Scene: Send {
    fn layout(&self) -> &Layout;
    /// Current time (s).
    fn time(&self) -> f64;
    /// Advances by one step of at most `limit` (s) and returns the step taken: all of `limit`
    /// with fixed steps; what the integrator's error control allows with adaptive ones.
    fn advance(&mut self, limit: f64) -> Result<f64, RunError>;
    /// What the integrator has counted so far (nothing for scenes without dynamics).
    fn statistics(&self) -> Statistics {
        Statistics::default()
    }
    /// Describes the current state; `dt` is the step just taken.
    fn frame(&self, needs: Needs, dt: f64) -> Frame;
}

/// Turns a dynamic step failure into a [`RunError`] for the scene's segment numbering.
pub fn step_error(error: StepError, step: u64, time: f64, segment_of_point: impl Fn(usize) -> usize) -> RunError {
    let segment = match &error {
        StepError::Friction { point, .. } => Some(segment_of_point(*point)),
        _ => None,
    };
    let mut message = error.to_string();
    if matches!(error, StepError::EnergyCreated { .. }) {
        message.push_str(": use a smaller time.dt (or raise time.energy_tolerance)");
    }
    RunError { step, time, segment, message }
}

/// Turns a friction failure of the single point of a point scene into a [`RunError`].
pub fn friction_error(error: FrictionError, state: &ContactState, step: u64, time: f64) -> RunError {
    RunError {
        step,
        time,
        segment: Some(0),
        message: format!(
            "f_t = {} Pa, f_n = {} Pa, 1/R* = {}: {error}",
            state.traction_t, state.traction_n, state.structure
        ),
    }
}
