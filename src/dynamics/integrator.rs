//! One interface for every time integrator of the equation of motion (14): Wilson's θ method
//! (fixed, or adaptive by step doubling), central differences, and the Runge–Kutta methods on
//! the rate form. An integrator advances a [`System`] and keeps its own memory between steps;
//! [`super::method`] says which one a case gets.

use crate::dynamics::control::AdaptiveError;
use crate::dynamics::memory::IntegratorMemory;
pub use crate::dynamics::statistics::Statistics;
use crate::dynamics::system::System;

/// A time integrator.
pub trait Integrator: Send {
    /// Advances `system` by one step of at most `limit` (s) and returns the step taken: all of
    /// `limit` for the fixed-step methods; what the error control allows for the adaptive
    /// ones, shortened to end just past the first located slip-threshold crossing.
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError>;

    /// What the method remembers between steps, for a checkpoint.
    fn memory(&self) -> IntegratorMemory;

    /// Takes back a [`Self::memory`] of the same method on `system` (already restored), so
    /// that the next step is the one the saved run would have taken.
    fn restore(&mut self, system: &System, memory: IntegratorMemory) -> Result<(), String>;

    /// The longest step the next [`Self::advance`] with `limit` may take: `limit` for the
    /// fixed-step methods, the step the error control will try first for the adaptive ones
    /// (a rejection or a located crossing only shortens it). The run loop asks, so that it
    /// keeps the state before a step that may end past `t_end` (`crate::run`).
    fn longest_next_step(&self, limit: f64) -> f64 {
        limit
    }

    /// What the method has counted so far.
    fn statistics(&self) -> Statistics {
        Statistics::default()
    }
}
