//! What the run loop sees of a scene ([`Scene`]), and how a failure inside one is reported
//! ([`RunError`]): the step, the time, and the segment involved.

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::dynamics::{IntegratorMemory, Statistics, StepError, SystemMemory};
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
    /// The longest step the next [`Self::advance`] with `limit` may take
    /// ([`crate::dynamics::Integrator::longest_next_step`]): `limit` with fixed steps.
    fn longest_next_step(&self, limit: f64) -> f64 {
        limit
    }
    /// What the integrator has counted so far (nothing for scenes without dynamics).
    fn statistics(&self) -> Statistics {
        Statistics::default()
    }
    /// Describes the current state; `dt` is the step just taken.
    fn frame(&self, needs: Needs, dt: f64) -> Frame;
    /// Everything needed to continue from the current state, for a checkpoint.
    fn memory(&self) -> SceneMemory;
    /// Continues from a [`Self::memory`] of a scene built from the same case; refuses one that
    /// does not fit (another scene, another mesh).
    fn restore(&mut self, memory: SceneMemory) -> Result<(), String>;
}

/// A scene's state as data ([`Scene::memory`]).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum SceneMemory {
    /// A body stepped by an integrator: the system and the integrator's memory.
    Dynamic { system: Box<SystemMemory>, integrator: Box<IntegratorMemory> },
    /// The point scene: its contact state, time, step, last plastic increment and the slip
    /// it has been driven through.
    Point { state: ContactState, time: f64, step: u64, last_increment: f64, relative_slip: f64 },
}

impl SceneMemory {
    /// Simulated time (s) and steps taken.
    pub fn time_and_step(&self) -> (f64, u64) {
        match self {
            SceneMemory::Dynamic { system, .. } => (system.state.time, system.state.step),
            SceneMemory::Point { time, step, .. } => (*time, *step),
        }
    }
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
