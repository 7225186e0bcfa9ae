//! One interface for every time integrator of the equation of motion (14): Wilson's θ method
//! (fixed, or adaptive by step doubling), central differences, and the Runge–Kutta methods on
//! the rate form. An integrator advances a [`System`] and keeps its own memory between steps;
//! [`super::method`] says which one a case gets.

use crate::dynamics::control::AdaptiveError;
use crate::dynamics::system::System;

/// A time integrator.
pub trait Integrator: Send {
    /// Advances `system` by one step of at most `limit` (s) and returns the step taken: all of
    /// `limit` for the fixed-step methods; what the error control allows for the adaptive
    /// ones, shortened to end just past the first located slip-threshold crossing.
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError>;

    /// What the method has counted so far.
    fn statistics(&self) -> Statistics {
        Statistics::default()
    }
}

/// What an integrator has counted over a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Adaptive steps accepted.
    pub accepted: u64,
    /// Adaptive attempts rejected by the error estimate or by a failed solve.
    pub rejected: u64,
    /// Newton iterations of an implicit Runge–Kutta method's stages: one right-hand side and
    /// one solve with the factored operator each.
    pub newton_iterations: u64,
    /// Factorizations of its operator (linearizations).
    pub factorizations: u64,
}
