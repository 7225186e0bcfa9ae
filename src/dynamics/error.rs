//! Why a step fails, and which failures a shorter step cures.

use std::fmt;

use crate::friction::{ContactState, FrictionError};
use crate::linalg::sparse::FactorError;

/// Why a step failed.
#[derive(Debug, Clone, PartialEq)]
pub enum StepError {
    /// The friction update of one contact point failed.
    Friction { point: usize, state: ContactState, error: FrictionError },
    /// Newton's method did not converge.
    NotConverged { iterations: usize, correction: f64 },
    /// The linear solve failed.
    Factor(FactorError),
    /// A non-finite value appeared.
    NonFinite,
    /// The integrator created more energy than its tolerance allows (the step is too coarse
    /// for the dynamics): `created` as a share of the work put in.
    EnergyCreated { share: f64, tolerance: f64 },
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::Friction { point, state, error } => write!(
                f,
                "contact point {point} (f_t = {} Pa, f_n = {} Pa, 1/R* = {}): {error}",
                state.traction_t, state.traction_n, state.structure
            ),
            StepError::NotConverged { iterations, correction } => write!(
                f,
                "Newton's method did not converge in {iterations} iterations (last displacement correction {correction:e} m)"
            ),
            StepError::Factor(e) => write!(f, "{e}"),
            StepError::NonFinite => write!(f, "a non-finite value appeared in the solution"),
            StepError::EnergyCreated { share, tolerance } => write!(
                f,
                "the energy balance does not close: the integrator has created energy equal to {:.3}% of the \
                 work put in (allowed: {:.3}%), so the time step is too coarse for this case's dynamics",
                100.0 * share,
                100.0 * tolerance
            ),
        }
    }
}

impl std::error::Error for StepError {}

/// How many times a failing step may be halved (down to 1/1024 of it).
pub const MAX_HALVINGS: u32 = 10;

impl StepError {
    /// Whether a shorter step may succeed where this one failed.
    pub(crate) fn cured_by_shorter_steps(&self) -> bool {
        match self {
            StepError::NotConverged { .. } | StepError::Factor(FactorError::NotPositiveDefinite) => true,
            StepError::Friction { error, .. } => error.cured_by_shorter_steps(),
            _ => false,
        }
    }
}
